/* Interactive terminal front end (see term.h).
 *
 * Each terminal cell shows two pixels stacked vertically: U+2580 '▀' in the upper pixel's colour on
 * the lower pixel's colour, both as 24-bit SGR escapes. A frame is composed in one static buffer and
 * sent with one write(), so the terminal never shows half a frame and the heap is never touched.
 *
 * Rendering follows the source paper's viewer: while the view moves (a key held, or the automatic
 * turn before the first key) the model is drawn one octree level coarser, with one-pixel holes
 * closed; once it stops, one frame at full depth is drawn, given up as soon as a key arrives (the
 * renderer's abort poll), and then the viewer sleeps in poll() until the next key. Rotation speed
 * is measured in time, not frames, so it is the same on a slow machine or a slow terminal.
 */
#define _DEFAULT_SOURCE
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <modelc/modelc.h>

#include "image.h"
#include "term.h"

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
/* MC_TERM_OUT_BYTES: the frame buffer. 8 MiB holds 200 000 cells, more than a 640x480 model on a
 * 640-column terminal; larger terminals get a shorter frame. Untouched pages cost no RAM. */
#ifndef MC_TERM_OUT_BYTES
#define MC_TERM_OUT_BYTES (8u << 20)
#endif

enum { KEY_LEFT, KEY_RIGHT, KEY_UP, KEY_DOWN, KEY_COUNT };

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
    mc_view start;
    double yaw, pitch;  /* angle units, fractional so slow frames lose nothing */
    double zoom;
    int auto_turn;      /* until the first key */
    int fine_needed;    /* the screen does not show the current view at full depth */
    int quit;
    key_hold keys[KEY_COUNT];
    layout lay;
    /* shown in the status line */
    unsigned drawn_depth;
    double frame_ms;
    uint32_t points;
} term_state;

static volatile sig_atomic_t got_quit, got_winch;
static struct termios saved_termios;
static char out[MC_TERM_OUT_BYTES];
static size_t out_len;

/* ---- small helpers ------------------------------------------------------------------------------ */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

/* Write everything, retrying after signals: a frame cut in the middle of an escape would garble the
 * screen. Returns -1 only when the terminal is gone. */
static int write_all(const char *p, size_t n)
{
    while (n > 0) {
        ssize_t k = write(STDOUT_FILENO, p, n);
        if (k < 0) {
            if (errno == EINTR || errno == EAGAIN) continue;
            return -1;
        }
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

static void put_bytes(const char *s, size_t n)
{
    if (n > sizeof out - out_len) n = sizeof out - out_len;   /* layout keeps this from happening */
    memcpy(out + out_len, s, n);
    out_len += n;
}

static void put_str(const char *s) { put_bytes(s, strlen(s)); }

/* snprintf would be called 150 000 times a frame; this is the hot path of the output. */
static void put_uint(unsigned v)
{
    char digits[10];
    int n = 0;
    do digits[n++] = (char)('0' + v % 10); while (v /= 10);
    while (n > 0 && out_len < sizeof out) out[out_len++] = digits[--n];
}

static void put_move(int row, int col)   /* 0-based */
{
    put_str("\x1b[");
    put_uint((unsigned)row + 1);
    put_str(";");
    put_uint((unsigned)col + 1);
    put_str("H");
}

static void put_rgb(uint32_t rgb)
{
    put_uint(rgb >> 16);
    put_str(";");
    put_uint((rgb >> 8) & 0xFF);
    put_str(";");
    put_uint(rgb & 0xFF);
}

/* ---- terminal setup ------------------------------------------------------------------------------ */

/* got_quit holds the signal number, so the exit status can say which one ended the viewer. */
static void on_signal(int sig)
{
    if (sig == SIGWINCH) got_winch = 1;
    else got_quit = sig;
}

/* No SA_RESTART: a signal must wake poll() so the main loop sees the flag at once. */
static void install_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGWINCH};
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) sigaction(sigs[i], &sa, NULL);
}

static void restore_signals(void)
{
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGHUP, SIG_DFL);
    signal(SIGWINCH, SIG_DFL);
}

/* Raw input: bytes as typed, no echo; Ctrl-C arrives as byte 3 (ISIG off) so it quits through the
 * same path as 'q', and Ctrl-S cannot freeze the output (IXON off). read() never blocks (VMIN=0). */
static int enter_raw_mode(void)
{
    if (tcgetattr(STDIN_FILENO, &saved_termios) != 0) return -1;
    struct termios raw = saved_termios;
    raw.c_iflag &= ~(tcflag_t)(IXON | ICRNL | INLCR | IGNCR | ISTRIP | BRKINT | PARMRK);
    raw.c_lflag &= ~(tcflag_t)(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    raw.c_cc[VMIN] = 0;
    raw.c_cc[VTIME] = 0;
    return tcsetattr(STDIN_FILENO, TCSANOW, &raw);
}

/* Alternate screen (the shell's screen comes back on exit), cursor hidden. */
static void enter_screen(void) { write_all("\x1b[?1049h\x1b[?25l", 14); }

static void leave_screen(void)
{
    static const char seq[] = "\x1b[0m\x1b[?25h\x1b[?1049l";
    write_all(seq, sizeof seq - 1);
    tcsetattr(STDIN_FILENO, TCSAFLUSH, &saved_termios);   /* FLUSH: unread keys do not reach the shell */
}

/* ---- layout ----------------------------------------------------------------------------------- */

/* Frame = the terminal minus the status line, two pixels per row, capped to the baked buffers and to
 * what the output buffer holds; centred if capped. */
static layout compute_layout(const mc_app *app)
{
    layout L;
    struct winsize ws;
    L.cols = 80;
    L.rows = 24;
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
        L.cols = ws.ws_col;
        L.rows = ws.ws_row;
    }
    long w = L.cols < app->max_width ? L.cols : app->max_width;
    long h = (L.rows - 1) * 2L < app->max_height ? (L.rows - 1) * 2L : app->max_height;
    if (w > MC_TARGET_MAX) w = MC_TARGET_MAX;
    if (h > MC_TARGET_MAX) h = MC_TARGET_MAX;
    if (h < 0) h = 0;
    while (h > 0 && (size_t)((h + 1) / 2) * ((size_t)w * CELL_BYTES_MAX + ROW_BYTES_MAX) >
                        sizeof out - STATUS_BYTES_MAX)
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
    int n = snprintf(buf, sizeof buf, "\x1b[0m\x1b[48;2;%d;%d;%dm\x1b[2J\x1b[0m", MC_HOST_BACKGROUND_R,
                     MC_HOST_BACKGROUND_G, MC_HOST_BACKGROUND_B);
    write_all(buf, (size_t)n);
}

/* ---- frame output ------------------------------------------------------------------------------ */

#define BACKGROUND_RGB \
    (((uint32_t)MC_HOST_BACKGROUND_R << 16) | ((uint32_t)MC_HOST_BACKGROUND_G << 8) | MC_HOST_BACKGROUND_B)

/* 0xRRGGBB of pixel (x, y); rows below the frame (an odd height's last cell) are background. */
static uint32_t pixel_rgb(const mc_target *t, const uint8_t *palette, int x, int y)
{
    if (y >= t->height) return BACKGROUND_RGB;
    size_t i = (size_t)y * t->width + (size_t)x;
    if (t->depth[i] == MC_DEPTH_EMPTY) return BACKGROUND_RGB;
    const uint8_t *c = palette + 3u * t->color[i];
    return ((uint32_t)c[0] << 16) | ((uint32_t)c[1] << 8) | c[2];
}

/* One cell. fg/bg hold the terminal's current colours (UINT32_MAX = unknown): an escape is sent only
 * for a colour that changes, and a cell of one colour that is already the background is a space. */
static void put_cell(uint32_t top, uint32_t bottom, uint32_t *fg, uint32_t *bg)
{
    if (top == bottom && top == *bg) {
        put_str(" ");
        return;
    }
    int set_fg = top != *fg, set_bg = bottom != *bg;
    if (set_fg || set_bg) {
        put_str("\x1b[");
        if (set_fg) {
            put_str("38;2;");
            put_rgb(top);
        }
        if (set_bg) {
            put_str(set_fg ? ";48;2;" : "48;2;");
            put_rgb(bottom);
        }
        put_str("m");
        *fg = top;
        *bg = bottom;
    }
    put_str("\xe2\x96\x80");   /* U+2580 UPPER HALF BLOCK */
}

static void put_frame(const mc_target *t, const uint8_t *palette, const layout *L)
{
    uint32_t fg = UINT32_MAX, bg = UINT32_MAX;   /* the status line reset the colours */
    for (int y = 0; y < t->height; y += 2) {
        put_move(L->y0 + y / 2, L->x0);
        for (int x = 0; x < t->width; x++)
            put_cell(pixel_rgb(t, palette, x, y), pixel_rgb(t, palette, x, y + 1), &fg, &bg);
    }
}

/* Last row, default colours, cut to the terminal width so it never wraps or scrolls. */
static void put_status(const term_state *s)
{
    char line[STATUS_BYTES_MAX - 32];
    int n = snprintf(line, sizeof line,
                     " %s | depth %u/%u | %.1f ms | %lu points | zoom %.2f | q quits, arrows turn, +/- zoom, r resets",
                     s->app->scene->name, s->drawn_depth, (unsigned)s->app->scene->depth, s->frame_ms,
                     (unsigned long)s->points, s->zoom);
    if (n < 0) n = 0;
    if (n > (int)sizeof line - 1) n = (int)sizeof line - 1;
    if (n > s->lay.cols) n = s->lay.cols;
    put_str("\x1b[0m");
    put_move(s->lay.rows - 1, 0);
    put_bytes(line, (size_t)n);
    put_str("\x1b[K");
}

/* ---- rendering ----------------------------------------------------------------------------------- */

mc_fill mc_host_fill = MC_FILL_DEFAULT;

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
    if (got_quit || got_winch) return 1;
    struct pollfd p = {STDIN_FILENO, POLLIN, 0};
    return poll(&p, 1, 0) > 0;
}

/* Renders at `depth` and shows the frame. Returns 1 if shown, 0 if given up (abort), -1 if the
 * terminal is gone. */
static int draw(term_state *s, unsigned depth, mc_abort_fn abort)
{
    const mc_app *app = s->app;
    mc_target t = {app->color, app->depth, s->lay.w, s->lay.h};
    mc_view v = current_view(s);
    mc_stats st = {0, 0, 0};
    double t0 = now_s();
    if (t.width > 0 && t.height > 0) {
        mc_clear(&t);
        mc_render(app->scene, &v, depth, &t, abort, NULL, &st);
        if (st.aborted) return 0;
        mc_finish(&t, mc_host_fill);
    }
    s->frame_ms = (now_s() - t0) * 1e3;
    s->drawn_depth = depth;
    s->points = st.points;
    out_len = 0;
    put_frame(&t, app->scene->palette, &s->lay);
    put_status(s);
    return write_all(out, out_len) == 0 ? 1 : -1;
}

/* ---- input -------------------------------------------------------------------------------------- */

static double hold_end(const key_hold *k)
{
    double a = k->last + HOLD_GAP_S, b = k->press + FIRST_REPEAT_S;
    return a > b ? a : b;
}

static void press_arrow(term_state *s, int key, double now)
{
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

static void handle_char(term_state *s, unsigned char c)
{
    switch (c) {
    case 'q': case 'Q': case 3: s->quit = 1; break;   /* 3 = Ctrl-C */
    case '+': case '=': s->zoom = clampd(s->zoom * ZOOM_STEP, ZOOM_MIN, ZOOM_MAX); break;
    case '-': case '_': s->zoom = clampd(s->zoom / ZOOM_STEP, ZOOM_MIN, ZOOM_MAX); break;
    case 'r': case 'R': reset_view(s); break;
    default: break;
    }
}

/* Length of the escape sequence at p (p[0] = ESC), 0 if it is incomplete. *arrow receives KEY_*
 * for ESC [ A..D and ESC O A..D (with any modifier parameters), else -1. */
static size_t parse_escape(const unsigned char *p, size_t n, int *arrow)
{
    *arrow = -1;
    if (n < 2) return 0;
    if (p[1] != '[' && p[1] != 'O') return 1;   /* a lone ESC: drop it, the next byte is a key */
    size_t i = 2;
    while (i < n && p[i] >= 0x20 && p[i] <= 0x3F) i++;   /* parameters and intermediates */
    if (i == n) return 0;
    switch (p[i]) {
    case 'A': *arrow = KEY_UP; break;
    case 'B': *arrow = KEY_DOWN; break;
    case 'C': *arrow = KEY_RIGHT; break;
    case 'D': *arrow = KEY_LEFT; break;
    default: break;
    }
    return i + 1;
}

/* Reads every byte waiting on stdin without blocking and applies the keys. A sequence cut between
 * two reads is kept for the next call. Returns -1 at end of input. */
static int read_keys(term_state *s, double now)
{
    static unsigned char buf[256];
    static size_t len;
    for (;;) {
        if (len == sizeof buf) len = 0;   /* only garbage gets this long */
        ssize_t n = read(STDIN_FILENO, buf + len, sizeof buf - len);
        if (n < 0) return errno == EINTR || errno == EAGAIN ? 0 : -1;
        if (n == 0) {
            /* nothing waiting (VMIN=0), or the terminal hung up */
            struct pollfd p = {STDIN_FILENO, POLLIN, 0};
            return poll(&p, 1, 0) > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) ? -1 : 0;
        }
        len += (size_t)n;
        s->auto_turn = 0;   /* the first key stops the automatic turn */
        size_t i = 0;
        while (i < len) {
            if (buf[i] != 0x1b) {
                handle_char(s, buf[i++]);
                continue;
            }
            int arrow;
            size_t used = parse_escape(buf + i, len - i, &arrow);
            if (used == 0) break;
            if (arrow >= 0) press_arrow(s, arrow, now);
            i += used;
        }
        memmove(buf, buf + i, len - i);
        len -= i;
        s->fine_needed = 1;
    }
}

/* Sleeps until a key arrives, a signal, or timeout_ms passes (-1: no timeout). */
static void wait_input(int timeout_ms)
{
    struct pollfd p = {STDIN_FILENO, POLLIN, 0};
    poll(&p, 1, timeout_ms);
}

/* Sleeps out the rest of a moving frame's interval; a frame that took longer does not sleep. */
static void pace(double frame_start)
{
    double left = FRAME_INTERVAL_S - (now_s() - frame_start);
    wait_input(left > 0 ? (int)ceil(left * 1e3) : 0);
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
    unsigned full = s->app->scene->depth, coarse = full > 1 ? full - 1u : 1u;
    double now = now_s();
    if (read_keys(s, now) < 0 || s->quit) return -1;
    advance(s, *prev, now);
    *prev = now;
    if (moving(s, now)) {
        if (draw(s, coarse, NULL) < 0) return -1;
        s->fine_needed = 1;
        pace(now);
    } else if (s->fine_needed) {
        int r = draw(s, full, input_waiting);
        if (r < 0) return -1;
        if (r > 0) s->fine_needed = 0;
    } else {
        wait_input(-1);
    }
    return 0;
}

int mc_host_interactive(const mc_app *app, mc_view start)
{
    if (enter_raw_mode() != 0) {
        fprintf(stderr, "%s-view: interactive mode needs a terminal on stdin: %s\n", app->scene->name,
                strerror(errno));
        return 2;
    }
    term_state s;
    memset(&s, 0, sizeof s);
    s.app = app;
    s.start = start;
    reset_view(&s);
    s.auto_turn = 1;
    got_quit = got_winch = 0;
    install_signals();
    enter_screen();
    resize(&s);

    double prev = now_s();
    while (!got_quit) {
        if (got_winch) {
            got_winch = 0;
            resize(&s);
        }
        if (step(&s, &prev) < 0) break;
    }
    leave_screen();
    restore_signals();
    return got_quit ? 128 + got_quit : 0;   /* the shell's convention for a signal */
}
