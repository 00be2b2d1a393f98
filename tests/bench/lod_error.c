/* Run time against error for the progressive mesh's level of detail (tests/bench/lod_error.sh): a
 * bake's mesh part drawn in the shaded style at several levels over the views of a turn, each frame
 * compared with the full level's frame of the same view.
 *
 * Built with -DPM=mc_pmesh_NAME -include NAME.h, the bake's .c files, all of runtime/src and
 * runtime/front/common/mesh_frame.c, -Iruntime/include -Iruntime/front/host (timing.h)
 * -Iruntime/front/common (mesh_frame.h), -D_POSIX_C_SOURCE=200809L.
 *
 * A frame: mc_front_mesh_frame(&lod, mem, cache, 0, &view, MC_FRONT_SHADED, &t, &st) (mc_clear, the
 * flat-shaded faces, back faces culled when the part is closed), with the static vertex cache
 * (--no-cache: none) and mc_mesh_lines' memory (MC_MESH_LINES_BYTES(F), zeroed; the shaded style
 * does not use it). View i of N: yaw i * MC_ANGLE_FULL / N, pitch --pitch (angle units, default 0),
 * roll 0, zoom 1, orthographic (mesh_frames' views at pitch 0). Level P (a percentage): the finest
 * level with at most P * F / 100 faces (rounded down), mc_pmesh_lod_fit, F the full mesh's faces.
 *
 *   lod_error --percent P1,P2,... [--views N] [--size WxH] [--reps R] [--pitch U] [--no-cache]
 *       For each view the full level's frame is the reference: its RGB (mc_target_rgb, the part's
 *       palette, a white background) and its coverage (depth not MC_DEPTH_EMPTY). Then R rounds; in
 *       each, every level in turn (the order reversed every other round), set untimed, and its N
 *       frames timed one by one (wall clock and process CPU time); the first round also compares
 *       each frame with the reference. One line per level:
 *         level P budget B faces F vertices V mse M psnr X psnr_min Y cov_diff D cov_diff_max E
 *         cov_union U ms T cpu_ms C
 *       mse: of the RGB channels over the N frames' pixels, pooled; psnr = 10 log10(255^2 / mse)
 *       ("inf" when the frames are the same bytes); psnr_min: the worst frame's; cov_diff: the
 *       pixels covered in one frame and not the other, over the N views, as a fraction of those
 *       covered in either (cov_union, summed); cov_diff_max: the worst frame's fraction; ms, cpu_ms:
 *       the median over the R * N frames.
 *   lod_error --cg P [--views N] [--size WxH] [--pitch U] [--no-cache]
 *       Sets level P (outside mc_front_mesh_frame) and draws its N frames: for valgrind
 *       --tool=callgrind --toggle-collect=mc_front_mesh_frame; prints "level P faces F frames N".
 *   lod_error --ppm PREFIX --view I --percent P1,P2,... [--views N] [--size WxH] [--pitch U]
 *       Writes view I at each level as PREFIX.P.ppm (binary PPM, the RGB above).
 * Sizes up to 1024x1024; at most 16 levels and 64 views.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/mesh_lines.h"
#include "modelc/mesh_render.h"
#include "modelc/target.h"
#include "mesh_frame.h"   /* runtime/front/common: mc_front_mesh_frame */
#include "timing.h"       /* runtime/front/host: clocks, medians */

#define MAX_SIDE 1024
#define MAX_LEVELS 16
#define MAX_VIEWS 64
#define MAX_FACES (1u << 23)

extern const mc_pmesh PM;

static uint8_t color[MAX_SIDE * MAX_SIDE];
static uint16_t depth[MAX_SIDE * MAX_SIDE];
static uint32_t anc[1u << 22];           /* the ancestor map: V entries of up to 4 bytes */
static mc_xvertex vcache[1u << 22];      /* the vertex cache: MC_MESH_CACHE_BYTES(V) */
static uint32_t lines_mem[(MC_MESH_LINES_BYTES(MAX_FACES) + 3u) / 4u];
static const uint8_t white[3] = {255, 255, 255};

static int w = 320, h = 240, views = 12, pitch = 0;
static mc_xvertex *cache = vcache;

static mc_view view_of(int i)
{
    mc_view v = mc_view_default();
    v.yaw = (int32_t)((int64_t)MC_ANGLE_FULL * i / views);
    v.pitch = pitch;
    v.roll = 0;
    v.zoom = MC_ZOOM_ONE;
    v.projection = MC_ORTHOGRAPHIC;
    return v;
}

static int frame(mc_pmesh_lod *lod, int i, const mc_target *t)
{
    const mc_view v = view_of(i);
    mc_front_mesh_stats st;
    return mc_front_mesh_frame(lod, (uint8_t *)lines_mem, cache, 0, &v, MC_FRONT_SHADED, t, &st);
}

static uint32_t budget_of(double p) { return (uint32_t)((double)PM.faces * p / 100.0); }

static void rgb_of(const mc_target *t, uint8_t *out)
{
    for (uint32_t i = 0; i < (uint32_t)t->width * t->height; i++) mc_target_rgb(t, i, PM.palette, white, out + 3 * i);
}

static int parse_levels(const char *s, double *p)
{
    int n = 0;
    while (*s && n < MAX_LEVELS) {
        char *end;
        p[n] = strtod(s, &end);
        if (end == s || p[n] <= 0 || p[n] > 100) return -1;
        n++;
        s = *end == ',' ? end + 1 : end;
        if (*end && *end != ',') return -1;
    }
    return *s ? -1 : n;
}

static int usage(void)
{
    fprintf(stderr, "usage: lod_error --percent P1,P2,... [--reps R] | --cg P | --ppm PREFIX --view I --percent ...  "
                    "[--views N] [--size WxH] [--pitch U] [--no-cache]\n");
    return 2;
}

int main(int argc, char **argv)
{
    double levels[MAX_LEVELS];
    int nlevels = 0, reps = 5, view_i = -1;
    double cg = 0;
    const char *ppm = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--no-cache")) { cache = NULL; continue; }
        if (i + 1 >= argc) return usage();
        const char *v = argv[++i];
        if (!strcmp(a, "--percent")) { if ((nlevels = parse_levels(v, levels)) < 1) return usage(); }
        else if (!strcmp(a, "--views")) views = atoi(v);
        else if (!strcmp(a, "--size")) { if (sscanf(v, "%dx%d", &w, &h) != 2) return usage(); }
        else if (!strcmp(a, "--reps")) reps = atoi(v);
        else if (!strcmp(a, "--pitch")) pitch = atoi(v);
        else if (!strcmp(a, "--cg")) cg = atof(v);
        else if (!strcmp(a, "--ppm")) ppm = v;
        else if (!strcmp(a, "--view")) view_i = atoi(v);
        else return usage();
    }
    if (w < 1 || h < 1 || w > MAX_SIDE || h > MAX_SIDE || views < 1 || views > MAX_VIEWS || reps < 1) return usage();
    if (PM.vertices > sizeof anc / sizeof anc[0] || MC_MESH_CACHE_BYTES(PM.vertices) > sizeof vcache ||
        PM.faces > MAX_FACES)
        return 2;
    memset(lines_mem, 0, MC_MESH_LINES_BYTES(PM.faces));
    const mc_target t = {color, depth, (uint16_t)w, (uint16_t)h};
    const size_t npx = (size_t)w * h;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);

    if (cg > 0) {   /* callgrind: the level's frames only */
        mc_pmesh_lod_fit(&lod, budget_of(cg));
        for (int i = 0; i < views; i++)
            if (frame(&lod, i, &t) != MC_OK) return 1;
        printf("level %g faces %u vertices %u frames %d%s\n", cg, (unsigned)lod.faces, (unsigned)lod.level, views,
               cache ? "" : " no-cache");
        return 0;
    }
    if (!nlevels) return usage();
    if (ppm) {   /* one view at each level */
        if (view_i < 0 || view_i >= views) return usage();
        uint8_t *rgb = malloc(3 * npx);
        if (!rgb) return 1;
        for (int l = 0; l < nlevels; l++) {
            mc_pmesh_lod_fit(&lod, budget_of(levels[l]));
            if (frame(&lod, view_i, &t) != MC_OK) return 1;
            rgb_of(&t, rgb);
            char path[4096];
            snprintf(path, sizeof path, "%s.%g.ppm", ppm, levels[l]);
            FILE *f = fopen(path, "wb");
            if (!f) { perror(path); return 1; }
            fprintf(f, "P6\n%d %d\n255\n", w, h);
            fwrite(rgb, 1, 3 * npx, f);
            if (fclose(f)) return 1;
            printf("level %g faces %u vertices %u view %d: %s\n", levels[l], (unsigned)lod.faces, (unsigned)lod.level,
                   view_i, path);
        }
        free(rgb);
        return 0;
    }

    /* the references: the full level's frames */
    uint8_t *ref = malloc(3 * npx * views), *refcov = malloc(npx * views), *rgb = malloc(3 * npx);
    double *ms = malloc(sizeof *ms * (size_t)nlevels * reps * views);
    double *cpu = malloc(sizeof *cpu * (size_t)nlevels * reps * views);
    if (!ref || !refcov || !rgb || !ms || !cpu) return 1;
    mc_pmesh_lod_set(&lod, PM.vertices);
    for (int i = 0; i < views; i++) {
        if (frame(&lod, i, &t) != MC_OK) return 1;
        rgb_of(&t, ref + 3 * npx * i);
        for (size_t k = 0; k < npx; k++) refcov[npx * i + k] = depth[k] != MC_DEPTH_EMPTY;
    }
    struct {
        uint32_t budget, faces, vertices;
        double sq, psnr_min, diff, uni, diff_max;
    } res[MAX_LEVELS];
    for (int r = 0; r < reps; r++)
        for (int j = 0; j < nlevels; j++) {
            const int l = r % 2 ? nlevels - 1 - j : j;
            res[l].budget = budget_of(levels[l]);
            mc_pmesh_lod_fit(&lod, res[l].budget);
            res[l].faces = lod.faces, res[l].vertices = lod.level;
            if (r == 0) res[l].sq = res[l].diff = res[l].uni = res[l].diff_max = 0, res[l].psnr_min = INFINITY;
            for (int i = 0; i < views; i++) {
                const double t0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
                const int rc = frame(&lod, i, &t);
                const size_t s = ((size_t)l * reps + r) * views + i;
                ms[s] = mc_host_now_ms() - t0;
                cpu[s] = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
                if (rc != MC_OK) return 1;
                if (r) continue;
                rgb_of(&t, rgb);
                const uint8_t *a = ref + 3 * npx * i, *ca = refcov + npx * i;
                double sq = 0, diff = 0, uni = 0;
                for (size_t k = 0; k < 3 * npx; k++) {
                    const double d = (double)a[k] - rgb[k];
                    sq += d * d;
                }
                for (size_t k = 0; k < npx; k++) {
                    const int cb = depth[k] != MC_DEPTH_EMPTY;
                    diff += ca[k] != cb;
                    uni += ca[k] || cb;
                }
                res[l].sq += sq;
                res[l].diff += diff;
                res[l].uni += uni;
                const double psnr = sq > 0 ? 10 * log10(255.0 * 255.0 * 3 * npx / sq) : INFINITY;
                if (psnr < res[l].psnr_min) res[l].psnr_min = psnr;
                if (uni > 0 && diff / uni > res[l].diff_max) res[l].diff_max = diff / uni;
            }
        }
    printf("mesh faces %u vertices %u base faces %u closed %u views %d size %dx%d pitch %d reps %d%s\n",
           (unsigned)PM.faces, (unsigned)PM.vertices, (unsigned)PM.base_faces, (unsigned)PM.closed, views, w, h, pitch,
           reps, cache ? "" : " no-cache");
    for (int l = 0; l < nlevels; l++) {
        const double mse = res[l].sq / (3.0 * npx * views);
        const double psnr = mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : INFINITY;
        printf("level %g budget %u faces %u vertices %u mse %.4f psnr %.3f psnr_min %.3f cov_diff %.6f "
               "cov_diff_max %.6f cov_union %.0f ms %.4f cpu_ms %.4f\n",
               levels[l], (unsigned)res[l].budget, (unsigned)res[l].faces, (unsigned)res[l].vertices, mse, psnr,
               res[l].psnr_min, res[l].uni > 0 ? res[l].diff / res[l].uni : 0.0, res[l].diff_max, res[l].uni,
               mc_host_median(ms + (size_t)l * reps * views, (size_t)reps * views),
               mc_host_median(cpu + (size_t)l * reps * views, (size_t)reps * views));
    }
    free(ref), free(refcov), free(rgb), free(ms), free(cpu);
    return 0;
}
