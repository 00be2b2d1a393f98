/* The modelc side of the filled-triangle benchmark (tests/bench/mesh.sh): mc_mesh_render drawing a
 * bake's progressive mesh at its full level of detail, one full turn of frames, against Mesa's
 * llvmpipe drawing the same triangles (tests/bench/osmesa_mesh.c). Built like pmesh_lod.c:
 * -DPM=mc_pmesh_NAME -include NAME.h, the bake's .c files, all of runtime/src and
 * runtime/front/common/mesh_frame.c, -Iruntime/include -Iruntime/front/host (timing.h)
 * -Iruntime/front/common (mesh_frame.h).
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
 *
 * --style lines: the line drawing instead (the line-drawing benchmark of mesh.sh): each frame is
 * mc_front_mesh_frame(..., MC_FRONT_LINES, ...) (runtime/front/common/mesh_frame.c with its sparse
 * depth buffer: the target made paper, the silhouettes, creases and borders offered to the buffer,
 * then the faces, back faces culled when the part is closed, emptying the line pixels they hide:
 * mc_mesh_lines_sparse), with a static mc_mesh_lines memory of MC_MESH_LINES_BYTES(faces)
 * (uint32-aligned, zeroed at the start), static sparse depth buffer bits and the static vertex cache
 * (--no-cache: none); --cull is ignored (the frame decides). Before the frames
 * (untimed, and outside mc_front_mesh_frame, so callgrind's --toggle-collect=mc_front_mesh_frame
 * leaves it out) one frame at yaw 0 is drawn by mc_mesh_render + mc_mesh_lines directly: it warms
 * the buffers and computes the level's crease bits, which mc_mesh_lines keeps while the level is
 * unchanged (every frame here is at the full level). Then
 *   --time N   also prints "lines per frame L" (mean of silhouettes + creases + borders of
 *              mc_lines_stats: the edges drawn, or skipped at the near plane), "silhouettes per
 *              frame", "creases per frame", "borders per frame", "skipped per frame", "line pixels
 *              per frame P" (mean of mc_lines_stats.pixels: the lines' pixels before the depth
 *              test) and "lines total T" (summed over the turn: tests/bench/osmesa_mesh.c --style
 *              lines --time N must find the same number)
 *   --frames N prints "lines per frame L" as well; with --step S the frames after the first
 *              alternate between the level and the one S splits finer (coarser where that passes
 *              the full mesh), set outside mc_front_mesh_frame: every frame but the first draws a
 *              level S splits from the last one's (for callgrind --toggle-collect=mc_mesh_creases_update:
 *              the crease bits brought over, mesh_lines.h)
 *   --ppm      the drawing (paper, black silhouettes, grey creases, blue borders); --mask FILE 255
 *              where a pixel holds a line's colour (MC_LINES_SILHOUETTE_COLOR .. BORDER_COLOR)
 *
 * --near N (the vertex cache on; --style is then ignored): what a hierarchy could spare the face pass
 * (tests/bench/cone_groups.sh). N frames of the turn, each drawn by mc_mesh_lines_sparse with
 * MC_LINES_NO_HIDING (every line pixel offered, none hidden), then the faces the face pass visits (a
 * closed part's front faces, mc_mesh_facing; else all) set against those pixels: per frame, "visited",
 * "meeting" (the box of pixel centres holds one, as the face pass tests it; a face with a flagged
 * corner counts), "within D" for D = 1, 2, 4, 8 (one within D pixels of the box of its corners'
 * pixels) and "spared in groups of G" for G = 32, 64, 128 (the faces in the Morton order of their
 * centres, G at a time: a group's visited faces when the box of their corners' pixels holds none),
 * means over the frames.
 *
 * --hiders N (the vertex cache on; --style is then ignored): which faces a line drawing's face pass
 * needs (tests/bench/cone_groups.sh). N frames of the turn (N <= 1024), each's line pixels offered
 * with MC_LINES_NO_HIDING, then the face pass done here face by face in its order (a closed part's
 * front faces, else all; the box of pixel centres tested, then mc_raster_triangle_hide_box, or the
 * clipped fan for a face with a flagged corner): a face is a hider when it empties an entry. Visiting
 * only the frame's hiders, in the same order, empties the same entries (every other face emptied
 * none, and none of them changed what a later face meets); so does any set that holds them, so
 * the union of the hiders of W neighbouring frames serves each of them. Each frame's entries left
 * are checked against mc_mesh_lines_sparse's own face pass (the same bits, or the run fails). Prints
 * per frame "visited", "meeting", "hiders", the line pixels offered and hidden, the visited faces
 * with a corner on a line (an end of an edge drawn: ring 1) and with a corner on such a face (ring 2)
 * and the hiders of each ring; and "union over W" for W = 1, 4, 16, 64 frames: the mean size of the
 * union of the hiders of W consecutive frames (the turn cut into such windows).
 */
/* -include NAME.h comes first: build with -D_POSIX_C_SOURCE=200809L for time.h's clocks */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/mesh_lines.h"
#include "modelc/mesh_render.h"
#include "modelc/finish.h"     /* MC_DEPTH_FILLED (--near) */
#include "modelc/raster.h"
#include "modelc/sdepth.h"
#include "modelc/target.h"
#include "mesh_frame.h"   /* runtime/front/common: mc_front_mesh_frame */
#include "timing.h"       /* runtime/front/host: clocks, medians */
#include "turn.h"         /* tests/bench: the views of the turn */

#define MAX_SIDE 1024

extern const mc_pmesh PM;

static uint8_t color[MAX_SIDE * MAX_SIDE];
static uint16_t depth[MAX_SIDE * MAX_SIDE];
static uint32_t anc[1u << 22];   /* the ancestor map: V entries of up to 4 bytes */
static mc_xvertex vcache[1u << 22];   /* mc_mesh_render's vertex cache: MC_MESH_CACHE_BYTES(V) */
#define MAX_FACES (1u << 23)
/* mc_mesh_lines' memory (--style lines): MC_MESH_LINES_BYTES(F), uint32-aligned */
static uint32_t lines_mem[(MC_MESH_LINES_BYTES(MAX_FACES) + 3u) / 4u];
static uint8_t nbr[MC_PMESH_NEIGHBOUR_BYTES(MAX_FACES, 4)];   /* --neighbours: the level's neighbour table */
/* the sparse depth buffer's bits (the lines style's hidden-line removal, mesh_frame.h) */
static uint32_t sdepth_bits[MC_SDEPTH_WORDS(MAX_SIDE, MAX_SIDE)];

static int is_line_color(uint8_t c)
{
    return c == MC_LINES_SILHOUETTE_COLOR || c == MC_LINES_CREASE_COLOR || c == MC_LINES_BORDER_COLOR;
}

static int write_image(const char *path, const mc_target *t, int mask, int lines)
{
    static const uint8_t white[3] = {255, 255, 255};
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return -1; }
    fprintf(f, "%s\n%u %u\n255\n", mask ? "P5" : "P6", (unsigned)t->width, (unsigned)t->height);
    for (uint32_t i = 0; i < (uint32_t)t->width * t->height; i++) {
        if (mask && lines) {
            fputc(is_line_color(t->color[i]) ? 255 : 0, f);
        } else if (mask) {
            fputc(t->depth[i] != MC_DEPTH_EMPTY ? 255 : 0, f);
        } else {
            uint8_t rgb[3];
            mc_target_rgb(t, i, PM.palette, white, rgb);
            fwrite(rgb, 1, 3, f);
        }
    }
    return fclose(f);
}

/* --style lines: see the header */
static int lines_main(mc_pmesh_lod *lod, const mc_target *t, mc_xvertex *cache, int time_n, int frames_n,
                      const char *ppm, const char *mask, long yaw, long step)
{
    /* --step: S splits finer, or coarser where that passes the full mesh (below the base: the base) */
    const uint32_t n0 = lod->level, s = (uint32_t)step;
    const uint32_t n1 = n0 + s <= PM.vertices ? n0 + s : n0 > s ? n0 - s : 0u;
    uint8_t *mem = (uint8_t *)lines_mem;
    memset(lines_mem, 0, MC_MESH_LINES_BYTES(PM.faces));
    mc_front_mesh_stats st;
    {   /* warm up, outside mc_front_mesh_frame: buffers, and the level's crease bits */
        const mc_view v = bench_turn_view(0);
        const unsigned cull = PM.closed ? MC_MESH_CULL_BACK : 0u;
        mc_clear(t);
        if (mc_mesh_render(lod, &v, cull | MC_MESH_DRAW_PAPER, t, cache, &st.faces) != MC_OK ||
            mc_mesh_lines(lod, &v, MC_LINES_ALL, t, mem, cache, &st.lines) != MC_OK)
            return 1;
    }
    if (frames_n) {   /* untimed: what callgrind counts (mc_front_mesh_frame only) */
        double nl = 0;
        for (int i = 0; i < frames_n; i++) {
            const mc_view v = bench_turn_view(bench_turn_yaw(i, frames_n));
            if (step) mc_pmesh_lod_set(lod, i & 1 ? n1 : n0);
            if (mc_front_mesh_frame(lod, mem, cache, sdepth_bits, &v, MC_FRONT_LINES, t, &st) != MC_OK) return 1;
            nl += (double)st.lines.silhouettes + st.lines.creases + st.lines.borders;
        }
        printf("frames %d style lines closed %u\n", frames_n, (unsigned)PM.closed);
        printf("faces per frame %u\n", (unsigned)lod->faces);
        printf("lines per frame %.1f\n", nl / frames_n);
    }
    if (time_n) {
        double *ms = malloc((size_t)time_n * sizeof *ms), *cpu = malloc((size_t)time_n * sizeof *cpu);
        if (!ms || !cpu) return 1;
        double sil = 0, cre = 0, bor = 0, skip = 0, px = 0, fpx = 0;
        for (int i = 0; i < time_n; i++) {
            const mc_view v = bench_turn_view(bench_turn_yaw(i, time_n));
            const double t0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
            const int rc = mc_front_mesh_frame(lod, mem, cache, sdepth_bits, &v, MC_FRONT_LINES, t, &st);
            ms[i] = mc_host_now_ms() - t0;
            cpu[i] = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
            if (rc != MC_OK) return 1;
            sil += st.lines.silhouettes, cre += st.lines.creases, bor += st.lines.borders;
            skip += st.lines.skipped, px += st.lines.pixels, fpx += st.faces.pixels;
        }
        printf("frames %d size %ux%u style lines closed %u\n", time_n, (unsigned)t->width, (unsigned)t->height,
               (unsigned)PM.closed);
        printf("ms per frame (median) %.4f\n", mc_host_median(ms, (size_t)time_n));
        printf("cpu ms per frame (median) %.4f\n", mc_host_median(cpu, (size_t)time_n));
        printf("triangles per frame %u\n", (unsigned)st.faces.faces);
        printf("face pixels per frame %.1f\n", fpx / time_n);
        printf("lines per frame %.1f\n", (sil + cre + bor) / time_n);
        printf("silhouettes per frame %.1f\n", sil / time_n);
        printf("creases per frame %.1f\n", cre / time_n);
        printf("borders per frame %.1f\n", bor / time_n);
        printf("skipped per frame %.1f\n", skip / time_n);
        printf("line pixels per frame %.1f\n", px / time_n);
        printf("lines total %.0f\n", sil + cre + bor);
        free(ms);
        free(cpu);
    }
    if (ppm || mask) {
        const mc_view v = bench_turn_view((int32_t)yaw);
        if (mc_front_mesh_frame(lod, mem, cache, sdepth_bits, &v, MC_FRONT_LINES, t, &st) != MC_OK) return 1;
        long drawn = 0;
        for (uint32_t i = 0; i < (uint32_t)t->width * t->height; i++) drawn += is_line_color(t->color[i]);
        printf("image yaw %ld style lines: lines %u (silhouettes %u creases %u borders %u skipped %u) "
               "line pixels %u shown %ld\n", yaw,
               (unsigned)(st.lines.silhouettes + st.lines.creases + st.lines.borders), (unsigned)st.lines.silhouettes,
               (unsigned)st.lines.creases, (unsigned)st.lines.borders, (unsigned)st.lines.skipped,
               (unsigned)st.lines.pixels, drawn);
        if (ppm && write_image(ppm, t, 0, 1)) return 1;
        if (mask && write_image(mask, t, 1, 1)) return 1;
    }
    return 0;
}

/* --near N: N frames of the turn, each's line pixels before any is hidden (mc_mesh_lines_sparse with
 * MC_LINES_NO_HIDING, into the sparse buffer) set against the faces the face pass visits (a closed
 * part's front faces, else all): see the header. */
static uint32_t morton_of[MAX_FACES], face_order[MAX_FACES];
static int by_morton(const void *a, const void *b)
{
    const uint32_t x = morton_of[*(const uint32_t *)a], y = morton_of[*(const uint32_t *)b];
    return x < y ? -1 : x > y;
}
static uint32_t spread10(uint32_t v)   /* the 10 bits of v to every third bit */
{
    v &= 0x3FFu;
    v = (v | v << 16) & 0x030000FFu;
    v = (v | v << 8) & 0x0300F00Fu;
    v = (v | v << 4) & 0x030C30C3u;
    return (v | v << 2) & 0x09249249u;
}
/* face f's pixel box (x0, x1, y0, y1: the pixels holding its corners' 1/16-pixel positions);
 * 0 when a corner is flagged (its box unknown: counted as near a line) */
static int pixel_box(const mc_pmesh_lod *lod, const mc_xvertex *cache, uint32_t f, int32_t b[4])
{
    uint32_t c[3];
    mc_pmesh_lod_face(lod, f, c);
    b[0] = b[2] = INT32_MAX, b[1] = b[3] = INT32_MIN;
    for (int k = 0; k < 3; k++) {
        const mc_xvertex *e = &cache[c[k]];
        if (e->flags) return 0;
        const int32_t px = e->x >> 4, py = e->y >> 4;
        b[0] = px < b[0] ? px : b[0], b[1] = px > b[1] ? px : b[1], b[2] = py < b[2] ? py : b[2], b[3] = py > b[3] ? py : b[3];
    }
    return 1;
}

/* Whether a line pixel of sd lies in box b grown by d pixels (clamped to the frame). */
static int line_near(const mc_sdepth *sd, const int32_t b[4], int32_t d)
{
    const int32_t x0 = b[0] - d < 0 ? 0 : b[0] - d, y0 = b[2] - d < 0 ? 0 : b[2] - d;
    const int32_t x1 = b[1] + d > sd->width - 1 ? sd->width - 1 : b[1] + d;
    const int32_t y1 = b[3] + d > sd->height - 1 ? sd->height - 1 : b[3] + d;
    return x0 <= x1 && y0 <= y1 && mc_sdepth_any(sd, (uint32_t)x0, (uint32_t)x1, (uint32_t)y0, (uint32_t)y1);
}
static int near_main(mc_pmesh_lod *lod, const mc_target *t, mc_xvertex *cache, int frames_n)
{
    enum { DS = 4, GS = 3 };
    static const int dist[DS] = {1, 2, 4, 8};
    static const uint32_t group[GS] = {32, 64, 128};
    uint8_t *mem = (uint8_t *)lines_mem;
    static uint8_t facing[MAX_FACES / 8 + 1];
    memset(lines_mem, 0, MC_MESH_LINES_BYTES(PM.faces));
    /* the faces in the Morton order of their centres (the level's corners' positions, 10 bits an axis) */
    for (uint32_t f = 0; f < lod->faces; f++) {
        uint32_t c[3];
        int32_t sum[3] = {0, 0, 0};
        mc_pmesh_lod_face(lod, f, c);
        for (int k = 0; k < 3; k++) {
            int32_t p[3];
            mc_pmesh_position(&PM, c[k], p);
            for (int a = 0; a < 3; a++) sum[a] += p[a];
        }
        uint32_t m = 0;
        for (int a = 0; a < 3; a++) m |= spread10((uint32_t)(sum[a] / 3 + 32768) >> 6) << a;
        morton_of[f] = m, face_order[f] = f;
    }
    qsort(face_order, lod->faces, sizeof face_order[0], by_morton);
    double visited = 0, meets = 0, near[DS] = {0}, spared[GS] = {0};
    for (int i = 0; i < frames_n; i++) {
        const mc_view v = bench_turn_view(bench_turn_yaw(i, frames_n));
        mc_sdepth sd;
        mc_lines_stats ls;
        if (mc_sdepth_init(&sd, t->width, t->height, sdepth_bits, t->depth, t->color, MC_DEPTH_FILLED, MC_MESH_PAPER) ||
            mc_mesh_lines_sparse(lod, &v, MC_LINES_ALL | MC_LINES_NO_HIDING, &sd, mem, cache, &ls) != MC_OK)
            return 1;
        mc_xform x;
        mc_xform_init(&x, &v, t->width, t->height);
        mc_mesh_facing(lod, &x, facing);
        for (uint32_t f = 0; f < lod->faces; f++) {
            if (PM.closed && !((facing[f >> 3] >> (f & 7u)) & 1u)) continue;
            visited++;
            uint32_t c[3];
            mc_pmesh_lod_face(lod, f, c);
            const mc_xvertex *a = &cache[c[0]], *b = &cache[c[1]], *e = &cache[c[2]];
            int32_t box[4];
            if (a->flags | b->flags | e->flags) {   /* (the face pass clips it: counted as meeting) */
                meets++;
                for (int k = 0; k < DS; k++) near[k]++;
                continue;
            }
            int32_t i0, i1, j0, j1;
            if (mc_raster_centre_run_inside(a->y, b->y, e->y, t->height, &j0, &j1) &&
                mc_raster_centre_run_inside(a->x, b->x, e->x, t->width, &i0, &i1) &&
                mc_sdepth_any(&sd, (uint32_t)i0, (uint32_t)i1, (uint32_t)j0, (uint32_t)j1))
                meets++;
            pixel_box(lod, cache, f, box);
            for (int k = 0; k < DS; k++) near[k] += line_near(&sd, box, dist[k]);
        }
        for (int g = 0; g < GS; g++)
            for (uint32_t s0 = 0; s0 < lod->faces; s0 += group[g]) {
                int32_t u[4] = {INT32_MAX, INT32_MIN, INT32_MAX, INT32_MIN};
                uint32_t n = 0;
                int flagged = 0;
                for (uint32_t s = s0; s < s0 + group[g] && s < lod->faces; s++) {
                    const uint32_t f = face_order[s];
                    if (PM.closed && !((facing[f >> 3] >> (f & 7u)) & 1u)) continue;
                    int32_t box[4];
                    n++;
                    if (!pixel_box(lod, cache, f, box)) { flagged = 1; continue; }
                    u[0] = box[0] < u[0] ? box[0] : u[0], u[1] = box[1] > u[1] ? box[1] : u[1];
                    u[2] = box[2] < u[2] ? box[2] : u[2], u[3] = box[3] > u[3] ? box[3] : u[3];
                }
                if (n && !flagged && !line_near(&sd, u, 0)) spared[g] += n;
            }
    }
    printf("near frames %d faces %u closed %u\n", frames_n, (unsigned)lod->faces, (unsigned)PM.closed);
    printf("visited per frame %.1f\n", visited / frames_n);
    printf("meeting per frame %.1f\n", meets / frames_n);
    for (int k = 0; k < DS; k++) printf("within %d per frame %.1f\n", dist[k], near[k] / frames_n);
    for (int g = 0; g < GS; g++) printf("spared in groups of %u per frame %.1f\n", (unsigned)group[g], spared[g] / frames_n);
    return 0;
}

/* --hiders N: the faces of N frames of the turn whose face pass empties an entry: see the header. */
#define MAX_HIDER_FRAMES 1024
static uint32_t hider_frames[MAX_FACES][MAX_HIDER_FRAMES / 32];   /* bit i: a hider in frame i */
static uint32_t used_copy[MC_SDEPTH_WORDS(MAX_SIDE, MAX_SIDE)];
static uint8_t hider_facing[MAX_FACES / 8 + 1];

/* Frame i's line pixels offered to sd, none hidden, with x and hider_facing set for its view. */
static int hiders_lines(mc_pmesh_lod *lod, const mc_target *t, mc_xvertex *cache, int i, int frames_n, mc_sdepth *sd,
                        mc_xform *x, unsigned flags)
{
    const mc_view v = bench_turn_view(bench_turn_yaw(i, frames_n));
    mc_lines_stats ls;
    if (mc_sdepth_init(sd, t->width, t->height, sdepth_bits, t->depth, t->color, MC_DEPTH_FILLED, MC_MESH_PAPER) ||
        mc_mesh_lines_sparse(lod, &v, MC_LINES_ALL | flags, sd, (uint8_t *)lines_mem, cache, &ls) != MC_OK)
        return 1;
    mc_xform_init(x, &v, t->width, t->height);
    mc_mesh_facing(lod, x, hider_facing);
    return 0;
}

/* Face f of the face pass, as mc_mesh_lines_sparse's (a closed part's back faces culled); returns the
 * entries it empties, *met set when its box holds one (a face with a flagged corner counts). */
static uint32_t hiders_face(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, mc_sdepth *sd,
                            uint32_t f, unsigned cull, int *met)
{
    uint32_t c[3], removed = 0;
    mc_pmesh_lod_face(lod, f, c);
    const mc_xvertex *e[3] = {&cache[c[0]], &cache[c[1]], &cache[c[2]]};
    *met = 0;
    if (e[0]->flags | e[1]->flags | e[2]->flags) {   /* as the face pass: the clipped polygon's fan */
        int32_t p[3][3];
        mc_raster_vertex tri[3], poly[MC_XFORM_CLIP_MAX];
        mc_mesh_face(lod, x, f, p, tri);
        const unsigned n = mc_mesh_clip_face(x, (const int32_t(*)[3])p, poly);
        *met = 1;
        for (unsigned k = 1; k + 1 < n; k++) {
            tri[0] = poly[0], tri[1] = poly[k], tri[2] = poly[k + 1];
            removed += mc_raster_triangle_hide(sd, tri, 0u);
        }
        return removed;
    }
    mc_raster_vertex tri[3];
    mc_raster_box box;
    for (int k = 0; k < 3; k++) tri[k].x = e[k]->x, tri[k].y = e[k]->y, tri[k].z = e[k]->z;
    if (!mc_raster_centres(tri, sd->width, sd->height, &box) ||
        !mc_sdepth_any(sd, (uint32_t)box.i0, (uint32_t)box.i1, (uint32_t)box.j0, (uint32_t)box.j1))
        return 0;
    *met = 1;
    return mc_raster_triangle_hide_box(sd, tri, cull, &box);
}

/* Whether face f hides in one of frames s0 .. s1 - 1. */
static int hider_in(uint32_t f, int s0, int s1)
{
    for (int i = s0; i < s1; i++)
        if ((hider_frames[f][i >> 5] >> (i & 31)) & 1u) return 1;
    return 0;
}

static int hiders_main(mc_pmesh_lod *lod, const mc_target *t, mc_xvertex *cache, int frames_n)
{
    enum { WS = 4 };
    static const int window[WS] = {1, 4, 16, 64};
    static uint8_t ring[MAX_FACES];   /* per vertex of the level: bit 0 ring 1, bit 1 ring 2 */
    memset(lines_mem, 0, MC_MESH_LINES_BYTES(PM.faces));
    const unsigned cull = PM.closed ? MC_RASTER_CULL_BACK : 0u;
    const uint8_t *facing = hider_facing;
    double visited = 0, meets = 0, hiders = 0, offered = 0, hidden = 0, in_ring1 = 0, in_ring2 = 0, hiders1 = 0,
           hiders2 = 0;
    for (int i = 0; i < frames_n; i++) {
        mc_sdepth sd;
        mc_xform x;
        if (hiders_lines(lod, t, cache, i, frames_n, &sd, &x, MC_LINES_NO_HIDING)) return 1;
        const uint32_t offered_now = sd.in_use;
        /* ring 1: the ends of the edges drawn (as osmesa_mesh lists them); ring 2: the corners of the
         * faces with one */
        memset(ring, 0, PM.vertices);
        for (uint32_t f = 0; f < lod->faces; f++)
            for (uint32_t k = 0; k < 3; k++) {
                const uint32_t hh = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, hh);
                if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;
                if (!(mc_mesh_edge_kind(lod, facing, hh, o) & MC_LINES_ALL)) continue;
                uint32_t c[3];
                mc_pmesh_lod_face(lod, f, c);
                ring[c[k]] = ring[c[(k + 1) % 3]] = 1;
            }
        for (uint32_t f = 0; f < lod->faces; f++) {
            uint32_t c[3];
            mc_pmesh_lod_face(lod, f, c);
            if ((ring[c[0]] | ring[c[1]] | ring[c[2]]) & 1u)
                for (int k = 0; k < 3; k++) ring[c[k]] |= 2u;
        }
        for (uint32_t f = 0; f < lod->faces; f++) {
            if (cull && !((facing[f >> 3] >> (f & 7u)) & 1u)) continue;
            int met;
            const uint32_t removed = hiders_face(lod, &x, cache, &sd, f, cull, &met);
            uint32_t c[3];
            mc_pmesh_lod_face(lod, f, c);
            const unsigned rg = ring[c[0]] | ring[c[1]] | ring[c[2]];
            visited++, meets += met, in_ring1 += rg & 1u, in_ring2 += (rg & 2u) != 0;
            if (removed) {
                hiders++, hider_frames[f][i >> 5] |= UINT32_C(1) << (i & 31);
                hiders1 += rg & 1u, hiders2 += (rg & 2u) != 0;
            }
        }
        offered += offered_now, hidden += offered_now - sd.in_use;
    }
    /* Each frame's entries left: the face pass's own (mc_mesh_lines_sparse); the same when only the
     * frame's hiders are visited, and when those of its 16-frame window are. */
    for (int i = 0; i < frames_n; i++) {
        mc_sdepth sd;
        mc_xform x;
        if (hiders_lines(lod, t, cache, i, frames_n, &sd, &x, 0)) return 1;
        const size_t words = (size_t)sd.height * sd.blocks;
        memcpy(used_copy, sd.used, words * sizeof *sd.used);
        for (int w = 0; w < 2; w++) {
            const int s0 = w ? i - i % 16 : i, s1 = w ? (s0 + 16 < frames_n ? s0 + 16 : frames_n) : i + 1;
            if (hiders_lines(lod, t, cache, i, frames_n, &sd, &x, MC_LINES_NO_HIDING)) return 1;
            for (uint32_t f = 0; f < lod->faces; f++) {
                int met;
                if ((!cull || ((facing[f >> 3] >> (f & 7u)) & 1u)) && hider_in(f, s0, s1))
                    hiders_face(lod, &x, cache, &sd, f, cull, &met);
            }
            if (memcmp(used_copy, sd.used, words * sizeof *sd.used)) {
                fprintf(stderr, "mesh_frames --hiders: frame %d: the entries left with %s differ from the face pass's\n", i,
                        w ? "its window's hiders" : "its hiders only");
                return 1;
            }
        }
    }
    printf("hiders frames %d faces %u closed %u\n", frames_n, (unsigned)lod->faces, (unsigned)PM.closed);
    printf("visited per frame %.1f\n", visited / frames_n);
    printf("meeting per frame %.1f\n", meets / frames_n);
    printf("hiders per frame %.1f\n", hiders / frames_n);
    printf("line pixels offered per frame %.1f\n", offered / frames_n);
    printf("line pixels hidden per frame %.1f\n", hidden / frames_n);
    printf("ring 1 per frame %.1f\n", in_ring1 / frames_n);
    printf("ring 2 per frame %.1f\n", in_ring2 / frames_n);
    printf("hiders in ring 1 per frame %.1f\n", hiders1 / frames_n);
    printf("hiders in ring 2 per frame %.1f\n", hiders2 / frames_n);
    for (int w = 0; w < WS; w++) {
        double sum = 0;
        int n = 0;
        for (int s0 = 0; s0 + window[w] <= frames_n; s0 += window[w], n++)
            for (uint32_t f = 0; f < lod->faces; f++) sum += hider_in(f, s0, s0 + window[w]);
        if (n) printf("union over %d per window %.1f\n", window[w], sum / n);
    }
    return 0;
}

static int usage(void)
{
    fprintf(stderr, "usage: mesh_frames --time N | --frames N | --ppm FILE | --mask FILE  "
                    "[--yaw U] [--size WxH] [--vertices N] [--step S] [--cull] [--no-cache] [--neighbours] [--near N] [--hiders N] "
                    "[--style shaded|lines]\n");
    return 2;
}

int main(int argc, char **argv)
{
    int time_n = 0, frames_n = 0, near_n = 0, hiders_n = 0, w = 320, h = 240, lines = 0, neighbours = 0;
    unsigned flags = 0;
    long vertices = -1;   /* the level: -1 the full mesh */
    long step = 0;        /* --step: splits between the levels --frames alternates */
    long yaw = 0;
    const char *ppm = NULL, *mask = NULL;
    mc_xvertex *cache = vcache;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--cull")) { flags |= MC_MESH_CULL_BACK; continue; }
        if (!strcmp(a, "--no-cache")) { cache = NULL; continue; }
        if (!strcmp(a, "--neighbours")) { neighbours = 1; continue; }
        if (i + 1 >= argc) return usage();
        const char *v = argv[++i];
        if (!strcmp(a, "--time")) time_n = atoi(v);
        else if (!strcmp(a, "--frames")) frames_n = atoi(v);
        else if (!strcmp(a, "--near")) near_n = atoi(v);
        else if (!strcmp(a, "--hiders")) hiders_n = atoi(v);
        else if (!strcmp(a, "--size")) { if (sscanf(v, "%dx%d", &w, &h) != 2) return usage(); }
        else if (!strcmp(a, "--ppm")) ppm = v;
        else if (!strcmp(a, "--mask")) mask = v;
        else if (!strcmp(a, "--yaw")) yaw = atol(v);
        else if (!strcmp(a, "--vertices")) vertices = atol(v);
        else if (!strcmp(a, "--step")) { if ((step = atol(v)) < 0) return usage(); }
        else if (!strcmp(a, "--style")) {
            if (!strcmp(v, "lines")) lines = 1;
            else if (strcmp(v, "shaded")) return usage();
        } else return usage();
    }
    if (time_n < 0 || frames_n < 0 || near_n < 0 || hiders_n < 0 || hiders_n > MAX_HIDER_FRAMES ||
        (!time_n && !frames_n && !near_n && !hiders_n && !ppm && !mask))
        return usage();
    if (w < 1 || h < 1 || w > MAX_SIDE || h > MAX_SIDE) {
        fprintf(stderr, "mesh_frames: size %dx%d beyond 1..%d\n", w, h, MAX_SIDE);
        return 2;
    }
    if (PM.vertices > sizeof anc / sizeof anc[0] || MC_MESH_CACHE_BYTES(PM.vertices) > sizeof vcache ||
        PM.faces > MAX_FACES)
        return 2;

    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    if (vertices > (long)PM.vertices) vertices = (long)PM.vertices;
    mc_pmesh_lod_set(&lod, vertices < 0 ? PM.vertices : (uint32_t)vertices);   /* (below the base: the base) */
    if (neighbours) mc_pmesh_lod_neighbours(&lod, nbr);   /* the level's neighbours kept in a table (pmesh.h) */
    const mc_target t = {color, depth, (uint16_t)w, (uint16_t)h};
    mc_mesh_stats st;
    if (step && (!lines || step >= (long)PM.vertices - (long)PM.base_vertices)) return usage();
    if (near_n) return cache ? near_main(&lod, &t, cache, near_n) : usage();
    if (hiders_n) return cache ? hiders_main(&lod, &t, cache, hiders_n) : usage();
    if (lines) return lines_main(&lod, &t, cache, time_n, frames_n, ppm, mask, yaw, step);

    if (frames_n) {   /* untimed: what callgrind counts (mc_mesh_render only) */
        for (int i = 0; i < frames_n; i++) {
            const mc_view v = bench_turn_view(bench_turn_yaw(i, frames_n));
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
            const mc_view v = bench_turn_view(0);
            mc_clear(&t);
            mc_mesh_render(&lod, &v, flags, &t, cache, &st);
        }
        double pixels = 0, drawn = 0;
        for (int i = 0; i < time_n; i++) {
            const mc_view v = bench_turn_view(bench_turn_yaw(i, time_n));
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
        const mc_view v = bench_turn_view((int32_t)yaw);
        mc_clear(&t);
        if (mc_mesh_render(&lod, &v, flags, &t, cache, &st) != MC_OK) return 1;
        long covered = 0;
        for (uint32_t i = 0; i < (uint32_t)w * h; i++) covered += depth[i] != MC_DEPTH_EMPTY;
        printf("image yaw %ld: faces %u drawn %u skipped %u pixels %u covered %ld\n", yaw, (unsigned)st.faces,
               (unsigned)st.drawn, (unsigned)st.skipped, (unsigned)st.pixels, covered);
        if (ppm && write_image(ppm, &t, 0, 0)) return 1;
        if (mask && write_image(mask, &t, 1, 0)) return 1;
    }
    return 0;
}
