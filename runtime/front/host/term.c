/* Interactive terminal front end: what the viewer shows and how it moves (see term.h); the
 * terminal itself (raw keys, signals, the output buffer) is termio.h's.
 *
 * Each terminal cell shows two pixels stacked vertically: U+2580 '▀' in the upper pixel's colour on
 * the lower pixel's colour, both as 24-bit SGR escapes. A frame is composed in termio's buffer and
 * sent with one write, so the terminal never shows half a frame and the heap is never touched.
 *
 * Rendering follows the source paper's viewer: while the view moves (a key held, or the automatic
 * turn before the first key) the model is drawn coarser, at twice the level-of-detail error bound
 * (one level coarser than the viewer's; with the bound off, one octree level coarser than full
 * depth), with one-pixel holes closed; once it stops, one frame at the viewer's bound is drawn,
 * given up as soon as a key arrives (the renderer's abort poll), and then the viewer sleeps until
 * the next key. Rotation speed is measured
 * in time, not frames, so it is the same on a slow machine or a slow terminal.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <modelc/modelc.h>

#include "../common/rgb.h"
#include "scene.h"
#include "term.h"
#include "termio.h"


#define TURN_DEGREES_PER_S 90.0
/* A held key auto-repeats every 30-50 ms: it counts as held until no event came for HOLD_GAP_S. The
 * first repeat only comes after 250-500 ms, so a fresh press counts as held for FIRST_REPEAT_S. */
#define HOLD_GAP_S 0.150
#define FIRST_REPEAT_S 0.500
/* Moving frames are paced: a terminal cannot show more, and faster output only queues up. */
#define FRAME_INTERVAL_S (1.0 / 30)
#define ZOOM_STEP 1.1
#define ZOOM_MIN (1.0 / 64)
#define ZOOM_MAX 64.0

/* Worst case per cell: "ESC[38;2;255;255;255;48;2;255;255;255m" (36 bytes) and '▀' (3 bytes). */
#define CELL_BYTES_MAX 40
#define ROW_BYTES_MAX 16     /* cursor position at each row start */
#define STATUS_BYTES_MAX 512

enum { KEY_LEFT = MC_TIO_LEFT, KEY_RIGHT = MC_TIO_RIGHT, KEY_UP = MC_TIO_UP, KEY_DOWN = MC_TIO_DOWN, KEY_COUNT = 4 };

/* One arrow key's press: held from `press` until max(last + HOLD_GAP_S, press + FIRST_REPEAT_S). */
typedef struct key_hold {
    double press, last;
} key_hold;

/* Where the frame goes on the terminal. */
typedef struct layout {
    int cols, rows;     /* terminal size in cells */
    uint16_t w, h;      /* frame size in pixels */
    int x0, y0;         /* top-left cell of the frame, 0-based */
} layout;

typedef struct term_state {
    const mc_app *app;
    const mc_octree *octree;
    mc_host_scene *scene;
    mc_view start;
    double yaw, pitch;  /* angle units, fractional so slow frames lose nothing */
    double zoom;
    int auto_turn;      /* until the first key */
    int fine_needed;    /* the screen does not show the current view at the fine level */
    uint16_t fine_error;   /* the viewer's level-of-detail bound (mc_octree_options.max_error) */
    int quit;
    key_hold keys[KEY_COUNT];
    layout lay;
    /* shown in the status line */
    unsigned drawn_depth;
    double frame_ms;
    uint32_t points;    /* points or faces drawn */
    double now;         /* when the keys being read arrived */
    mc_host_stream *stream;   /* or NULL: the points come from the model */
} term_state;


/* ---- small helpers ------------------------------------------------------------------------------ */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }


/* ---- layout ----------------------------------------------------------------------------------- */

/* Frame = the terminal minus the status line, two pixels per row, capped to the baked buffers and to
 * what the output buffer holds; centred if capped. */
static layout compute_layout(const mc_app *app)
{
    layout L;
    mc_tio_size(&L.cols, &L.rows);
    long w = L.cols < app->max_width ? L.cols : app->max_width;
    long h = (L.rows - 1) * 2L < app->max_height ? (L.rows - 1) * 2L : app->max_height;
    if (w > MC_TARGET_MAX) w = MC_TARGET_MAX;
    if (h > MC_TARGET_MAX) h = MC_TARGET_MAX;
    if (h < 0) h = 0;
    while (h > 0 && (size_t)((h + 1) / 2) * ((size_t)w * CELL_BYTES_MAX + ROW_BYTES_MAX) >
                        MC_TERM_OUT_BYTES - STATUS_BYTES_MAX)
        h -= 2;
    if (h < 0) h = 0;
    L.w = (uint16_t)w;
    L.h = (uint16_t)h;
    L.x0 = (L.cols - (int)w) / 2;
    L.y0 = (L.rows - 1 - (int)(h + 1) / 2) / 2;
    return L;
}

/* Clear in the background colour (terminals erase with the current background), so the margins
 * around a capped frame match the frame's own background. */
static void clear_screen(void)
{
    char buf[64];
    int n = snprintf(buf, sizeof buf, "\x1b[0m\x1b[48;2;%d;%d;%dm\x1b[2J\x1b[0m", mc_front_background[0],
                     mc_front_background[1], mc_front_background[2]);
    mc_tio_write(buf, (size_t)n);
}

/* ---- frame output ------------------------------------------------------------------------------ */

/* 0xRRGGBB of pixel (x, y); rows below the frame (an odd height's last cell) are background. */
static uint32_t pixel_rgb(const mc_target *t, const uint8_t *palette, int x, int y)
{
    uint8_t c[3] = {mc_front_background[0], mc_front_background[1], mc_front_background[2]};
    if (y < t->height) mc_front_rgb(t, palette, (uint32_t)y * t->width + (uint32_t)x, 1, c);
    return ((uint32_t)c[0] << 16) | ((uint32_t)c[1] << 8) | c[2];
}

/* One cell. fg/bg hold the terminal's current colours (UINT32_MAX = unknown): an escape is sent only
 * for a colour that changes, and a cell of one colour that is already the background is a space. */
static void put_cell(uint32_t top, uint32_t bottom, uint32_t *fg, uint32_t *bg)
{
    if (top == bottom && top == *bg) {
        mc_tio_put_str(" ");
        return;
    }
    int set_fg = top != *fg, set_bg = bottom != *bg;
    if (set_fg || set_bg) {
        mc_tio_put_str("\x1b[");
        if (set_fg) {
            mc_tio_put_str("38;2;");
            mc_tio_put_rgb(top);
        }
        if (set_bg) {
            mc_tio_put_str(set_fg ? ";48;2;" : "48;2;");
            mc_tio_put_rgb(bottom);
        }
        mc_tio_put_str("m");
        *fg = top;
        *bg = bottom;
    }
    mc_tio_put_str("\xe2\x96\x80");   /* U+2580 UPPER HALF BLOCK */
}

static void put_frame(const mc_target *t, const uint8_t *palette, const layout *L)
{
    uint32_t fg = UINT32_MAX, bg = UINT32_MAX;   /* the status line reset the colours */
    for (int y = 0; y < t->height; y += 2) {
        mc_tio_put_move(L->y0 + y / 2, L->x0);
        for (int x = 0; x < t->width; x++)
            put_cell(pixel_rgb(t, palette, x, y), pixel_rgb(t, palette, x, y + 1), &fg, &bg);
    }
}

/* Last row, default colours, cut to the terminal width so it never wraps or scrolls. */
static void put_status(const term_state *s)
{
    char line[STATUS_BYTES_MAX - 32];
    const mc_host_scene *sc = s->scene;
    char note[160];
    const char *keys = mc_host_scene_has_mesh(sc) ? "q quits, arrows turn, +/- zoom, m mode, [ ] detail, r resets"
                                                  : "q quits, arrows turn, +/- zoom, r resets";
    if (s->stream) {
        mc_host_stream_status(s->stream, note, sizeof note);
        keys = note;
    }
    int n = sc->mode == MC_HOST_POINTS
                ? snprintf(line, sizeof line, " %s | points | depth %u/%u at %ux%u | %.1f ms | %lu points | zoom %.2f | %s",
                           s->app->model->name, s->drawn_depth, (unsigned)s->octree->depth, (unsigned)s->lay.w,
                           (unsigned)s->lay.h, s->frame_ms, (unsigned long)s->points, s->zoom, keys)
                : snprintf(line, sizeof line, " %s | %s | %u/%u vertices | %.1f ms | %lu faces | zoom %.2f | %s",
                           s->app->model->name, mc_host_mode_name(sc->mode), sc->lod.pm ? (unsigned)sc->lod.level : 0u,
                           sc->lod.pm ? (unsigned)sc->lod.pm->vertices : 0u, s->frame_ms, (unsigned long)s->points,
                           s->zoom, keys);
    if (n < 0) n = 0;
    if (n > (int)sizeof line - 1) n = (int)sizeof line - 1;
    if (n > s->lay.cols) n = s->lay.cols;
    mc_tio_put_str("\x1b[0m");
    mc_tio_put_move(s->lay.rows - 1, 0);
    mc_tio_put(line, (size_t)n);
    mc_tio_put_str("\x1b[K");
}

/* ---- rendering ----------------------------------------------------------------------------------- */

static mc_view current_view(const term_state *s)
{
    mc_view v = s->start;
    v.yaw = (int32_t)lround(fmod(s->yaw, MC_ANGLE_FULL));
    v.pitch = (int32_t)lround(fmod(s->pitch, MC_ANGLE_FULL));
    v.zoom = (int32_t)lround(s->zoom * MC_ZOOM_ONE);
    return v;
}

/* The renderer's abort poll (about 500 times a frame): give up the fine frame as soon as a key, a
 * resize or a quit signal is waiting, so it is handled at once instead of after the frame. */
static int input_waiting(void *user)
{
    (void)user;
    return mc_tio_input_waiting();
}

/* Renders at `depth` and shows the frame. Returns 1 if shown, 0 if given up (abort), -1 if the
 * terminal is gone. */
static int draw(term_state *s, unsigned depth, mc_abort_fn abort)
{
    const mc_app *app = s->app;
    mc_target t = {app->color, app->depth, s->lay.w, s->lay.h};
    mc_view v = current_view(s);
    uint32_t drawn = 0;
    double t0 = now_s();
    if (t.width > 0 && t.height > 0 && mc_host_scene_draw(s->scene, &v, depth, abort, &t, &drawn) == 1) return 0;
    s->frame_ms = (now_s() - t0) * 1e3;
    s->drawn_depth = s->scene->mode == MC_HOST_POINTS ? s->scene->drawn_depth : depth;
    s->points = drawn;
    mc_tio_begin();
    put_frame(&t, mc_host_scene_palette(s->scene), &s->lay);
    put_status(s);
    return mc_tio_flush() == 0 ? 1 : -1;
}

/* ---- input -------------------------------------------------------------------------------------- */

static double hold_end(const key_hold *k)
{
    double a = k->last + HOLD_GAP_S, b = k->press + FIRST_REPEAT_S;
    return a > b ? a : b;
}

static void press_arrow(void *user, int key)
{
    term_state *s = user;
    const double now = s->now;
    key_hold *k = &s->keys[key];
    if (now >= hold_end(k)) k->press = now;   /* a new press, not an auto-repeat */
    k->last = now;
}

static void release_all(term_state *s)
{
    for (int i = 0; i < KEY_COUNT; i++) s->keys[i].press = s->keys[i].last = -1e9;
}

static void reset_view(term_state *s)
{
    s->yaw = s->start.yaw;
    s->pitch = s->start.pitch;
    s->zoom = clampd(s->start.zoom / (double)MC_ZOOM_ONE, ZOOM_MIN, ZOOM_MAX);
    release_all(s);
}

static void handle_char(void *user, unsigned char c)
{
    term_state *s = user;
    switch (c) {
    case 'q': case 'Q': case 3: s->quit = 1; break;   /* 3 = Ctrl-C */
    case '+': case '=': s->zoom = clampd(s->zoom * ZOOM_STEP, ZOOM_MIN, ZOOM_MAX); break;
    case '-': case '_': s->zoom = clampd(s->zoom / ZOOM_STEP, ZOOM_MIN, ZOOM_MAX); break;
    case 'r': case 'R': reset_view(s); break;
    case 'm': case 'M':   /* the next mode the model has */
        if (mc_host_scene_has_mesh(s->scene)) s->scene->mode = (mc_host_mode)((s->scene->mode + 1) % 4);
        break;
    case '[': case ']':   /* half or twice the splits above the base mesh */
        if (mc_host_scene_has_mesh(s->scene) && s->scene->lod.pm) {
            const mc_pmesh_lod *lod = &s->scene->lod;
            uint32_t base = lod->pm->base_vertices, splits = lod->level - base;
            splits = c == '[' ? splits / 2 : splits ? splits * 2 : 1;
            mc_host_scene_set_level(s->scene, splits > lod->pm->vertices - base ? lod->pm->vertices : base + splits);
        }
        break;
    default: break;
    }
}


/* Applies every key waiting; the first key stops the automatic turn. Returns -1 at end of input. */
static int read_keys(term_state *s, double now)
{
    s->now = now;
    int n = mc_tio_read_keys(handle_char, press_arrow, s);
    if (n > 0) {
        s->auto_turn = 0;
        s->fine_needed = 1;
    }
    return n < 0 ? -1 : 0;
}

/* Sleeps out the rest of a moving frame's interval; a frame that took longer does not sleep. */
static void pace(double frame_start)
{
    double left = FRAME_INTERVAL_S - (now_s() - frame_start);
    mc_tio_wait(left > 0 ? (int)ceil(left * 1e3) : 0);
}

/* ---- motion ------------------------------------------------------------------------------------- */

/* Seconds of [from, to] during which key k was held. */
static double held_time(const key_hold *k, double from, double to)
{
    double a = k->press > from ? k->press : from;
    double b = hold_end(k) < to ? hold_end(k) : to;
    return b > a ? b - a : 0;
}

static int moving(const term_state *s, double now)
{
    if (s->auto_turn) return 1;
    for (int i = 0; i < KEY_COUNT; i++)
        if (now < hold_end(&s->keys[i])) return 1;
    return 0;
}

/* Turns the view for the time between two frames: angle = speed x time held, whatever the frame
 * rate. Right turns the model's front to the right (+yaw), Up turns it upwards (-pitch). */
static void advance(term_state *s, double from, double to)
{
    double speed = TURN_DEGREES_PER_S * MC_ANGLE_FULL / 360.0;   /* angle units per second */
    const key_hold *k = s->keys;
    if (s->auto_turn) s->yaw += speed * (to - from);
    s->yaw += speed * (held_time(&k[KEY_RIGHT], from, to) - held_time(&k[KEY_LEFT], from, to));
    s->pitch += speed * (held_time(&k[KEY_DOWN], from, to) - held_time(&k[KEY_UP], from, to));
    s->yaw = fmod(s->yaw, MC_ANGLE_FULL);
    s->pitch = fmod(s->pitch, MC_ANGLE_FULL);
}

/* ---- main loop ---------------------------------------------------------------------------------- */

static void resize(term_state *s)
{
    s->lay = compute_layout(s->app);
    clear_screen();
    s->fine_needed = 1;
}

/* One step: moving -> a paced coarse frame; stopped -> one abortable fine frame, then sleep.
 * Returns -1 when the loop should end. */
static int step(term_state *s, double *prev)
{
    if (s->stream && !s->stream->done) {
        if (mc_host_stream_pump(s->stream, 0)) {
            s->octree = s->scene->octree = mc_host_stream_octree(s->stream);
            mc_host_scene_stream_mesh(s->scene, mc_host_stream_pmesh(s->stream), s->stream->mesh_level);
            s->fine_needed = 1;
        }
        if (s->stream->done) s->fine_needed = 1;   /* the status line changes */
    }
    if (!s->octree) {   /* a stream with no drawable octree yet (the mesh modes wait for it too) */
        s->drawn_depth = 0;
        mc_tio_wait(s->stream->done ? -1 : 20);
        return read_keys(s, now_s()) < 0 || s->quit ? -1 : 0;
    }
    const unsigned full = s->octree->depth;
    const unsigned coarse = s->fine_error ? full : full > 1 ? full - 1u : 1u;
    const uint32_t coarse_error = 2u * s->fine_error;
    double now = now_s();
    if (read_keys(s, now) < 0 || s->quit) return -1;
    advance(s, *prev, now);
    *prev = now;
    if (moving(s, now)) {
        s->scene->opt.max_error = (uint16_t)(coarse_error < 0xFFFFu ? coarse_error : 0xFFFFu);
        if (draw(s, coarse, NULL) < 0) return -1;
        s->fine_needed = 1;
        pace(now);
    } else if (s->fine_needed) {
        s->scene->opt.max_error = s->fine_error;
        int r = draw(s, full, input_waiting);
        if (r < 0) return -1;
        if (r > 0) s->fine_needed = 0;
    } else {
        mc_tio_wait(s->stream && !s->stream->done ? 20 : -1);
    }
    return 0;
}

int mc_host_interactive(mc_host_scene *scene, mc_view start, mc_host_stream *stream)
{
    const mc_app *app = scene->app;
    if (mc_tio_enter() != 0) {
        fprintf(stderr, "%s-view: interactive mode needs a terminal on stdin: %s\n", app->model->name,
                strerror(errno));
        return 2;
    }
    term_state s;
    memset(&s, 0, sizeof s);
    s.app = app;
    s.octree = scene->octree;
    s.scene = scene;
    s.stream = stream;
    s.fine_error = scene->opt.max_error;
    s.start = start;
    reset_view(&s);
    s.auto_turn = 1;
    resize(&s);

    double prev = now_s();
    while (!mc_tio_quit_signal()) {
        if (mc_tio_resized()) resize(&s);
        if (step(&s, &prev) < 0) break;
    }
    mc_tio_leave();
    const int sig = mc_tio_quit_signal();
    return sig ? 128 + sig : 0;   /* the shell's convention for a signal */
}
