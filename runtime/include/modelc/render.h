/* Point-octree renderer (Barth, Schwanecke & Wild; after Botsch et al. 2002).
 *
 * Walks the octree depth first. Each level has eight displacement vectors, already rotated, scaled
 * and projected, so a child's screen position is its parent's plus one vector: additions only. The
 * level above the drawn one sets pixels directly instead of recursing (the paper's Algorithm 2),
 * its children visited by walking the set bits of the mask. Each drawn leaf is one pixel, depth
 * tested. Subtrees whose bounding sphere lies wholly off screen are skipped (their data is stepped
 * over, not decoded); subtrees wholly on screen are drawn without per-point bounds checks.
 *
 * No heap, no floating point, no recursion deeper than the drawn depth (at most MC_MAX_DEPTH frames
 * of mc_render's internal node function). Buffers belong to the caller; while mc_render runs they
 * may hold values it puts back before returning (the select form of the depth test parks losing
 * leaves on a spare pixel).
 */
#ifndef MODELC_RENDER_H
#define MODELC_RENDER_H

#include <stdint.h>
#include "scene.h"
#include "view.h"

/* Depth value of a pixel nothing was drawn on. Drawn depths are always below MC_DEPTH_EMPTY - 1. */
#define MC_DEPTH_EMPTY 0xFFFFu

typedef struct mc_target {
    uint8_t *color;    /* width * height palette indices, row-major */
    uint16_t *depth;   /* width * height depths: smaller is nearer */
    uint16_t width, height;
} mc_target;

/* Largest target side: keeps width/2 plus a translation inside MC_COORD_LIMIT. */
#define MC_TARGET_MAX (MC_COORD_LIMIT / 8 < 8192 ? MC_COORD_LIMIT / 8 : 8192)

/* Polled every time the walk enters a node at depth min(MC_ABORT_LEVEL, d - 3) for drawn depth d
 * (depth 0, once, when d <= 3); return non-zero to give up. */
typedef int (*mc_abort_fn)(void *user);

typedef struct mc_stats {
    uint32_t points;   /* leaves that landed on screen (before the depth test) */
    uint32_t polls;    /* abort polls made */
    int aborted;       /* the frame was given up: the target holds a partial image */
} mc_stats;

enum { MC_OK = 0, MC_ERR_ARG = -1, MC_ERR_DEPTH = -2, MC_ERR_SIZE = -3 };

/* Empties the target: every depth MC_DEPTH_EMPTY, every colour 0. */
void mc_clear(const mc_target *t);

/* Draws scene at octree depth `depth` (1..scene->depth) into t, on top of what t holds (call
 * mc_clear first for a fresh frame). abort may be NULL. stats may be NULL.
 * Returns MC_OK, or MC_ERR_ARG for NULL pointers, MC_ERR_DEPTH for a depth the scene does not have,
 * MC_ERR_SIZE for a target larger than MC_TARGET_MAX on a side or empty. */
int mc_render(const mc_scene *scene, const mc_view *view, unsigned depth, const mc_target *t,
              mc_abort_fn abort, void *user, mc_stats *stats);

#endif
