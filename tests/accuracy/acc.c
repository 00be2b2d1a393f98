/* Accuracy and cost of one runtime build against the mesh reference (make
 * bench-accuracy, tests/accuracy/bench.sh):
 *
 *   acc REF_DUMP --tag TAG [--frames N] [--cg] [--size WxH] [--error PX] [--dump DIR]
 *
 * Built per setting by tests/accuracy/bench.sh: the runtime (runtime/src, with -DMC_FRAC_BITS=F, or
 * with tests/accuracy/pos_single.h for the float build of the renderer, config.h MC_POS_HEADER), one bake of the model at depth D
 * (ACC_SCENE naming its descriptor, mc_octree_NAME), runtime/ref/ref.c and runtime/ref/mesh_ref.c.
 * With -DACC_EXACT=1 the "exact" build: the octree is drawn by the double-precision walk of
 * runtime/ref/ref.c (mc_ref_points: every leaf placed exactly from its integer cell coordinates) with
 * the runtime's footprints and a 16-bit depth buffer, so that the runtime's finishing (mc_finish)
 * runs on it unchanged: the error no number format of the renderer can beat. It is not an optimised
 * renderer (a 3x3 matrix product per leaf, in double, through a callback): its time is no target.
 *
 * For each view (yaw, pitch in degrees, zoom) x splat (one pixel, zoom footprint when the runtime has
 * them) x fill (none, one-pixel, scanline when the runtime has it), it prints one CSV row:
 *   tag,yaw,pitch,zoom,splat,fill,psnr,ssim,coverage,ms,cpu_ms,status
 *   psnr: dB over R, G, B of the whole frame against the mesh reference (background black in both),
 *         the reference coloured through the bake's own palette (the same lighting, the same mapping);
 *   ssim: mean SSIM of the luminance (BT.601) with the 11x11 Gaussian window (sigma 1.5, K1 0.01,
 *         K2 0.03; Wang et al. 2004), over the windows wholly inside the frame;
 *   coverage: the share of the pixels covered by either image that only one of them covers;
 *   ms, cpu_ms: median wall-clock / thread CPU milliseconds of mc_clear + render + finish over N frames
 *         (at least N, and at least 40 ms of frames, at most 400);
 *   status: ok, or the runtime's error (e.g. size: mc_octree_render refuses a target larger than
 *         MC_TARGET_MAX, which is 2^(27 - MC_FRAC_BITS) pixels).
 * --error PX: the level-selection bound (mc_octree_options.max_error = 16 PX, Q4 pixels): the renderer
 * draws the shallowest level whose nodes span at most PX pixels (mc_octree_lod_depth), never deeper
 * than the bake; the exact build draws the same level. 0 (default): the bake's depth.
 * --dump DIR: also writes each image and the reference as DIR/vI_SPLAT_FILL.ppm and DIR/vI_ref.ppm.
 * --cg: no reference and no timing; each of the four cost views is drawn once per splat and finished
 * once per fill through the noinline functions acc_clear, acc_render_S, acc_fill_M_S, which
 * tests/accuracy/bench.sh runs under callgrind (--toggle-collect=acc_*) to count instructions per frame.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modelc/modelc.h>
#include "mesh_ref.h"
#include "ref.h"
#include "timing.h"   /* runtime/front/host: clocks, medians */

#ifndef ACC_EXACT
#define ACC_EXACT 0
#endif
extern const mc_octree ACC_SCENE;
static const mc_octree *scene = &ACC_SCENE;

#ifdef MC_SPLAT_DEFAULT_MODE
#define HAVE_SPLATS 1
#else
#define HAVE_SPLATS 0
#endif
#ifdef MC_DEPTH_FILLED
#define HAVE_SCANLINE 1
#else
#define HAVE_SCANLINE 0
#endif

#define MAXW 1024
#define MAXH 1024
static unsigned W = 320, H = 240;
static uint8_t color[MAXW * MAXH], saved_color[MAXW * MAXH];
static uint16_t depthbuf[MAXW * MAXH], saved_depth[MAXW * MAXH];
static uint8_t ref_rgb[3 * MAXW * MAXH], ref_cov[MAXW * MAXH];

typedef struct view_spec { double yaw, pitch, zoom; } view_spec;
/* rotations 0..60 degrees, zoom 1..2 */
static const view_spec views[] = {
    {0, 0, 1}, {20, 5, 1}, {40, 10, 1}, {60, 15, 1},
    {0, 0, 1.5}, {20, 5, 1.5}, {40, 10, 1.5}, {60, 15, 1.5},
    {0, 0, 2}, {20, 5, 2}, {40, 10, 2}, {60, 15, 2},
};
/* the instruction-count subset */
static const view_spec cg_views[] = {{20, 5, 1}, {60, 15, 1}, {20, 5, 2}, {60, 15, 2}};

static const char *splat_names[] = {"pixel", "zoom"};
static const char *fill_names[] = {"none", "pixel", "scanline"};
static const int nsplats = HAVE_SPLATS ? 2 : 1, nfills = HAVE_SCANLINE ? 3 : 2;

/* the footprint of the view make_view made last, and the level-selection bound (--error) */
static mc_octree_options opt;

static mc_view make_view(const view_spec *s, int splat)
{
    mc_view v = mc_view_default();
    v.yaw = (int32_t)lround(s->yaw / 360.0 * MC_ANGLE_FULL);
    v.pitch = (int32_t)lround(s->pitch / 360.0 * MC_ANGLE_FULL);
    v.zoom = (int32_t)lround(s->zoom * MC_ZOOM_ONE);
#if HAVE_SPLATS
    opt.splat = splat ? MC_SPLAT_ZOOM : MC_SPLAT_PIXEL;
#else
    (void)splat;
#endif
    return v;
}

/* ---- the "exact" build: exact leaf positions, the runtime's footprints -------------------------- */
#if ACC_EXACT
typedef struct exact_ctx { const mc_target *t; int side; } exact_ctx;

static void exact_plot(const mc_ref_point *p, void *user)
{
    exact_ctx *c = user;
    if (!p->on_screen) return;
    double z = p->depth * 30000.0;   /* 1 -+ sqrt(3)/2 cube sides -> 4019..55981 */
    uint16_t d = (uint16_t)(z < 0 ? 0 : z > 65000 ? 65000 : z);
    long x0 = (long)floor(p->sx - (c->side - 1) / 2.0), y0 = (long)floor(p->sy - (c->side - 1) / 2.0);
    long x1 = x0 + c->side, y1 = y0 + c->side;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > c->t->width) x1 = c->t->width;
    if (y1 > c->t->height) y1 = c->t->height;
    for (long y = y0; y < y1; y++)
        for (long x = x0; x < x1; x++) {
            size_t i = (size_t)y * c->t->width + (size_t)x;
            if (d < c->t->depth[i]) { c->t->depth[i] = d; c->t->color[i] = *p->color; }
        }
}

#endif

static int render(const mc_view *v, const mc_target *t)
{
#if ACC_EXACT
    mc_view c = mc_view_clamp(v, t->width, t->height);
    exact_ctx fc = {t, 1};
    const unsigned level = mc_octree_lod_depth(&c, t->width, t->height, scene->depth, opt.max_error);
#if HAVE_SPLATS
    if (opt.splat == MC_SPLAT_ZOOM || (opt.splat == MC_SPLAT_DEFAULT && MC_SPLAT_DEFAULT_MODE == MC_SPLAT_ZOOM)) {
        double leaf = c.zoom / 65536.0 * (t->width < t->height ? t->width : t->height) / (double)(1u << level);
        double s = ceil(leaf - 1e-9);
        fc.side = s < 1 ? 1 : s > MC_SPLAT_MAX ? MC_SPLAT_MAX : (int)s;
    }
#endif
    mc_ref_points(scene, &c, level, t->width, t->height, exact_plot, &fc);
    return MC_OK;
#else
    return mc_octree_render(scene, v, scene->depth, &opt, t, NULL, NULL, NULL);
#endif
}

static uint32_t finish(const mc_target *t, int fill)
{
    if (fill == 0) return 0;
#if HAVE_SCANLINE
    return mc_finish(t, fill == 1 ? MC_FILL_PIXEL : MC_FILL_SCANLINE);
#else
    return mc_finish_pixel_holes(t);
#endif
}

/* ---- metrics ------------------------------------------------------------------------------------- */
static void to_rgb(const mc_target *t, uint8_t *rgb, uint8_t *cov)
{
    for (size_t i = 0; i < (size_t)t->width * t->height; i++) {
        int drawn = t->depth[i] != MC_DEPTH_EMPTY;
        cov[i] = (uint8_t)drawn;
        for (int a = 0; a < 3; a++) rgb[3 * i + a] = drawn ? scene->palette[3 * t->color[i] + a] : 0;
    }
}

static double psnr(const uint8_t *a, const uint8_t *b, size_t n)
{
    double se = 0;
    for (size_t i = 0; i < 3 * n; i++) { double d = (double)a[i] - b[i]; se += d * d; }
    if (se == 0) return 99.0;
    return 10 * log10(255.0 * 255.0 / (se / (3.0 * n)));
}

static double luma(const uint8_t *p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; }

/* separable 11-tap Gaussian of src (w x h) into dst, valid part only: (w-10) x (h-10) */
static void blur(const double *src, double *tmp, double *dst, unsigned w, unsigned h, const double g[11])
{
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x + 10 < w; x++) {
            double s = 0;
            for (int k = 0; k < 11; k++) s += g[k] * src[(size_t)y * w + x + k];
            tmp[(size_t)y * w + x] = s;
        }
    for (unsigned y = 0; y + 10 < h; y++)
        for (unsigned x = 0; x + 10 < w; x++) {
            double s = 0;
            for (int k = 0; k < 11; k++) s += g[k] * tmp[(size_t)(y + k) * w + x];
            dst[(size_t)y * w + x] = s;
        }
}

static double ssim(const uint8_t *a, const uint8_t *b, unsigned w, unsigned h)
{
    size_t n = (size_t)w * h;
    double *buf = malloc(12 * n * sizeof(double));
    if (!buf) return NAN;
    double *x = buf, *y = x + n, *xx = y + n, *yy = xx + n, *xy = yy + n, *tmp = xy + n;
    double *mx = tmp + n, *my = mx + n, *sxx = my + n, *syy = sxx + n, *sxy = syy + n;
    for (size_t i = 0; i < n; i++) {
        x[i] = luma(a + 3 * i), y[i] = luma(b + 3 * i);
        xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
    }
    double g[11], gs = 0;
    for (int k = 0; k < 11; k++) gs += g[k] = exp(-(k - 5) * (k - 5) / (2 * 1.5 * 1.5));
    for (int k = 0; k < 11; k++) g[k] /= gs;
    blur(x, tmp, mx, w, h, g);
    blur(y, tmp, my, w, h, g);
    blur(xx, tmp, sxx, w, h, g);
    blur(yy, tmp, syy, w, h, g);
    blur(xy, tmp, sxy, w, h, g);
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double sum = 0;
    size_t cnt = 0;
    for (unsigned yy0 = 0; yy0 + 10 < h; yy0++)
        for (unsigned xx0 = 0; xx0 + 10 < w; xx0++) {
            size_t i = (size_t)yy0 * w + xx0;
            double ux = mx[i], uy = my[i];
            double vx = sxx[i] - ux * ux, vy = syy[i] - uy * uy, cxy = sxy[i] - ux * uy;
            sum += (2 * ux * uy + c1) * (2 * cxy + c2) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
            cnt++;
        }
    free(buf);
    return sum / (double)cnt;
}

static double coverage_diff(const uint8_t *a, const uint8_t *b, size_t n)
{
    size_t diff = 0, any = 0;
    for (size_t i = 0; i < n; i++) { diff += a[i] != b[i]; any += a[i] || b[i]; }
    return any ? (double)diff / (double)any : 0;
}

/* ---- timing -------------------------------------------------------------------------------------- */
static void time_frames(const mc_view *v, const mc_target *t, int fill, int frames, double *ms, double *cpu)
{
    static double wall[400], thr[400];
    int n = 0;
    double total = 0;
    while (n < 400 && (n < frames || total < 40.0)) {
        double w0 = mc_host_clock_ms(CLOCK_MONOTONIC), c0 = mc_host_clock_ms(CLOCK_THREAD_CPUTIME_ID);
        mc_clear(t);
        render(v, t);
        finish(t, fill);
        double c1 = mc_host_clock_ms(CLOCK_THREAD_CPUTIME_ID), w1 = mc_host_clock_ms(CLOCK_MONOTONIC);
        wall[n] = w1 - w0, thr[n] = c1 - c0;
        total += wall[n++];
    }
    *ms = mc_host_median(wall, (size_t)n);
    *cpu = mc_host_median(thr, (size_t)n);
}

/* ---- callgrind mode: one function per counted part ----------------------------------------------- */
#define NOINLINE __attribute__((noinline))
NOINLINE void acc_clear(const mc_target *t) { mc_clear(t); }
NOINLINE void acc_render_pixel(const mc_view *v, const mc_target *t) { render(v, t); }
NOINLINE void acc_render_zoom(const mc_view *v, const mc_target *t) { render(v, t); }
NOINLINE void acc_fill_pixel_pixel(const mc_target *t) { finish(t, 1); }
NOINLINE void acc_fill_pixel_zoom(const mc_target *t) { finish(t, 1); }
NOINLINE void acc_fill_scanline_pixel(const mc_target *t) { finish(t, 2); }
NOINLINE void acc_fill_scanline_zoom(const mc_target *t) { finish(t, 2); }

static void save(const mc_target *t)
{
    memcpy(saved_color, t->color, (size_t)t->width * t->height);
    memcpy(saved_depth, t->depth, (size_t)t->width * t->height * 2);
}
static void restore(const mc_target *t)
{
    memcpy(t->color, saved_color, (size_t)t->width * t->height);
    memcpy(t->depth, saved_depth, (size_t)t->width * t->height * 2);
}

static void write_ppm(const char *dir, const char *name, const uint8_t *rgb)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.ppm", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return;
    fprintf(f, "P6\n%u %u\n255\n", W, H);
    fwrite(rgb, 3, (size_t)W * H, f);
    fclose(f);
}

static int run_cg(const mc_target *t)
{
    for (size_t vi = 0; vi < sizeof cg_views / sizeof cg_views[0]; vi++)
        for (int s = 0; s < nsplats; s++) {
            mc_view v = make_view(&cg_views[vi], s);
            acc_clear(t);
            if (s) acc_render_zoom(&v, t); else acc_render_pixel(&v, t);
            save(t);
            if (s) acc_fill_pixel_zoom(t); else acc_fill_pixel_pixel(t);
            restore(t);
            if (nfills > 2) { if (s) acc_fill_scanline_zoom(t); else acc_fill_scanline_pixel(t); }
        }
    printf("cg_views %zu splats %d fills %d\n", sizeof cg_views / sizeof cg_views[0], nsplats, nfills);
    return 0;
}

int main(int argc, char **argv)
{
    const char *ref_path = NULL, *tag = "?", *dump = NULL;
    int frames = 15, cg = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--tag") && i + 1 < argc) tag = argv[++i];
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--cg")) cg = 1;
        else if (!strcmp(argv[i], "--error") && i + 1 < argc) {
            const double px = atof(argv[++i]);
            if (!(px >= 0 && px <= 64)) {
                fprintf(stderr, "acc: bad --error (0..64 pixels)\n");
                return 2;
            }
            opt.max_error = (uint16_t)lround(px * MC_LOD_PIXEL);
        }
        else if (!strcmp(argv[i], "--dump") && i + 1 < argc) dump = argv[++i];
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) {
            if (sscanf(argv[++i], "%ux%u", &W, &H) != 2 || W < 16 || H < 16 || W > MAXW || H > MAXH) {
                fprintf(stderr, "acc: bad --size\n");
                return 2;
            }
        } else if (argv[i][0] != '-') ref_path = argv[i];
        else { fprintf(stderr, "usage: acc REF_DUMP --tag TAG [--frames N] [--cg] [--size WxH] [--error PX]\n"); return 2; }
    }
    mc_target t = {color, depthbuf, (uint16_t)W, (uint16_t)H};
    if (cg) return run_cg(&t);
    if (!ref_path) { fprintf(stderr, "acc: no reference dump given\n"); return 2; }
    mc_mesh_ref m;
    char err[300];
    if (mc_mesh_ref_load(ref_path, &m, err, sizeof err) != 0) { fprintf(stderr, "acc: %s\n", err); return 1; }
    size_t n = (size_t)W * H;
    static uint8_t img[3 * MAXW * MAXH], cov[MAXW * MAXH];
    for (size_t vi = 0; vi < sizeof views / sizeof views[0]; vi++) {
        const view_spec *vs = &views[vi];
        mc_view v0 = make_view(vs, 0);
        if (mc_mesh_ref_render(&m, &v0, W, H, scene->palette, scene->palette_size, ref_rgb, ref_cov, NULL) < 0) {
            fprintf(stderr, "acc: out of memory\n");
            return 1;
        }
        for (int s = 0; s < nsplats; s++) {
            mc_view v = make_view(vs, s);
            mc_clear(&t);
            int rc = render(&v, &t);
            if (rc != MC_OK) {
                for (int f = 0; f < nfills; f++)
                    printf("%s,%g,%g,%g,%s,%s,,,,,,%s\n", tag, vs->yaw, vs->pitch, vs->zoom, splat_names[s],
                           fill_names[f], rc == MC_ERR_SIZE ? "size" : "error");
                continue;
            }
            save(&t);
            for (int f = 0; f < nfills; f++) {
                restore(&t);
                finish(&t, f);
                to_rgb(&t, img, cov);
                if (dump) {
                    char name[64];
                    snprintf(name, sizeof name, "v%zu_%s_%s", vi, splat_names[s], fill_names[f]);
                    write_ppm(dump, name, img);
                    snprintf(name, sizeof name, "v%zu_ref", vi);
                    write_ppm(dump, name, ref_rgb);
                }
                double p = psnr(img, ref_rgb, n), q = ssim(img, ref_rgb, W, H), c = coverage_diff(cov, ref_cov, n);
                double ms, cpu;
                time_frames(&v, &t, f, frames, &ms, &cpu);
                printf("%s,%g,%g,%g,%s,%s,%.3f,%.5f,%.5f,%.4f,%.4f,ok\n", tag, vs->yaw, vs->pitch, vs->zoom,
                       splat_names[s], fill_names[f], p, q, c, ms, cpu);
            }
        }
        fflush(stdout);
    }
    mc_mesh_ref_free(&m);
    return 0;
}
