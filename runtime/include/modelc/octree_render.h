/* Point-octree renderer (Barth, Schwanecke & Wild; after Botsch et al. 2002).
 *
 * Walks the octree depth first. Each level has eight displacement vectors, already rotated, scaled
 * and projected, so a child's screen position is its parent's plus one vector: additions only. The
 * level above the drawn one sets pixels directly instead of recursing (the paper's Algorithm 2),
 * its children visited by walking the set bits of the mask. Each drawn leaf is one pixel (or a
 * footprint, mc_splat), depth tested. Subtrees whose bounding sphere lies wholly off screen are
 * skipped (their data is stepped over, not decoded); subtrees wholly on screen, their leaves'
 * footprints included, are drawn without per-point bounds checks (one pixel, or one unclipped
 * square, a leaf).
 *
 * Perspective (drawn level d >= 3): each node at level d-3 is projected exactly (one division) and,
 * where a bound computed per node shows the first-order expansion of the projection about its
 * centre puts every leaf below within MC_LINEAR_ERROR / 256 pixel of its exact projection
 * (config.h; 1/16 by default), its leaves are drawn through that expansion like an orthographic
 * node: additions only, off-screen subtrees skipped, unchecked where wholly on screen. Elsewhere
 * (near the eye, or at the near plane) each level d-2 child gets its own expansion, or its leaves
 * divide one by one.
 *
 * No heap, no floating point, no recursion deeper than the drawn depth (at most MC_MAX_DEPTH frames
 * of the renderer's internal node function). Buffers belong to the caller; while mc_octree_render
 * runs they may hold values it puts back before returning (the select form of the depth test parks
 * losing leaves on a spare pixel).
 */
#ifndef MODELC_OCTREE_RENDER_H
#define MODELC_OCTREE_RENDER_H

#include <stdint.h>
#include "octree.h"
#include "target.h"
#include "xform.h"

/* How many pixels a leaf covers (the splat). The source paper draws one pixel per leaf; above zoom 1
 * a leaf spans more than a pixel and one-pixel splats leave a lattice of holes.
 *   MC_SPLAT_PIXEL: one pixel per leaf, the paper's (and the fastest) drawing.
 *   MC_SPLAT_ZOOM: an s x s square centred on the leaf, s = ceil(leaf side on screen) in pixels, at
 *     most MC_SPLAT_MAX; chosen once per frame (per point in perspective, where the leaf side grows
 *     with its magnification). s = 1 draws exactly what MC_SPLAT_PIXEL draws, on the same fast path.
 *     A leaf is drawn when its centre is on the target; its square is clipped to the target.
 *   MC_SPLAT_DEFAULT (0, what zeroed options hold): MC_SPLAT_DEFAULT_MODE from config.h.
 * Other values are taken as MC_SPLAT_DEFAULT. */
typedef enum mc_splat { MC_SPLAT_DEFAULT = 0, MC_SPLAT_PIXEL = 1, MC_SPLAT_ZOOM = 2 } mc_splat;

/* Back-facing subtrees, where the bake has normal cones (octree.h; the generator makes them for
 * closed meshes only):
 *   MC_CULL_DEFAULT (0, what zeroed options hold): a node at level d-3 (d the level drawn, d >= 4)
 *     whose cone faces wholly away from the viewer is skipped, its data stepped over. In
 *     perspective the cone must face away from every direction in which the eye sees the model's
 *     bounding sphere (sin of that spread: sqrt(3)/2 / eye), so fewer nodes go. On a closed surface a
 *     back-facing point is hidden behind the surface in front of it; the frame changes where the
 *     far side showed through gaps between front leaves, and where a back leaf's cell centre lay
 *     nearer than the front one's (surfaces within a leaf of each other; tests/host measures both).
 *   MC_CULL_OFF: every leaf is drawn (the source paper's walk, and the reference renderer's).
 * Other values are taken as MC_CULL_DEFAULT. */
typedef enum mc_cull { MC_CULL_DEFAULT = 0, MC_CULL_OFF = 1 } mc_cull;

/* How the octree is drawn, beside the camera (mc_view). A NULL pointer, or a zeroed struct, means
 * the defaults. */
typedef struct mc_octree_options {
    mc_splat splat;       /* leaf footprint */
    uint16_t max_error;   /* screen-space level of detail, Q4 pixels (16 = one pixel): draw the
                           * shallowest level whose nodes span at most this on screen, never deeper
                           * than the depth asked (mc_octree_lod_depth); 0: the depth asked */
    mc_cull cull;         /* back-facing subtrees */
} mc_octree_options;

/* One fixed-point pixel of max_error. */
#define MC_LOD_PIXEL 16

/* The level mc_octree_render draws for `depth` asked and a max_error (Q4 pixels) on a w x h target:
 * depth itself when max_error is 0; otherwise the least level l >= 1 (at most depth) whose node side
 * on screen, S / 2^l with S = zoom * min(w, h) the cube's side in pixels, is at most max_error / 16,
 * in perspective magnified by eye / (eye - sqrt(3)/2), the most any point of the model's bounding
 * sphere is (depth itself when the sphere reaches within 1/64 of a cube side of the eye). Exact in
 * integers, after mc_view_clamp. In orthographic every node of a level spans the same on screen, so
 * this is the level where a node first covers at most the bound; in perspective it is where the
 * nearest node does, and farther ones are finer than they need. */
unsigned mc_octree_lod_depth(const mc_view *view, uint32_t w, uint32_t h, unsigned depth, uint16_t max_error);

/* Draws octree at depth `depth` (1..octree->depth; with opt->max_error, at mc_octree_lod_depth's
 * level) seen through view into t, on top of what t holds (call mc_clear first for a fresh frame).
 * Drawing at a level reads only that level's colours and the masks above it (octree.h). opt, abort
 * and stats may be NULL. abort is polled every
 * time the walk enters a node at depth min(MC_ABORT_LEVEL, depth - 3) (depth 0, once, when depth
 * <= 3); stats->points counts the leaves that landed on the target, stats->depth the level drawn,
 * stats->culled the back-facing nodes skipped.
 * Returns MC_OK, or MC_ERR_ARG for NULL pointers, MC_ERR_DEPTH for a depth the octree does not
 * have, MC_ERR_SIZE for a target larger than MC_TARGET_MAX on a side or empty. */
int mc_octree_render(const mc_octree *octree, const mc_view *view, unsigned depth, const mc_octree_options *opt,
                     const mc_target *t, mc_abort_fn abort, void *user, mc_stats *stats);

#endif
