/* Hole filling and splats against a reference image, for one model:
 *
 *   psnr [--frames N]
 *
 * Built by tests/finish/suite.sh with TEST_SCENE, the catalogue bake (depth D), and REF_SCENE, the
 * same model baked at depth D + 1 (sampled twice as densely: suite.sh says why). The reference image
 * is the double-precision renderer
 * (runtime/ref, mc_ref_render: z-buffered, one pixel per leaf, exact positions) of the depth D + 1
 * octree: its leaves are half the size, so at 320x240 they are under a pixel up to zoom 2 (0.94 px)
 * and it has (almost) no holes. Against it the score measures what filling and splats change, apart
 * from the sampling error that tests/accuracy measures against the original triangles
 * (runtime/ref/mesh_ref.h). Colours are compared in RGB through each bake's own palette; the background is (0, 0, 0)
 * in both.
 *
 * For each view (30 degrees of yaw at zoom 1, frontal at zoom 2, 30 degrees at zoom 2) and each splat
 * (one pixel, zoom footprint) it renders the fixed-point image at depth D and finishes it with each
 * fill (none, one-pixel, scanline), and prints PSNR (dB) against the reference, the share of pixels
 * whose coverage (drawn or not) differs, and the milliseconds per frame (render + finish, median of
 * N frames). Checks: no fill lowers PSNR; the scanline fill is at least as good as the one-pixel
 * fill; at 30 degrees and zoom 2 with one-pixel splats (the paper's drawing, where zoomed views show
 * a lattice of holes) the scanline fill raises PSNR by over 1 dB; the defaults (zoom splats and the
 * scanline fill) give the best image of the six; at zoom 1 both splats draw the same image.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modelc/modelc.h>
#include "ref.h"
#include "timing.h"   /* runtime/front/host: clocks, medians */

extern const mc_model TEST_MODEL, REF_MODEL;
#define TEST_SCENE (*TEST_MODEL.octree)
#define REF_SCENE (*REF_MODEL.octree)

#define W 320
#define H 240

static uint8_t color[W * H], ref_color[W * H];
static uint16_t depth[W * H], ref_depth[W * H];
static double ref_z[W * H];

/* empty pixels are black in both images */
static void rgb(const mc_octree *s, uint8_t *c, uint16_t *z, size_t i, int out[3])
{
    static const uint8_t black[3] = {0, 0, 0};
    const mc_target one = {c, z, W, H};
    uint8_t v[3];
    mc_target_rgb(&one, (uint32_t)i, s->palette, black, v);
    for (int k = 0; k < 3; k++) out[k] = v[k];
}

static double psnr(double *coverage_diff)
{
    double se = 0;
    size_t cov = 0;
    for (size_t i = 0; i < W * H; i++) {
        int a[3], b[3];
        rgb(&TEST_SCENE, color, depth, i, a);
        rgb(&REF_SCENE, ref_color, ref_depth, i, b);
        for (int k = 0; k < 3; k++) se += (double)(a[k] - b[k]) * (a[k] - b[k]);
        cov += (depth[i] == MC_DEPTH_EMPTY) != (ref_depth[i] == MC_DEPTH_EMPTY);
    }
    *coverage_diff = 100.0 * cov / (W * H);
    double mse = se / (3.0 * W * H);
    return mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : 99.0;
}

int main(int argc, char **argv)
{
    int frames = 11;
    if (argc > 2 && !strcmp(argv[1], "--frames")) frames = atoi(argv[2]);
    if (frames < 1) frames = 1;
    static const struct { const char *name; double yaw, zoom; } views[] = {
        {"yaw30", 30, 1}, {"zoom2", 0, 2}, {"yaw30-zoom2", 30, 2}};
    static const struct { const char *name; mc_splat splat; } splats[] = {
        {"pixel", MC_SPLAT_PIXEL}, {"zoom", MC_SPLAT_ZOOM}};
    static const struct { const char *name; mc_fill fill; } fills[] = {
        {"none", MC_FILL_NONE}, {"pixel", MC_FILL_PIXEL}, {"scanline", MC_FILL_SCANLINE}};
    mc_target t = {color, depth, W, H}, rt = {ref_color, ref_depth, W, H};
    int failed = 0;
    printf("# %s depth %u against the double-precision reference of %s (depth %u), %ux%u\n", TEST_MODEL.name,
           (unsigned)TEST_SCENE.depth, REF_MODEL.name, (unsigned)REF_SCENE.depth, W, H);
    printf("# %-12s %-6s %-9s %8s %10s %9s %8s\n", "view", "splat", "fill", "PSNR dB", "coverage%", "filled", "ms");
    for (size_t vi = 0; vi < sizeof views / sizeof views[0]; vi++) {
        mc_view v = mc_view_default();
        v.yaw = (int32_t)lround(views[vi].yaw * MC_ANGLE_FULL / 360.0);
        v.zoom = (int32_t)lround(views[vi].zoom * MC_ZOOM_ONE);
        mc_ref_render(&REF_SCENE, &v, REF_SCENE.depth, &rt, ref_z);
        double all[2][3];
        for (size_t si = 0; si < sizeof splats / sizeof splats[0]; si++) {
            const mc_octree_options opt = {splats[si].splat, 0, MC_CULL_DEFAULT};
            double p[3];
            for (size_t fi = 0; fi < sizeof fills / sizeof fills[0]; fi++) {
                double ms[101];
                uint32_t filled = 0;
                int n = frames > 101 ? 101 : frames;
                for (int f = 0; f < n; f++) {
                    double t0 = mc_host_now_ms();
                    mc_clear(&t);
                    mc_octree_render(&TEST_SCENE, &v, TEST_SCENE.depth, &opt, &t, NULL, NULL, NULL);
                    filled = mc_finish(&t, fills[fi].fill);
                    ms[f] = mc_host_now_ms() - t0;
                }
                mc_host_sort(ms, (size_t)n);
                double cov;
                p[fi] = psnr(&cov);
                printf("# %-12s %-6s %-9s %8.2f %10.2f %9u %8.3f\n", views[vi].name, splats[si].name, fills[fi].name,
                       p[fi], cov, filled, ms[n / 2]);
            }
            /* no fill lowers PSNR; the scanline fill is at least as good as the one-pixel fill; at
             * 30 degrees and zoom 2 with one-pixel splats (the paper's scaled view) it raises PSNR */
            for (size_t fi = 1; fi < 3; fi++) {
                int ok = p[fi] >= p[0] - 1e-9;
                printf("%s - finish: %s %s, %s splat: %s fill does not lower PSNR (%.2f dB -> %.2f dB)\n",
                       ok ? "ok" : "not ok", TEST_MODEL.name, views[vi].name, splats[si].name, fills[fi].name, p[0], p[fi]);
                failed += !ok;
            }
            int ok = p[2] >= p[1] - 1e-9;
            printf("%s - finish: %s %s, %s splat: scanline fill at least as good as one-pixel fill (%.2f dB vs %.2f dB)\n",
                   ok ? "ok" : "not ok", TEST_MODEL.name, views[vi].name, splats[si].name, p[2], p[1]);
            failed += !ok;
            if (views[vi].yaw == 30 && views[vi].zoom == 2 && splats[si].splat == MC_SPLAT_PIXEL) {
                ok = p[2] > p[0] + 1;
                printf("%s - finish: %s %s, %s splat: scanline fill raises PSNR by over 1 dB (%.2f dB -> %.2f dB)\n",
                       ok ? "ok" : "not ok", TEST_MODEL.name, views[vi].name, splats[si].name, p[0], p[2]);
                failed += !ok;
            }
            for (size_t fi = 0; fi < 3; fi++) all[si][fi] = p[fi];
        }
        /* the defaults (zoom splats, scanline fill) give the best image of the six */
        double best = 0;
        for (size_t si = 0; si < 2; si++)
            for (size_t fi = 0; fi < 3; fi++) best = all[si][fi] > best ? all[si][fi] : best;
        int ok = all[1][2] >= best - 1e-9;
        printf("%s - finish: %s %s: zoom splats with the scanline fill (the defaults) give the highest PSNR of the six (%.2f dB, best %.2f dB)\n",
               ok ? "ok" : "not ok", TEST_MODEL.name, views[vi].name, all[1][2], best);
        failed += !ok;
        if (views[vi].zoom <= 1) {   /* leaves under a pixel: both splats draw the same image */
            const mc_octree_options pixel = {MC_SPLAT_PIXEL, 0, MC_CULL_DEFAULT}, zoom = {MC_SPLAT_ZOOM, 0, MC_CULL_DEFAULT};
            mc_clear(&t);
            mc_octree_render(&TEST_SCENE, &v, TEST_SCENE.depth, &pixel, &t, NULL, NULL, NULL);
            memcpy(ref_color, color, sizeof color);
            memcpy(ref_depth, depth, sizeof depth);
            mc_clear(&t);
            mc_octree_render(&TEST_SCENE, &v, TEST_SCENE.depth, &zoom, &t, NULL, NULL, NULL);
            ok = !memcmp(ref_color, color, sizeof color) && !memcmp(ref_depth, depth, sizeof depth);
            printf("%s - finish: %s %s: zoom and one-pixel splats draw the same image when leaves are under a pixel\n",
                   ok ? "ok" : "not ok", TEST_MODEL.name, views[vi].name);
            failed += !ok;
        }
    }
    return failed != 0;
}
