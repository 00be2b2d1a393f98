/* Image quality of a bake's frames against the double-precision mesh reference, for tests/bench/views.sh:
 *
 *   views_psnr REF_DUMP [--size WxH] [--zoom Z] [--views N] [--error PX] [--ppm PREFIX]
 *
 * Links against a bake (mc_app_model), the runtime, the viewer's scene (runtime/front/host/scene.c) and the
 * mesh reference (runtime/ref/mesh_ref.c). REF_DUMP is the bake's `modelc --dump-reference` file.
 * Each of N views of a turn (yaw = i * 4096 / N modelc angle units, pitch 0, orthographic; default 8) is
 * drawn as the viewer draws it (mc_host_scene_draw: mc_clear, mc_octree_render with the default footprint
 * and max_error = PX * MC_LOD_PIXEL, default 1 pixel, 0 = the bake's depth, then mc_finish with the
 * default fill) and compared with the mesh reference (mc_mesh_ref_render) coloured through the bake's own
 * palette, both on a black background, as tests/accuracy/acc.c compares them:
 *   PSNR over R, G, B (99 dB when identical); the pooled figure sums the squared errors of all N views;
 *   coverage: the share of the pixels covered by either image that only one of them covers.
 * Prints "key: value" lines: the drawn depth, pooled PSNR, the worst view's PSNR, the pooled coverage
 * difference, and one "view I: ..." line per view. --ppm PREFIX writes view 0 (frontal) and its reference
 * as PREFIX.ppm and PREFIX.ref.ppm.
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/app.h>
#include <modelc/modelc.h>
#include "mesh_ref.h"
#include "scene.h"

static void to_rgb(const mc_target *t, const uint8_t *palette, uint8_t *rgb, uint8_t *cov)
{
    for (size_t i = 0; i < (size_t)t->width * t->height; i++) {
        int drawn = t->depth[i] != MC_DEPTH_EMPTY;
        cov[i] = (uint8_t)drawn;
        for (int a = 0; a < 3; a++) rgb[3 * i + a] = drawn ? palette[3 * t->color[i] + a] : 0;
    }
}

static int write_ppm(const char *path, const uint8_t *rgb, unsigned w, unsigned h)
{
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return -1; }
    fprintf(f, "P6\n%u %u\n255\n", w, h);
    fwrite(rgb, 3, (size_t)w * h, f);
    return fclose(f);
}

static double psnr_of(double se, double values) { return se > 0 ? 10 * log10(255.0 * 255.0 / (se / values)) : 99.0; }

int main(int argc, char **argv)
{
    const char *ref_path = NULL, *ppm = NULL;
    unsigned w = 320, h = 240;
    int views = 8;
    double zoom = 1, error_px = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (a[0] != '-') { ref_path = a; continue; }
        if (!v) { fprintf(stderr, "views_psnr: %s needs a value\n", a); return 2; }
        i++;
        if (!strcmp(a, "--size")) { if (sscanf(v, "%ux%u", &w, &h) != 2) return 2; }
        else if (!strcmp(a, "--zoom")) zoom = atof(v);
        else if (!strcmp(a, "--views")) views = atoi(v);
        else if (!strcmp(a, "--error")) error_px = atof(v);
        else if (!strcmp(a, "--ppm")) ppm = v;
        else { fprintf(stderr, "views_psnr: unknown option %s\n", a); return 2; }
    }
    if (!ref_path || views < 1 || w < 1 || h < 1 || w > mc_app_model.max_width || h > mc_app_model.max_height ||
        !(zoom >= 1.0 / 64 && zoom <= 64) || !(error_px == 0 || (error_px >= 1.0 / 16 && error_px <= 64))) {
        fprintf(stderr, "usage: views_psnr REF_DUMP [--size WxH (at most %ux%u)] [--zoom Z] [--views N] [--error PX] "
                        "[--ppm PREFIX]\n", mc_app_model.max_width, mc_app_model.max_height);
        return 2;
    }
    mc_mesh_ref m;
    char err[300];
    if (mc_mesh_ref_load(ref_path, &m, err, sizeof err) != 0) { fprintf(stderr, "views_psnr: %s\n", err); return 1; }
    const mc_octree *scene = mc_app_model.model->octree;
    const size_t n = (size_t)w * h;
    uint8_t *img = malloc(3 * n), *cov = malloc(n), *ref = malloc(3 * n), *ref_cov = malloc(n);
    if (!img || !cov || !ref || !ref_cov) { fprintf(stderr, "views_psnr: out of memory\n"); return 1; }

    /* the viewer's frame: its scene, points mode, the default footprint and fill, --error's bound */
    /* designated: every other field at its default (zero), whatever mc_octree_options holds */
    const mc_octree_options opt = {.splat = MC_SPLAT_DEFAULT, .max_error = (uint16_t)lround(error_px * MC_LOD_PIXEL)};
    mc_host_scene s;
    if (mc_host_scene_init(&s, &mc_app_model, MC_HOST_POINTS, &opt, MC_FILL_DEFAULT)) return 1;
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)w, (uint16_t)h};

    double se_all = 0, worst = 99.0;
    size_t diff_all = 0, any_all = 0;
    printf("model: %s\nbake depth: %u\nsize: %ux%u\nzoom: %g\nerror px: %g\nviews: %d\n", mc_app_model.model->name,
           (unsigned)scene->depth, w, h, zoom, error_px, views);
    for (int vi = 0; vi < views; vi++) {
        mc_view v = mc_view_default();
        v.yaw = (int32_t)((int64_t)MC_ANGLE_FULL * vi / views);
        v.zoom = (int32_t)lround(zoom * MC_ZOOM_ONE);
        uint32_t drawn = 0;
        if (mc_host_scene_draw(&s, &v, scene->depth, NULL, &t, &drawn) != MC_OK) {
            fprintf(stderr, "views_psnr: render failed\n");
            return 1;
        }
        if (mc_mesh_ref_render(&m, &v, w, h, scene->palette, scene->palette_size, ref, ref_cov, NULL) < 0) {
            fprintf(stderr, "views_psnr: out of memory\n");
            return 1;
        }
        to_rgb(&t, scene->palette, img, cov);
        double se = 0;
        size_t diff = 0, any = 0;
        for (size_t i = 0; i < 3 * n; i++) { double d = (double)img[i] - ref[i]; se += d * d; }
        for (size_t i = 0; i < n; i++) { diff += cov[i] != ref_cov[i]; any += cov[i] || ref_cov[i]; }
        double p = psnr_of(se, 3.0 * n);
        worst = p < worst ? p : worst;
        se_all += se, diff_all += diff, any_all += any;
        printf("view %d: yaw %d units, depth drawn %u, points %u, PSNR %.3f dB, coverage differs %.5f\n", vi, (int)v.yaw,
               s.drawn_depth, drawn, p, any ? (double)diff / any : 0.0);
        if (vi == 0 && ppm) {
            char path[512];
            snprintf(path, sizeof path, "%s.ppm", ppm);
            if (write_ppm(path, img, w, h)) return 1;
            snprintf(path, sizeof path, "%s.ref.ppm", ppm);
            if (write_ppm(path, ref, w, h)) return 1;
        }
    }
    printf("depth drawn: %u\n", s.drawn_depth);
    printf("psnr pooled: %.3f\n", psnr_of(se_all, 3.0 * n * views));
    printf("psnr worst view: %.3f\n", worst);
    printf("coverage differs: %.5f\n", any_all ? (double)diff_all / any_all : 0.0);
    mc_mesh_ref_free(&m);
    free(img), free(cov), free(ref), free(ref_cov);
    return 0;
}
