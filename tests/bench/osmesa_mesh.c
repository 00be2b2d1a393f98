/* The Mesa side of the filled-triangle benchmark (tests/bench/mesh.sh): Mesa's software OpenGL
 * (OSMesa, llvmpipe; run with LP_NUM_THREADS=0 for one thread) drawing the triangles mc_mesh_render
 * draws (tests/bench/mesh_frames.c): a bake's progressive mesh at its full level, flat-shaded in the
 * same palette entries.
 *
 * Built with -DPM=mc_pmesh_NAME -include NAME.h, the bake's .c files and all of runtime/src (with
 * -ffunction-sections -Wl,--gc-sections: mc_mesh_shade gives each face the palette index
 * mc_mesh_render gives it; --style lines takes the edge list from mesh_lines.c); it never calls
 * mc_mesh_render or mc_mesh_lines. The faces of the full level are decoded once
 * (mc_pmesh_lod_face, mc_pmesh_position; unit-cube coordinates q / 65536 in double, exact in float)
 * and uploaded into a vertex buffer, three unshared vertices per face with the face's flat colour.
 * The view matches modelc's orthographic projection (modelc/xform.h): the bounding cube centred,
 * its side spanning the shorter screen side at zoom 1, screen y down (GL window rows are bottom-up;
 * images are flipped on output), +z toward the viewer, R = Rz(roll) * Rx(pitch) * Ry(yaw) with
 * pitch = roll = 0 here; depth test GL_LESS on a 16-bit depth buffer, as modelc's.
 *
 *   osmesa_mesh [--time N] [--size WxH] [--cull] [--ppm FILE] [--mask FILE] [--yaw U] [--style shaded|lines]
 *
 * --time N    N frames of one turn (yaw = i * 4096 / N modelc angle units, as mesh_frames --time):
 *             glClear + glDrawArrays(GL_TRIANGLES) + glFinish each; prints the median wall-clock
 *             time and the median CPU time of the process per frame
 * --cull      glCullFace(GL_BACK) with counter-clockwise front faces: the faces MC_MESH_CULL_BACK
 *             culls (pmesh.h stores corners counter-clockwise seen from outside). Observed with Mesa
 *             22.3.6 llvmpipe: with culling on, drawing the faces of a buffer that holds exactly them
 *             took about 4x the CPU time (much of it in the kernel) of the same draw from a buffer
 *             with anything after them, one vertex more will do, for the same pixels (bunny00: 39
 *             against 10 ms); --style lines' buffer has the lines after the faces, so its pre-pass
 *             is the fast case. Without culling the two take the same time.
 * --ppm FILE  the frame at yaw U (--yaw, modelc angle units, default 0 = frontal) as a binary PPM,
 *             white background; --mask FILE its coverage (255 = drawn) as a binary PGM
 * --style lines  the line drawing "the GPU way" (mesh.sh's line-drawing table), against
 *             mc_front_mesh_frame(MC_FRONT_LINES) (tests/bench/mesh_frames.c --style lines). Before
 *             anything is timed, for each frame's view (the N of --time, and the --yaw image) the
 *             edges modelc draws in that frame are listed from the runtime exactly as mc_mesh_lines
 *             enumerates them: mc_mesh_facing for the view, then for each face f and edge k with
 *             o = mc_pmesh_lod_opposite(lod, 4 f + k) none or in a later face, kind =
 *             mc_mesh_edge_kind(...), kept when a silhouette, crease or border (and its face has no
 *             corner the projection flags: mc_mesh_lines skips those); each kept edge becomes two
 *             vertices (its corners' unit-cube positions, as the faces') in its palette colour
 *             (MC_LINES_*_COLOR), alpha 255. The faces (all of the level) go into the vertex buffer
 *             in paper (MC_MESH_PAPER) with alpha 0, then every frame's lines after them: one upload.
 *             Timed per frame: glClear (paper, alpha 0) + the depth pre-pass glDrawArrays(GL_TRIANGLES)
 *             of all faces with glPolygonOffset(1, 1) on GL_POLYGON_OFFSET_FILL (lines lying on a
 *             face pass) and back faces culled when the part is closed (pmesh.h closed: as
 *             mc_front_mesh_frame; --cull is then ignored) + glDrawArrays(GL_LINES) of the frame's
 *             edges + glFinish; depth test GL_LEQUAL for both. Prints "lines total T" (over the N
 *             frames: mesh_frames --style lines --time N prints the same count), "lines per frame" and
 *             "edge list ms per frame (median) X": the wall-clock time the listing of one frame's edges
 *             took on the CPU (not part of the timed frame: what an application without the edge list
 *             would spend finding it the runtime's way); --mask FILE is then 255 where a line was
 *             drawn (alpha), --ppm the drawing.
 */
/* -include NAME.h comes first: build with -D_POSIX_C_SOURCE=200809L for time.h's clocks */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/mesh_lines.h"    /* the edge list of --style lines: mc_mesh_facing, mc_mesh_edge_kind */
#include "modelc/mesh_render.h"   /* mc_mesh_shade, mc_mesh_face */
#include "modelc/pmesh.h"
#include "osmesa_start.h"   /* tests/bench: the context, and what it is */
#include "timing.h"               /* runtime/front/host: clocks, medians */
#include "turn.h"                 /* tests/bench: the views of the turn mesh_frames draws */

extern const mc_pmesh PM;

typedef struct vertex {
    float x, y, z;
    uint8_t r, g, b, a;
} vertex;

static uint32_t anc[1u << 22];   /* the ancestor map: V entries of up to 4 bytes */
static int w = 320, h = 240;
static GLsizei nvertices;
/* --style lines: the faces are vertices 0 .. nvertices-1, frame i's lines line_first[i] + line_count[i] */
static int lines_mode;
static GLint *line_first;
static GLsizei *line_count;

/* One frame of the turn at yaw_units (modelc angle units): what is timed. li: the frame's line list
 * (--style lines). */
static void draw_frame(int32_t yaw_units, int li)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    const double s = (w < h ? w : h);   /* zoom 1: cube side = shorter screen side, in pixels */
    glScaled(s, s, s);
    /* R = Rz(roll) * Rx(pitch) * Ry(yaw); roll = pitch = 0 here */
    glRotated(0.0, 0, 0, 1);
    glRotated(0.0, 1, 0, 0);
    glRotated(yaw_units * 360.0 / MC_ANGLE_FULL, 0, 1, 0);
    glDrawArrays(GL_TRIANGLES, 0, nvertices);
    if (lines_mode) glDrawArrays(GL_LINES, line_first[li], line_count[li]);
    glFinish();
}

typedef struct vlist {
    vertex *v;
    size_t n, cap;
} vlist;

static int vpush(vlist *l, vertex x)
{
    if (l->n == l->cap) {
        const size_t cap = l->cap ? 2 * l->cap : 1u << 16;
        vertex *v = realloc(l->v, cap * sizeof *v);
        if (!v) return -1;
        l->v = v, l->cap = cap;
    }
    l->v[l->n++] = x;
    return 0;
}

static vertex unit_vertex(const int32_t p[3], const uint8_t *rgb, uint8_t a)
{
    return (vertex){(float)(p[0] / 65536.0), (float)(p[1] / 65536.0), (float)(p[2] / 65536.0), rgb[0], rgb[1], rgb[2], a};
}

/* Appends the edges mc_mesh_lines draws at the level through yaw's view (see the header) to l;
 * returns how many, or -1. *skipped: edges of a drawn kind left out for a flagged corner. */
static long list_lines(const mc_pmesh_lod *lod, int32_t yaw, uint8_t *facing, vlist *l, long *skipped)
{
    const mc_view view = bench_turn_view(yaw);
    mc_xform x;
    mc_xform_init(&x, &view, (uint32_t)w, (uint32_t)h);
    mc_mesh_facing(lod, &x, facing);
    long n = 0;
    for (uint32_t f = 0; f < lod->faces; f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t hh = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, hh);
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;   /* the earlier face's */
            const unsigned kind = mc_mesh_edge_kind(lod, facing, hh, o);
            if (!(kind & MC_LINES_ALL)) continue;
            int32_t p[3][3];
            mc_raster_vertex rv[3];
            if (mc_mesh_face(lod, &x, f, p, rv)) { ++*skipped; continue; }
            const unsigned c = kind == MC_EDGE_SILHOUETTE ? MC_LINES_SILHOUETTE_COLOR
                               : kind == MC_EDGE_CREASE   ? MC_LINES_CREASE_COLOR
                                                          : MC_LINES_BORDER_COLOR;
            if (c >= PM.palette_size) return -1;
            const uint8_t *rgb = PM.palette + 3 * c;
            if (vpush(l, unit_vertex(p[k], rgb, 255)) || vpush(l, unit_vertex(p[(k + 1) % 3], rgb, 255))) return -1;
            n++;
        }
    return n;
}

/* OSMesa's buffer is bottom-up (GL window rows); images are written top-down like modelc's. */
static int write_image(const char *path, const uint8_t *rgba, int mask)
{
    FILE *f = fopen(path, "wb");
    if (!f) { perror(path); return -1; }
    fprintf(f, "%s\n%d %d\n255\n", mask ? "P5" : "P6", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int x = 0; x < w; x++) {
            const uint8_t *p = rgba + 4 * ((size_t)y * w + x);
            if (mask) {
                fputc(p[3] ? 255 : 0, f);
            } else if (p[3] || lines_mode) {   /* lines: the paper is drawn (cleared) paper */
                fputc(p[0], f); fputc(p[1], f); fputc(p[2], f);
            } else {
                fputc(255, f); fputc(255, f); fputc(255, f);   /* mesh_frames' white background */
            }
        }
    return fclose(f);
}

int main(int argc, char **argv)
{
    int frames = 0, cull = 0;
    long yaw = 0;
    const char *ppm = NULL, *mask = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--cull")) { cull = 1; continue; }
        if (i + 1 >= argc) { fprintf(stderr, "osmesa_mesh: %s needs a value\n", a); return 2; }
        const char *v = argv[++i];
        if (!strcmp(a, "--time")) frames = atoi(v);
        else if (!strcmp(a, "--size")) { if (sscanf(v, "%dx%d", &w, &h) != 2) return 2; }
        else if (!strcmp(a, "--ppm")) ppm = v;
        else if (!strcmp(a, "--mask")) mask = v;
        else if (!strcmp(a, "--yaw")) yaw = atol(v);
        else if (!strcmp(a, "--style") && !strcmp(v, "lines")) lines_mode = 1;
        else if (!strcmp(a, "--style") && !strcmp(v, "shaded")) lines_mode = 0;
        else { fprintf(stderr, "osmesa_mesh: unknown option %s\n", a); return 2; }
    }
    if (frames < 0 || w < 1 || h < 1 || w > 4096 || h > 4096) return 2;
    if (!frames && !ppm && !mask) {
        fprintf(stderr, "usage: osmesa_mesh --time N | --ppm FILE | --mask FILE  [--yaw U] [--size WxH] [--cull] "
                        "[--style shaded|lines]\n");
        return 2;
    }
    if (PM.vertices > sizeof anc / sizeof anc[0]) return 2;

    /* the full level's faces, three vertices each, in stored face order */
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    mc_pmesh_lod_set(&lod, PM.vertices);
    const uint32_t faces = lod.faces;
    if (lines_mode) cull = PM.closed;   /* as mc_front_mesh_frame */
    vertex *vb = malloc((size_t)faces * 3 * sizeof *vb);
    if (!vb || MC_MESH_PAPER >= PM.palette_size) return 1;
    for (uint32_t f = 0; f < faces; f++) {
        uint32_t c[3];
        int32_t p[3][3];
        mc_pmesh_lod_face(&lod, f, c);
        for (int k = 0; k < 3; k++) mc_pmesh_position(&PM, c[k], p[k]);
        const unsigned shade = mc_mesh_shade(p[0], p[1], p[2]);
        if (shade >= PM.palette_size) return 1;
        const uint8_t *rgb = PM.palette + 3 * (lines_mode ? MC_MESH_PAPER : shade);
        for (int k = 0; k < 3; k++) vb[3 * f + k] = unit_vertex(p[k], rgb, lines_mode ? 0 : 255);
    }
    nvertices = (GLsizei)(3 * faces);
    /* --style lines: every frame's edge list (frames 0 .. frames-1 of the turn, then the image's) */
    vlist all = {vb, 3 * (size_t)faces, 3 * (size_t)faces};
    long lines_total = 0, lines_image = 0, lines_skipped = 0;
    double list_ms = 0;
    if (lines_mode) {
        uint8_t *facing = malloc(MC_MESH_FACING_BYTES(faces) + 1);
        line_first = malloc(((size_t)frames + 1) * sizeof *line_first);
        line_count = malloc(((size_t)frames + 1) * sizeof *line_count);
        double *lms = malloc(((size_t)frames + 1) * sizeof *lms);
        if (!facing || !line_first || !line_count || !lms) return 1;
        for (int i = 0; i <= frames; i++) {
            const int32_t y = i < frames ? bench_turn_yaw(i, frames) : (int32_t)yaw;
            line_first[i] = (GLint)all.n;
            const double t0 = mc_host_now_ms();
            const long n = list_lines(&lod, y, facing, &all, &lines_skipped);
            lms[i] = mc_host_now_ms() - t0;
            if (n < 0) { fprintf(stderr, "osmesa_mesh: listing the lines failed\n"); return 1; }
            line_count[i] = (GLsizei)(2 * n);
            if (i < frames) lines_total += n;
            else lines_image = n;
        }
        list_ms = mc_host_median(lms, (size_t)frames + 1);
        free(lms);
        free(facing);
        vb = all.v;
    }

    uint8_t *buf = osmesa_start("osmesa_mesh", w, h);
    if (!buf) return 1;

    GLuint vbo;
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)all.n * (GLsizeiptr)sizeof *vb, vb, GL_STATIC_DRAW);
    free(vb);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(3, GL_FLOAT, sizeof(vertex), (const void *)0);
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(vertex), (const void *)offsetof(vertex, r));

    glViewport(0, 0, w, h);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    /* pixels, origin at the screen centre (GL window y up; images are flipped on output);
     * eye-space z in [-s, s] covers the bounding sphere, nearer (larger z) = smaller depth */
    const double s = (w < h ? w : h);
    glOrtho(-w / 2.0, w / 2.0, -h / 2.0, h / 2.0, -s, s);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(lines_mode ? GL_LEQUAL : GL_LESS);
    if (lines_mode) {   /* the pre-pass's faces pushed back: lines lying on them pass */
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.0f, 1.0f);
    }
    glShadeModel(GL_FLAT);
    glDisable(GL_DITHER);
    glDisable(GL_LIGHTING);
    if (cull) {
        glEnable(GL_CULL_FACE);
        glFrontFace(GL_CCW);   /* counter-clockwise in GL's y-up window = modelc's front faces */
        glCullFace(GL_BACK);
    } else {
        glDisable(GL_CULL_FACE);
    }
    if (lines_mode)
        glClearColor(PM.palette[3 * MC_MESH_PAPER] / 255.0f, PM.palette[3 * MC_MESH_PAPER + 1] / 255.0f,
                     PM.palette[3 * MC_MESH_PAPER + 2] / 255.0f, 0);
    else
        glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);

    /* warm up: llvmpipe compiles its shaders on the first draws */
    for (int i = 0; i < 3; i++) draw_frame(0, 0);
    if (glGetError() != GL_NO_ERROR) { fprintf(stderr, "osmesa_mesh: GL error\n"); return 1; }

    printf("triangles per frame %u\n", (unsigned)faces);
    printf("closed %u cull %d style %s\n", (unsigned)PM.closed, cull, lines_mode ? "lines" : "shaded");
    if (lines_mode) {
        printf("lines total %ld\n", lines_total);
        printf("lines per frame %.1f\n", frames ? (double)lines_total / frames : 0.0);
        printf("lines skipped %ld\n", lines_skipped);
        printf("lines at the image's yaw %ld\n", lines_image);
        printf("edge list ms per frame (median) %.4f\n", list_ms);
    }
    if (frames) {
        double *ms = malloc((size_t)frames * sizeof *ms), *cpu = malloc((size_t)frames * sizeof *cpu);
        if (!ms || !cpu) return 1;
        for (int i = 0; i < frames; i++) {
            const int32_t y = bench_turn_yaw(i, frames);
            const double t0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
            draw_frame(y, i);
            ms[i] = mc_host_now_ms() - t0;
            cpu[i] = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
        }
        printf("frames %d size %dx%d%s\n", frames, w, h, cull ? " cull" : "");
        printf("ms per frame (median) %.4f\n", mc_host_median(ms, (size_t)frames));
        printf("cpu ms per frame (median) %.4f\n", mc_host_median(cpu, (size_t)frames));
        free(cpu);
        free(ms);
    }
    if (ppm || mask) {
        draw_frame((int32_t)yaw, frames);
        long covered = 0;
        for (size_t i = 0; i < (size_t)w * h; i++) covered += buf[4 * i + 3] != 0;
        printf("image yaw %ld: covered %ld\n", yaw, covered);
        if (ppm && write_image(ppm, buf, 0)) return 1;
        if (mask && write_image(mask, buf, 1)) return 1;
    }
    if (glGetError() != GL_NO_ERROR) { fprintf(stderr, "osmesa_mesh: GL error\n"); return 1; }
    glDeleteBuffers(1, &vbo);
    OSMesaDestroyContext(OSMesaGetCurrentContext());
    free(buf);
    return 0;
}
