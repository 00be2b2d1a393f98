/* The modelc side of the filled-triangle benchmark (tests/bench/mesh.sh): mc_mesh_render drawing a
 * bake's progressive mesh at its full level of detail, one full turn of frames, against Mesa's
 * llvmpipe drawing the same triangles (tests/bench/osmesa_mesh.c). Built like pmesh_lod.c:
 * -DPM=mc_pmesh_NAME -include NAME.h, the bake's .c files and all of runtime/src, -Iruntime/include
 * -Iruntime/front/host (timing.h).
 *
 *   mesh_frames --time N [--size WxH] [--cull]
 *       N frames of one turn (yaw = i * MC_ANGLE_FULL / N, pitch = roll = 0, zoom 1, orthographic:
 *       the viewer's mc_view), each mc_clear + mc_mesh_render, timed by the wall clock; prints
 *       "ms per frame (median) X", "cpu ms per frame (median) X" (process CPU time, which leaves out
 *       time spent preempted), "triangles per frame F" (faces of the level), "drawn per frame D" and
 *       "pixels per frame P" (means of mc_mesh_stats.drawn and .pixels)
 *   mesh_frames --frames N [--size WxH] [--cull]
 *       the same frames untimed, for valgrind --tool=callgrind --toggle-collect=mc_mesh_render;
 *       prints "frames N" and "faces per frame F"
 *   mesh_frames --ppm FILE [--mask FILE] [--yaw U] [--size WxH] [--cull]
 *       the frame at yaw U (angle units, default 0 = frontal) as a binary PPM through mc_target_rgb
 *       with the mesh's palette and a white background; --mask FILE its coverage as a binary PGM
 *       (255 where the depth is not MC_DEPTH_EMPTY). Either may be given alone, and with --time.
 * --cull: MC_MESH_CULL_BACK. --no-cache: mc_mesh_render without its vertex cache (each face projects
 * its corners; the same images), else with a static one. Sizes up to 1024x1024 (static buffers).
 * Default size 320x240.
 */
/* -include NAME.h comes first: build with -D_POSIX_C_SOURCE=200809L for time.h's clocks */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/mesh_render.h"
#include "modelc/target.h"
#include "timing.h"   /* runtime/front/host: clocks, medians */

#define MAX_SIDE 1024

extern const mc_pmesh PM;

static uint8_t color[MAX_SIDE * MAX_SIDE];
static uint16_t depth[MAX_SIDE * MAX_SIDE];
static uint32_t anc[1u << 22];   /* the ancestor map: V entries of up to 4 bytes */
static mc_xvertex vcache[1u << 22];   /* mc_mesh_render's vertex cache: MC_MESH_CACHE_BYTES(V) */

static mc_view frame_view(int32_t yaw)
{
    mc_view v = mc_view_default();   /* zoom 1, orthographic, as the viewer starts */
    v.yaw = yaw;
    v.pitch = 0;
    v.roll = 0;
    v.zoom = MC_ZOOM_ONE;
    v.projection = MC_ORTHOGRAPHIC;
    return v;
}

static int32_t turn_yaw(int i, int n) { return (int32_t)((int64_t)MC_ANGLE_FULL * i / n); }

static int write_image(const char *path, const mc_target *t, int mask)
{
    static const uint8_t white[3] = {255, 255, 255};
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return -1; }
    fprintf(f, "%s\n%u %u\n255\n", mask ? "P5" : "P6", (unsigned)t->width, (unsigned)t->height);
    for (uint32_t i = 0; i < (uint32_t)t->width * t->height; i++) {
        if (mask) {
            fputc(t->depth[i] != MC_DEPTH_EMPTY ? 255 : 0, f);
        } else {
            uint8_t rgb[3];
            mc_target_rgb(t, i, PM.palette, white, rgb);
            fwrite(rgb, 1, 3, f);
        }
    }
    return fclose(f);
}

static int usage(void)
{
    fprintf(stderr, "usage: mesh_frames --time N | --frames N | --ppm FILE | --mask FILE  "
                    "[--yaw U] [--size WxH] [--cull] [--no-cache]\n");
    return 2;
}

int main(int argc, char **argv)
{
    int time_n = 0, frames_n = 0, w = 320, h = 240;
    unsigned flags = 0;
    long yaw = 0;
    const char *ppm = NULL, *mask = NULL;
    mc_xvertex *cache = vcache;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--cull")) { flags |= MC_MESH_CULL_BACK; continue; }
        if (!strcmp(a, "--no-cache")) { cache = NULL; continue; }
        if (i + 1 >= argc) return usage();
        const char *v = argv[++i];
        if (!strcmp(a, "--time")) time_n = atoi(v);
        else if (!strcmp(a, "--frames")) frames_n = atoi(v);
        else if (!strcmp(a, "--size")) { if (sscanf(v, "%dx%d", &w, &h) != 2) return usage(); }
        else if (!strcmp(a, "--ppm")) ppm = v;
        else if (!strcmp(a, "--mask")) mask = v;
        else if (!strcmp(a, "--yaw")) yaw = atol(v);
        else return usage();
    }
    if (time_n < 0 || frames_n < 0 || (!time_n && !frames_n && !ppm && !mask)) return usage();
    if (w < 1 || h < 1 || w > MAX_SIDE || h > MAX_SIDE) {
        fprintf(stderr, "mesh_frames: size %dx%d beyond 1..%d\n", w, h, MAX_SIDE);
        return 2;
    }
    if (PM.vertices > sizeof anc / sizeof anc[0] || MC_MESH_CACHE_BYTES(PM.vertices) > sizeof vcache) return 2;

    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    mc_pmesh_lod_set(&lod, PM.vertices);   /* the full mesh */
    const mc_target t = {color, depth, (uint16_t)w, (uint16_t)h};
    mc_mesh_stats st;

    if (frames_n) {   /* untimed: what callgrind counts (mc_mesh_render only) */
        for (int i = 0; i < frames_n; i++) {
            const mc_view v = frame_view(turn_yaw(i, frames_n));
            mc_clear(&t);
            if (mc_mesh_render(&lod, &v, flags, &t, cache, &st) != MC_OK) return 1;
        }
        printf("frames %d\n", frames_n);
        printf("faces per frame %u\n", (unsigned)lod.faces);
    }
    if (time_n) {
        double *ms = malloc((size_t)time_n * sizeof *ms), *cpu = malloc((size_t)time_n * sizeof *cpu);
        if (!ms || !cpu) return 1;
        {   /* warm up: touch the buffers and the mesh once */
            const mc_view v = frame_view(0);
            mc_clear(&t);
            mc_mesh_render(&lod, &v, flags, &t, cache, &st);
        }
        double pixels = 0, drawn = 0;
        for (int i = 0; i < time_n; i++) {
            const mc_view v = frame_view(turn_yaw(i, time_n));
            const double t0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
            mc_clear(&t);
            const int rc = mc_mesh_render(&lod, &v, flags, &t, cache, &st);
            ms[i] = mc_host_now_ms() - t0;
            cpu[i] = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
            if (rc != MC_OK) return 1;
            pixels += st.pixels;
            drawn += st.drawn;
        }
        printf("frames %d size %dx%d%s\n", time_n, w, h, flags ? " cull" : "");
        printf("ms per frame (median) %.4f\n", mc_host_median(ms, (size_t)time_n));
        printf("cpu ms per frame (median) %.4f\n", mc_host_median(cpu, (size_t)time_n));
        printf("triangles per frame %u\n", (unsigned)st.faces);
        printf("drawn per frame %.1f\n", drawn / time_n);
        printf("pixels per frame %.1f\n", pixels / time_n);
        free(ms);
        free(cpu);
    }
    if (ppm || mask) {
        const mc_view v = frame_view((int32_t)yaw);
        mc_clear(&t);
        if (mc_mesh_render(&lod, &v, flags, &t, cache, &st) != MC_OK) return 1;
        long covered = 0;
        for (uint32_t i = 0; i < (uint32_t)w * h; i++) covered += depth[i] != MC_DEPTH_EMPTY;
        printf("image yaw %ld: faces %u drawn %u skipped %u pixels %u covered %ld\n", yaw, (unsigned)st.faces,
               (unsigned)st.drawn, (unsigned)st.skipped, (unsigned)st.pixels, covered);
        if (ppm && write_image(ppm, &t, 0)) return 1;
        if (mask && write_image(mask, &t, 1)) return 1;
    }
    return 0;
}
