/* Benchmark driver for valgrind --tool=callgrind: renders F views of one full turn with
 * mc_clear + mc_octree_render only (no finishing, no output), so that
 *   valgrind --tool=callgrind --toggle-collect=mc_octree_render ./callgrind_frames F
 * counts exactly the renderer's instructions. Links against a bake (mc_app_model) and the runtime.
 *
 *   callgrind_frames [F [YAW0]] [--size WxH] [--ppm FILE] [--mask FILE] [--image-yaw U] [VIEW]
 *   callgrind_frames --time N [--finish] [--size WxH] [VIEW]
 *
 * F      views of the turn (default 20): yaw = YAW0 + i * 4096 / F modelc angle units, as the
 *        viewer's --bench does; F = 1 draws the frontal view only
 * Prints the frames, the sum of mc_stats.points and the mean number of pixels covered.
 * --ppm FILE / --mask FILE: write one frame (no finishing; yaw U angle units from --image-yaw, default 0
 * = frontal) as a binary PPM, and its coverage (255 = drawn) as a binary PGM.
 * --time N: instead, time N frames of the turn exactly as the viewer's --bench does (mc_clear +
 * mc_octree_render [+ mc_finish_pixel_holes with --finish]) and print the median wall-clock time and the
 * median CPU time of the process per frame (CPU time leaves out time spent preempted on a busy
 * machine, like osmesa_points' "cpu ms").
 * VIEW (tests/bench/views.sh): --zoom Z (default 1), --perspective (eye 2 cube sides, mc_view_default's),
 * --error PX (mc_octree_options.max_error = PX * MC_LOD_PIXEL, 0 = the bake's depth; default 0, the
 * renderer's NULL options). Given any of them, the program also prints "depth drawn: N" (mc_stats.depth
 * of the last frame); without them it draws and prints exactly what it did before they existed.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modelc/app.h>
#include <modelc/modelc.h>
#include "timing.h"   /* runtime/front/host: clocks, medians */

static long covered(const mc_target *t)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)t->width * t->height; i++) n += t->depth[i] != MC_DEPTH_EMPTY;
    return n;
}

static int write_image(const char *path, const mc_target *t, const uint8_t *palette, int mask)
{
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return -1; }
    fprintf(f, "%s\n%d %d\n255\n", mask ? "P5" : "P6", t->width, t->height);
    for (size_t i = 0; i < (size_t)t->width * t->height; i++) {
        int drawn = t->depth[i] != MC_DEPTH_EMPTY;
        if (mask) {
            fputc(drawn ? 255 : 0, f);
        } else if (drawn) {
            fwrite(palette + 3 * t->color[i], 1, 3, f);
        } else {
            fputc(24, f); fputc(24, f); fputc(32, f);
        }
    }
    return fclose(f);
}

/* The view options: NULL options (the bake's depth, the default footprint) unless --error is given. */
static mc_view base_view;
static mc_octree_options options;
static const mc_octree_options *opt;
static int view_options;   /* any of --zoom, --perspective, --error given: print the drawn depth */

/* The viewer's --bench loop, timed with both clocks. */
static int time_frames(const mc_target *t, int frames, int finish)
{
    const mc_octree *scene = mc_app_model.model->octree;
    double *ms = malloc((size_t)frames * sizeof *ms), *cpu = malloc((size_t)frames * sizeof *cpu);
    if (!ms || !cpu) return 1;
    mc_view v = base_view;
    uint64_t points = 0;
    unsigned drawn_depth = 0;
    for (int i = 0; i < frames; i++) {
        v.yaw = (int32_t)((int64_t)MC_ANGLE_FULL * i / frames);
        mc_stats st;
        double t0 = mc_host_clock_ms(CLOCK_MONOTONIC), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
        mc_clear(t);
        mc_octree_render(scene, &v, scene->depth, opt, t, NULL, NULL, &st);
        if (finish) mc_finish_pixel_holes(t);
        ms[i] = mc_host_clock_ms(CLOCK_MONOTONIC) - t0;
        cpu[i] = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
        points += st.points;
        drawn_depth = st.depth;
    }
    printf("frames: %d%s\n", frames, finish ? "" : " no-finish");
    printf("ms per frame (median): %.3f\n", mc_host_median(ms, (size_t)frames));
    printf("cpu ms per frame (median): %.3f\n", mc_host_median(cpu, (size_t)frames));
    printf("points drawn per frame: %.0f\n", (double)points / frames);
    if (view_options) printf("depth drawn: %u\n", drawn_depth);
    free(ms);
    free(cpu);
    return 0;
}

int main(int argc, char **argv)
{
    int frames = 20, pos = 0, time_n = 0, finish = 0;
    long yaw0 = 0, image_yaw = 0;
    unsigned w = 320, h = 240;
    const char *ppm = NULL, *mask = NULL;
    double zoom = 1, error_px = 0;
    base_view = mc_view_default();
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc) {
            if (sscanf(argv[++i], "%ux%u", &w, &h) != 2) return 2;
        } else if (!strcmp(argv[i], "--ppm") && i + 1 < argc) {
            ppm = argv[++i];
        } else if (!strcmp(argv[i], "--mask") && i + 1 < argc) {
            mask = argv[++i];
        } else if (!strcmp(argv[i], "--image-yaw") && i + 1 < argc) {
            image_yaw = atol(argv[++i]);
        } else if (!strcmp(argv[i], "--time") && i + 1 < argc) {
            time_n = atoi(argv[++i]);
            if (time_n < 1) return 2;
        } else if (!strcmp(argv[i], "--finish")) {
            finish = 1;
        } else if (!strcmp(argv[i], "--zoom") && i + 1 < argc) {
            zoom = atof(argv[++i]);
            if (!(zoom >= 1.0 / 64 && zoom <= 64)) return 2;
            view_options = 1;
        } else if (!strcmp(argv[i], "--perspective")) {
            base_view.projection = MC_PERSPECTIVE;
            view_options = 1;
        } else if (!strcmp(argv[i], "--error") && i + 1 < argc) {
            error_px = atof(argv[++i]);
            if (!(error_px == 0 || (error_px >= 1.0 / 16 && error_px <= 64))) return 2;
            options.max_error = (uint16_t)(error_px * MC_LOD_PIXEL + 0.5);   /* no libm: run.sh links without -lm */
            opt = &options;
            view_options = 1;
        } else if (pos == 0) {
            frames = atoi(argv[i]); pos++;
        } else if (pos == 1) {
            yaw0 = atol(argv[i]); pos++;
        } else {
            fprintf(stderr, "usage: callgrind_frames [F [YAW0]] [--size WxH] [--ppm FILE] [--mask FILE] [--image-yaw U] [VIEW]\n"
                            "       callgrind_frames --time N [--finish] [--size WxH] [VIEW]\n"
                            "VIEW: [--zoom Z] [--perspective] [--error PX]\n");
            return 2;
        }
    }
    if (frames < 1 || w < 1 || h < 1 || w > mc_app_model.max_width || h > mc_app_model.max_height) {
        fprintf(stderr, "callgrind_frames: bad frames or size (at most %ux%u)\n", mc_app_model.max_width,
                mc_app_model.max_height);
        return 2;
    }
    const mc_octree *scene = mc_app_model.model->octree;
    base_view.zoom = (int32_t)(zoom * MC_ZOOM_ONE + 0.5);
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)w, (uint16_t)h};
    if (time_n) return time_frames(&t, time_n, finish);
    mc_view v = base_view;
    uint64_t points = 0;
    unsigned drawn_depth = 0;
    double pixels = 0;
    for (int i = 0; i < frames; i++) {
        v.yaw = (int32_t)(yaw0 + (int64_t)MC_ANGLE_FULL * i / frames);
        mc_stats st;
        mc_clear(&t);
        if (mc_octree_render(scene, &v, scene->depth, opt, &t, NULL, NULL, &st) != MC_OK) return 1;
        points += st.points;
        pixels += covered(&t);
        drawn_depth = st.depth;
    }
    printf("frames: %d\n", frames);
    printf("points drawn (sum): %llu\n", (unsigned long long)points);
    printf("pixels covered per view (mean of %d views): %.0f\n", frames, pixels / frames);
    if (view_options) printf("depth drawn: %u\n", drawn_depth);
    if (ppm || mask) {
        v.yaw = (int32_t)image_yaw;
        mc_clear(&t);
        mc_octree_render(scene, &v, scene->depth, opt, &t, NULL, NULL, NULL);
        printf("pixels covered in the image (yaw %ld units): %ld\n", image_yaw, covered(&t));
        if (ppm && write_image(ppm, &t, scene->palette, 0)) return 1;
        if (mask && write_image(mask, &t, scene->palette, 1)) return 1;
    }
    return 0;
}
