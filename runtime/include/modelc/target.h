/* What a renderer draws into, and the contract every renderer shares.
 *
 * Promise: an mc_target is a colour buffer (one palette index per pixel) and a depth buffer (16 bits
 * per pixel, smaller is nearer), both owned by the caller, row-major, width * height entries.
 * MC_DEPTH_EMPTY marks a pixel nothing was drawn on; renderers never write it (their depths stay
 * below MC_DEPTH_EMPTY - 1, leaving MC_DEPTH_FILLED to the hole filler, finish.h), so a renderer
 * can draw on top of what a target holds. mc_clear empties a target. mc_target_rgb converts one
 * pixel to RGB through a palette of RGB triplets, empty pixels to a background the caller chooses:
 * the one conversion every image writer and display uses, so their pictures agree byte for byte.
 *
 * Renderers return MC_OK or a negative MC_ERR_*, poll an mc_abort_fn when given one, and report
 * what they drew in an mc_stats.
 */
#ifndef MODELC_TARGET_H
#define MODELC_TARGET_H

#include <stdint.h>
#include "fixed.h"

/* Depth value of a pixel nothing was drawn on. Drawn depths are always below MC_DEPTH_EMPTY - 1. */
#define MC_DEPTH_EMPTY 0xFFFFu

typedef struct mc_target {
    uint8_t *color;    /* width * height palette indices, row-major */
    uint16_t *depth;   /* width * height depths: smaller is nearer */
    uint16_t width, height;
} mc_target;

/* Largest target side: keeps width/2 plus a translation inside MC_COORD_LIMIT. */
#define MC_TARGET_MAX (MC_COORD_LIMIT / 8 < 8192 ? MC_COORD_LIMIT / 8 : 8192)

/* Renderers' return values. */
enum { MC_OK = 0, MC_ERR_ARG = -1, MC_ERR_DEPTH = -2, MC_ERR_SIZE = -3 };

/* Polled by a renderer while it draws (when and how often is the renderer's to say); return
 * non-zero to give up the frame. */
typedef int (*mc_abort_fn)(void *user);

typedef struct mc_stats {
    uint32_t points;   /* points that landed on the target (before the depth test) */
    uint32_t polls;    /* abort polls made */
    int aborted;       /* the frame was given up: the target holds a partial image */
    uint32_t depth;    /* the level drawn (octree_render.h: the level of detail may draw shallower) */
    uint32_t culled;   /* back-facing nodes skipped (octree_render.h, mc_cull) */
} mc_stats;

/* Empties the target: every depth MC_DEPTH_EMPTY, every colour 0. */
void mc_clear(const mc_target *t);

/* The RGB of pixel i (0 <= i < width * height) into rgb[0..2]: palette entry t->color[i] (palette
 * holds RGB triplets), or background[0..2] where the depth is MC_DEPTH_EMPTY. */
static inline void mc_target_rgb(const mc_target *t, uint32_t i, const uint8_t *palette, const uint8_t background[3],
                                 uint8_t rgb[3])
{
    const uint8_t *c = t->depth[i] == MC_DEPTH_EMPTY ? background : palette + 3u * t->color[i];
    rgb[0] = c[0];
    rgb[1] = c[1];
    rgb[2] = c[2];
}

#endif
