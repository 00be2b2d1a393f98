/* The Mesa side of the benchmarks (osmesa_points.c, osmesa_mesh.c): one OSMesa context current on a
 * w x h RGBA buffer with a 16-bit depth buffer, and what it is (renderer, version, LP_NUM_THREADS,
 * depth bits) printed first, so that every run says which rasterizer it timed. */
#ifndef MODELC_BENCH_OSMESA_START_H
#define MODELC_BENCH_OSMESA_START_H

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/* The colour buffer of the current context, or NULL after one line on stderr naming prog. */
static uint8_t *osmesa_start(const char *prog, int w, int h)
{
    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    if (!ctx) {
        fprintf(stderr, "%s: OSMesaCreateContextExt failed\n", prog);
        return NULL;
    }
    uint8_t *buf = calloc((size_t)w * h, 4);
    if (!buf || !OSMesaMakeCurrent(ctx, buf, GL_UNSIGNED_BYTE, w, h)) {
        fprintf(stderr, "%s: OSMesaMakeCurrent failed\n", prog);
        return NULL;
    }
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    const char *lp = getenv("LP_NUM_THREADS");
    printf("renderer: %s\n", (const char *)glGetString(GL_RENDERER));
    printf("version: %s\n", (const char *)glGetString(GL_VERSION));
    printf("LP_NUM_THREADS: %s\n", lp ? lp : "(unset)");
    printf("depth bits: %d\n", depth_bits);
    return buf;
}

#endif
