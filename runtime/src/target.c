/* Clearing a target: see modelc/target.h. */
#include "modelc/target.h"

void mc_clear(const mc_target *t)
{
    /* locals, and one loop per buffer: the compiler cannot prove the two buffers do not alias
     * t itself, and would otherwise reload both pointers and store one element at a time */
    uint32_t n = (uint32_t)t->width * t->height;
    uint16_t *depth = t->depth;
    uint8_t *color = t->color;
    uint32_t i = 0;
    /* eight adjacent constant stores per step: compilers merge them into wide stores (freestanding
     * code gets no memset, and -O2 does not vectorise a loop of unknown length) */
    for (; i + 8 <= n; i += 8) {
        depth[i] = MC_DEPTH_EMPTY; depth[i + 1] = MC_DEPTH_EMPTY; depth[i + 2] = MC_DEPTH_EMPTY;
        depth[i + 3] = MC_DEPTH_EMPTY; depth[i + 4] = MC_DEPTH_EMPTY; depth[i + 5] = MC_DEPTH_EMPTY;
        depth[i + 6] = MC_DEPTH_EMPTY; depth[i + 7] = MC_DEPTH_EMPTY;
        color[i] = 0; color[i + 1] = 0; color[i + 2] = 0; color[i + 3] = 0;
        color[i + 4] = 0; color[i + 5] = 0; color[i + 6] = 0; color[i + 7] = 0;
    }
    for (; i < n; i++) { depth[i] = MC_DEPTH_EMPTY; color[i] = 0; }
}
