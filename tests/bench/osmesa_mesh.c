/* The Mesa side of the filled-triangle benchmark (tests/bench/mesh.sh): Mesa's software OpenGL
 * (OSMesa, llvmpipe; run with LP_NUM_THREADS=0 for one thread) drawing the triangles mc_mesh_render
 * draws (tests/bench/mesh_frames.c): a bake's progressive mesh at its full level, flat-shaded in the
 * same palette entries.
 *
 * Built with -DPM=mc_pmesh_NAME -include NAME.h, the bake's .c files, runtime/src/pmesh.c and
 * runtime/src/mesh_render.c (mc_mesh_shade: each face's palette index is the one mc_mesh_render
 * gives it); it never calls mc_mesh_render. The faces of the full level are decoded once
 * (mc_pmesh_lod_face, mc_pmesh_position; unit-cube coordinates q / 65536 in double, exact in float)
 * and uploaded into a vertex buffer, three unshared vertices per face with the face's flat colour.
 * The view matches modelc's orthographic projection (modelc/xform.h): the bounding cube centred,
 * its side spanning the shorter screen side at zoom 1, screen y down (GL window rows are bottom-up;
 * images are flipped on output), +z toward the viewer, R = Rz(roll) * Rx(pitch) * Ry(yaw) with
 * pitch = roll = 0 here; depth test GL_LESS on a 16-bit depth buffer, as modelc's.
 *
 *   osmesa_mesh [--time N] [--size WxH] [--cull] [--ppm FILE] [--mask FILE] [--yaw U]
 *
 * --time N    N frames of one turn (yaw = i * 4096 / N modelc angle units, as mesh_frames --time):
 *             glClear + glDrawArrays(GL_TRIANGLES) + glFinish each; prints the median wall-clock
 *             time and the median CPU time of the process per frame
 * --cull      glCullFace(GL_BACK) with counter-clockwise front faces: the faces MC_MESH_CULL_BACK
 *             culls (pmesh.h stores corners counter-clockwise seen from outside)
 * --ppm FILE  the frame at yaw U (--yaw, modelc angle units, default 0 = frontal) as a binary PPM,
 *             white background; --mask FILE its coverage (255 = drawn) as a binary PGM
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

#include "modelc/mesh_render.h"   /* mc_mesh_shade only */
#include "modelc/pmesh.h"
#include "timing.h"               /* runtime/front/host: clocks, medians */

#define ANGLE_FULL 4096

extern const mc_pmesh PM;

typedef struct vertex {
    float x, y, z;
    uint8_t r, g, b, a;
} vertex;

static uint32_t anc[1u << 22];   /* the ancestor map: V entries of up to 4 bytes */
static int w = 320, h = 240;
static GLsizei nvertices;

/* One frame of the turn at yaw_units (modelc angle units): what is timed. */
static void draw_frame(int32_t yaw_units)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    const double s = (w < h ? w : h);   /* zoom 1: cube side = shorter screen side, in pixels */
    glScaled(s, s, s);
    /* R = Rz(roll) * Rx(pitch) * Ry(yaw); roll = pitch = 0 here */
    glRotated(0.0, 0, 0, 1);
    glRotated(0.0, 1, 0, 0);
    glRotated(yaw_units * 360.0 / ANGLE_FULL, 0, 1, 0);
    glDrawArrays(GL_TRIANGLES, 0, nvertices);
    glFinish();
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
            } else if (p[3]) {
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
        else { fprintf(stderr, "osmesa_mesh: unknown option %s\n", a); return 2; }
    }
    if (frames < 0 || w < 1 || h < 1 || w > 4096 || h > 4096) return 2;
    if (!frames && !ppm && !mask) {
        fprintf(stderr, "usage: osmesa_mesh --time N | --ppm FILE | --mask FILE  [--yaw U] [--size WxH] [--cull]\n");
        return 2;
    }
    if (PM.vertices > sizeof anc / sizeof anc[0]) return 2;

    /* the full level's faces, three vertices each, in stored face order */
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    mc_pmesh_lod_set(&lod, PM.vertices);
    const uint32_t faces = lod.faces;
    vertex *vb = malloc((size_t)faces * 3 * sizeof *vb);
    if (!vb) return 1;
    for (uint32_t f = 0; f < faces; f++) {
        uint32_t c[3];
        int32_t p[3][3];
        mc_pmesh_lod_face(&lod, f, c);
        for (int k = 0; k < 3; k++) mc_pmesh_position(&PM, c[k], p[k]);
        const unsigned shade = mc_mesh_shade(p[0], p[1], p[2]);
        if (shade >= PM.palette_size) return 1;
        const uint8_t *rgb = PM.palette + 3 * shade;
        for (int k = 0; k < 3; k++)
            vb[3 * f + k] = (vertex){(float)(p[k][0] / 65536.0), (float)(p[k][1] / 65536.0), (float)(p[k][2] / 65536.0),
                                     rgb[0], rgb[1], rgb[2], 255};
    }
    nvertices = (GLsizei)(3 * faces);

    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    if (!ctx) { fprintf(stderr, "osmesa_mesh: OSMesaCreateContextExt failed\n"); return 1; }
    uint8_t *buf = calloc((size_t)w * h, 4);
    if (!buf || !OSMesaMakeCurrent(ctx, buf, GL_UNSIGNED_BYTE, w, h)) {
        fprintf(stderr, "osmesa_mesh: OSMesaMakeCurrent failed\n");
        return 1;
    }
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    const char *lp = getenv("LP_NUM_THREADS");
    printf("renderer: %s\n", (const char *)glGetString(GL_RENDERER));
    printf("version: %s\n", (const char *)glGetString(GL_VERSION));
    printf("LP_NUM_THREADS: %s\n", lp ? lp : "(unset)");
    printf("depth bits: %d\n", depth_bits);

    GLuint vbo;
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)nvertices * (GLsizeiptr)sizeof *vb, vb, GL_STATIC_DRAW);
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
    glDepthFunc(GL_LESS);
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
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);

    /* warm up: llvmpipe compiles its shaders on the first draws */
    for (int i = 0; i < 3; i++) draw_frame(0);
    if (glGetError() != GL_NO_ERROR) { fprintf(stderr, "osmesa_mesh: GL error\n"); return 1; }

    printf("triangles per frame %u\n", (unsigned)faces);
    if (frames) {
        double *ms = malloc((size_t)frames * sizeof *ms), *cpu = malloc((size_t)frames * sizeof *cpu);
        if (!ms || !cpu) return 1;
        for (int i = 0; i < frames; i++) {
            const int32_t y = (int32_t)((int64_t)ANGLE_FULL * i / frames);
            const double t0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
            draw_frame(y);
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
        draw_frame((int32_t)yaw);
        long covered = 0;
        for (size_t i = 0; i < (size_t)w * h; i++) covered += buf[4 * i + 3] != 0;
        printf("image yaw %ld: covered %ld\n", yaw, covered);
        if (ppm && write_image(ppm, buf, 0)) return 1;
        if (mask && write_image(mask, buf, 1)) return 1;
    }
    if (glGetError() != GL_NO_ERROR) { fprintf(stderr, "osmesa_mesh: GL error\n"); return 1; }
    glDeleteBuffers(1, &vbo);
    OSMesaDestroyContext(ctx);
    free(buf);
    return 0;
}
