/* Benchmark baseline: Mesa's software OpenGL (OSMesa) drawing the same cells as a modelc bake.
 *
 * Links against a bake's generated sources (for mc_app_model.model->octree) but not against the runtime's
 * renderer: the cells are decoded by tests/bench/cells.h in double precision and uploaded once into a
 * vertex buffer as one-pixel GL_POINTS with per-point colours (in the order mc_octree_render draws them).
 * The view matches modelc's (modelc/xform.h): orthographic, the model's bounding cube centred with its
 * side spanning the shorter screen side at zoom 1, screen y down, +z toward the viewer,
 * R = Rz(roll) * Rx(pitch) * Ry(yaw); depth test GL_LESS on a 16-bit depth buffer like modelc's.
 *
 *   osmesa_points [--frames N] [--size WxH] [--views K] [--ppm FILE] [--mask FILE]
 *                 [--image-yaw U] [--ply FILE] [--ply-rgb FILE] [--no-bench]
 *                 [--zoom Z] [--perspective] [--footprint]
 *
 * --frames N   time N frames of one full turn (yaw = i * 4096 / N modelc angle units, as the viewer's
 *              --bench does): glClear + glDrawArrays + glFinish each, print the median wall-clock time
 *              and the median CPU time of the process (which leaves out time spent preempted on a
 *              busy machine)
 * --views K    count the pixels drawn in K views of the turn (untimed), print the mean
 * --ppm FILE   write one frame as a binary PPM: yaw U modelc angle units from --image-yaw (default 0,
 *              frontal)
 * --mask FILE  write that frame's coverage (255 = drawn) as a binary PGM
 * --ply FILE   write the cells' integer coordinates as an ASCII PLY point cloud (for draco_encoder);
 *              --ply-rgb FILE the same with the palette colours
 * --zoom Z     modelc's zoom: the cube's side spans Z times the shorter screen side (default 1)
 * --perspective  modelc's perspective (xform.h): the eye 2 cube sides from the model's centre (the default
 *              mc_view eye), screen x = w/2 + S eye q.x / (eye - q.z) with S = zoom * min(w, h), likewise y;
 *              glFrustum with its near and far planes at the model's bounding sphere
 * --footprint  point size = modelc's zoom footprint (MC_SPLAT_ZOOM, octree_render.h) of the bake's leaves:
 *              s = ceil(leaf side on screen), 1..16 pixels, once per frame in orthographic (glPointSize), per
 *              point in perspective (a GLSL 1.20 vertex shader writing gl_PointSize = ceil(side * eye / d)
 *              from the point's eye-space distance); prints "point size: ..."
 * Without these three the program draws and prints exactly what it did before they existed (one-pixel
 * points, zoom 1, orthographic).
 * Run with LP_NUM_THREADS=0 to keep llvmpipe on one thread.
 */
#define _POSIX_C_SOURCE 200809L
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modelc/app.h>
#include "cells.h"
#include "osmesa_start.h"   /* tests/bench: the context, and what it is */
#include "timing.h"   /* runtime/front/host: clocks, medians */

#define ANGLE_FULL 4096
#define EYE 2.0            /* mc_view_default's eye distance, cube sides */
#define HALF_SQRT3 0.8660254037844386
#define SPLAT_MAX 16       /* config.h MC_SPLAT_MAX */

typedef struct vertex {
    float x, y, z;
    uint8_t r, g, b, a;
} vertex;

static int w = 320, h = 240;
static GLsizei npoints;
static double zoom = 1;
static int perspective;

/* S: pixels per cube side (modelc's zoom * min(w, h)) */
static double cube_pixels(void) { return zoom * (w < h ? w : h); }

/* One frame of the turn at `yaw_units` (modelc angle units): what is timed. */
static void draw_frame(int32_t yaw_units)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    double s = cube_pixels();            /* the cube's side in pixels: zoom * shorter screen side */
    if (perspective) glTranslated(0, 0, -s * EYE);   /* the eye EYE cube sides from the centre */
    glScaled(s, s, s);
    /* R = Rz(roll) * Rx(pitch) * Ry(yaw); roll = pitch = 0 here */
    glRotated(0.0, 0, 0, 1);
    glRotated(0.0, 1, 0, 0);
    glRotated(yaw_units * 360.0 / ANGLE_FULL, 0, 1, 0);
    glDrawArrays(GL_POINTS, 0, npoints);
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
                fputc(24, f); fputc(24, f); fputc(32, f);   /* the viewer's background */
            }
        }
    return fclose(f);
}

static long covered(const uint8_t *rgba)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) n += rgba[4 * i + 3] != 0;
    return n;
}

static int write_ply(const char *path, const bench_cell *cells, uint32_t n, const uint8_t *palette, int rgb)
{
    FILE *f = fopen(path, "w");
    if (!f) { perror(path); return -1; }
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %u\nproperty float x\nproperty float y\nproperty float z\n", n);
    if (rgb) fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    fprintf(f, "end_header\n");
    for (uint32_t i = 0; i < n; i++) {
        fprintf(f, "%u %u %u", cells[i].ix, cells[i].iy, cells[i].iz);
        if (rgb) {
            const uint8_t *c = palette + 3 * cells[i].color;
            fprintf(f, " %u %u %u", c[0], c[1], c[2]);
        }
        fputc('\n', f);
    }
    return fclose(f);
}

/* --footprint in perspective: each point's size from its eye-space distance d (pixels, as the modelview
 * above scales): modelc's leaf side at magnification eye / dist, rounded up, 1..SPLAT_MAX. */
static int footprint_shader(double leaf_px)
{
    static const char *vs =
        "#version 120\n"
        "uniform float k;  /* leaf side at the model's centre (pixels) * S * eye */\n"
        "void main() {\n"
        "    vec4 e = gl_ModelViewMatrix * gl_Vertex;\n"
        "    gl_Position = gl_ProjectionMatrix * e;\n"
        "    gl_FrontColor = gl_Color;\n"
        "    gl_PointSize = clamp(ceil(k / -e.z - 1e-4), 1.0, 16.0);  /* SPLAT_MAX */\n"
        "}\n";
    static const char *fs = "#version 120\nvoid main() { gl_FragColor = gl_Color; }\n";
    GLuint prog = glCreateProgram();
    const char *src[2] = {vs, fs};
    const GLenum kinds[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int i = 0; i < 2; i++) {
        GLuint sh = glCreateShader(kinds[i]);
        GLint ok = 0;
        glShaderSource(sh, 1, &src[i], NULL);
        glCompileShader(sh);
        glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[512];
            glGetShaderInfoLog(sh, sizeof log, NULL, log);
            fprintf(stderr, "osmesa_points: shader: %s\n", log);
            return -1;
        }
        glAttachShader(prog, sh);
    }
    GLint ok = 0;
    glLinkProgram(prog);
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) { fprintf(stderr, "osmesa_points: shader program does not link\n"); return -1; }
    glUseProgram(prog);
    glUniform1f(glGetUniformLocation(prog, "k"), (GLfloat)(leaf_px * cube_pixels() * EYE));
    glEnable(GL_VERTEX_PROGRAM_POINT_SIZE);
    return 0;
}

int main(int argc, char **argv)
{
    int frames = 200, views = 20, bench = 1, footprint = 0;
    long image_yaw = 0;
    const char *ppm = NULL, *mask = NULL, *ply = NULL, *ply_rgb = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--no-bench")) { bench = 0; continue; }
        if (!strcmp(a, "--perspective")) { perspective = 1; continue; }
        if (!strcmp(a, "--footprint")) { footprint = 1; continue; }
        if (!v) { fprintf(stderr, "osmesa_points: %s needs a value\n", a); return 2; }
        i++;
        if (!strcmp(a, "--frames")) frames = atoi(v);
        else if (!strcmp(a, "--views")) views = atoi(v);
        else if (!strcmp(a, "--size")) { if (sscanf(v, "%dx%d", &w, &h) != 2) return 2; }
        else if (!strcmp(a, "--ppm")) ppm = v;
        else if (!strcmp(a, "--mask")) mask = v;
        else if (!strcmp(a, "--image-yaw")) image_yaw = atol(v);
        else if (!strcmp(a, "--ply")) ply = v;
        else if (!strcmp(a, "--ply-rgb")) ply_rgb = v;
        else if (!strcmp(a, "--zoom")) { zoom = atof(v); if (!(zoom >= 1.0 / 64 && zoom <= 64)) return 2; }
        else { fprintf(stderr, "osmesa_points: unknown option %s\n", a); return 2; }
    }
    if (frames < 1 || views < 0 || w < 1 || h < 1 || w > 4096 || h > 4096) return 2;

    const mc_octree *scene = mc_app_model.model->octree;
    uint32_t n;
    bench_cell *cells = bench_decode_cells(scene, &n);
    if (!cells) return 1;
    if (ply && write_ply(ply, cells, n, scene->palette, 0)) return 1;
    if (ply_rgb && write_ply(ply_rgb, cells, n, scene->palette, 1)) return 1;
    if (!bench && !ppm && !mask && views == 0) return 0;

    uint8_t *buf = osmesa_start("osmesa_points", w, h);
    if (!buf) return 1;

    vertex *vb = malloc((size_t)n * sizeof *vb);
    if (!vb) return 1;
    for (uint32_t i = 0; i < n; i++) {
        const uint8_t *c = scene->palette + 3 * cells[i].color;
        vb[i] = (vertex){(float)cells[i].x, (float)cells[i].y, (float)cells[i].z, c[0], c[1], c[2], 255};
    }
    npoints = (GLsizei)n;
    GLuint vbo;
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)n * sizeof *vb, vb, GL_STATIC_DRAW);
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
    double s = cube_pixels();
    if (perspective) {
        /* x_window = w/2 + f x_e / d with f = S eye (pixels) and d = -z_e: the frustum's half width at
         * the near plane n is n (w/2) / f; n and f bound the sphere (eye -+ sqrt(3)/2 cube sides) */
        double f = s * EYE, n = s * (EYE - HALF_SQRT3) * 0.99, fa = s * (EYE + HALF_SQRT3) * 1.01;
        glFrustum(-n * w / 2.0 / f, n * w / 2.0 / f, -n * h / 2.0 / f, n * h / 2.0 / f, n, fa);
    } else {
        glOrtho(-w / 2.0, w / 2.0, -h / 2.0, h / 2.0, -s, s);
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_POINT_SMOOTH);
    glDisable(GL_DITHER);
    glPointSize(1.0f);
    if (footprint) {
        /* modelc's zoom footprint of a leaf of the bake's depth: its side S / 2^D pixels, rounded up */
        double leaf = s / (double)(1u << scene->depth);
        if (perspective) {
            if (footprint_shader(leaf)) return 1;
            printf("point size: per point, ceil(%.4f * eye / distance) pixels, 1..%d\n", leaf, SPLAT_MAX);
        } else {
            double size = ceil(leaf - 1e-9);
            size = size < 1 ? 1 : size > SPLAT_MAX ? SPLAT_MAX : size;
            glPointSize((GLfloat)size);
            printf("point size: %.0f\n", size);
        }
    }
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);

    /* warm up: llvmpipe compiles its shaders on the first draws */
    for (int i = 0; i < 3; i++) draw_frame(0);
    if (glGetError() != GL_NO_ERROR) { fprintf(stderr, "osmesa_points: GL error\n"); return 1; }

    printf("points: %u\n", n);
    if (bench) {
        double *ms = malloc((size_t)frames * sizeof *ms), *cpu = malloc((size_t)frames * sizeof *cpu);
        if (!ms || !cpu) return 1;
        for (int i = 0; i < frames; i++) {
            int32_t yaw = (int32_t)((int64_t)ANGLE_FULL * i / frames);
            double t0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID);
            draw_frame(yaw);
            ms[i] = mc_host_now_ms() - t0;
            cpu[i] = mc_host_clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
        }
        double median = mc_host_median(ms, (size_t)frames), cpu_median = mc_host_median(cpu, (size_t)frames);
        printf("frames: %d size %dx%d\n", frames, w, h);
        printf("ms per frame (median): %.3f\n", median);
        printf("cpu ms per frame (median): %.3f\n", cpu_median);
        printf("Mpoints/s: %.2f\n", n / median / 1e3);
        free(cpu);
        free(ms);
    }
    if (views > 0) {
        double sum = 0;
        for (int i = 0; i < views; i++) {
            draw_frame((int32_t)((int64_t)ANGLE_FULL * i / views));
            sum += covered(buf);
        }
        printf("pixels covered per view (mean of %d views): %.0f\n", views, sum / views);
    }
    if (ppm || mask) {
        draw_frame((int32_t)image_yaw);
        printf("pixels covered in the image (yaw %ld units): %ld\n", image_yaw, covered(buf));
        if (ppm && write_image(ppm, buf, 0)) return 1;
        if (mask && write_image(mask, buf, 1)) return 1;
    }
    glDeleteBuffers(1, &vbo);
    OSMesaDestroyContext(OSMesaGetCurrentContext());
    free(buf);
    free(cells);
    return 0;
}
