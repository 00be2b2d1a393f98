/* Silhouette edges of a progressive mesh's current level, found two ways: exactly, by testing every
 * edge, or by the source paper's probabilistic search within a work bound, which follows the
 * silhouettes from frame to frame.
 *
 * A silhouette edge is mesh_lines.h's: one of its two faces is front-facing (projected corners
 * counter-clockwise on the screen) and the other is not; a face with a corner the projection flags
 * is not front-facing. An edge is named by a half-edge of a face present at the level.
 *
 * Promise (mc_sil_exact): the list holds every silhouette edge of the level once (the first
 * `capacity` of them in face order when there are more; the return value counts them all). Work:
 * every face's facing once (three projections each) and every edge's neighbour search.
 *
 * Promise (mc_sil_search): the list holds silhouette edges of the level only, each once, found with
 * at most `budget` edge tests (an edge test: the edge's neighbour search and its two faces' facing,
 * each face's facing computed at most once a frame), in this order:
 *   1. the list the previous call left (frame coherence): each edge whose face is still present is
 *      retested and kept if it still is a silhouette;
 *   2. chain following: around both endpoints of each edge in the list, the edges meeting there are
 *      tested, and the silhouettes found join the list (and are followed in turn);
 *   3. seeds: when the list's chains are done and budget is left, up to `seeds` edges drawn at random
 *      from the part's edge order (pmesh.h: sharpest first), skewed towards its start (index
 *      E u^2 for u uniform: sharp edges are more often silhouettes), each silhouette found followed
 *      as in 2.
 * The random draws come from a 32-bit xorshift generator whose state is in mc_sil, so the same calls
 * find the same edges on every machine (firmware checksums stay reproducible). What it misses it
 * finds in later frames from the seeds and the chains; what it finds is always correct.
 *
 * Memory: the caller's, MC_SIL_FACE_BYTES(F) bytes of per-face marks (cleared each call; aligned
 * for uint32_t) and `capacity` half-edges of list; and, given to mc_sil_cache, a vertex cache
 * (MC_MESH_CACHE_BYTES(V), mesh_render.h) with MC_SIL_SEEN_WORDS(V) words of bits, so that a call
 * projects each vertex it meets once (without, each facing projects its face's three corners). The
 * same calls find the same edges either way. No heap, bounded stack, no floating point. Freestanding.
 */
#ifndef MODELC_SILHOUETTE_H
#define MODELC_SILHOUETTE_H

#include <stdint.h>
#include "mesh_render.h"

/* Bytes of per-face marks for a part of F faces (whole 32-bit words). */
#define MC_SIL_FACE_BYTES(faces) ((((uint32_t)(faces) + 3u) / 4u) * 4u)
/* Words of vertex bits for a part of V vertices (mc_sil_cache). */
#define MC_SIL_SEEN_WORDS(vertices) (((uint32_t)(vertices) + 31u) / 32u)

typedef struct mc_sil {
    uint8_t *marks;      /* per face: facing known, front, edges 0..2 tested this call */
    uint32_t *list;      /* the silhouettes found (half-edges) */
    uint32_t capacity;   /* entries of list */
    uint32_t count;      /* entries in use */
    uint32_t rng;        /* xorshift32 state, never 0 */
    mc_xvertex *cache;   /* null, or per vertex its projection this call (where seen says so) */
    uint32_t *seen;      /* per vertex a bit: projected this call (cleared each call) */
} mc_sil;

typedef struct mc_sil_stats {
    uint32_t tests;      /* edge tests made */
    uint32_t facings;    /* faces whose facing was computed */
    uint32_t kept;       /* of the previous list, still silhouettes */
    uint32_t seeds;      /* random edges tested */
    uint32_t found;      /* silhouettes in the list at the end */
} mc_sil_stats;

/* An empty list, no vertex cache; seed: any value (0 is replaced by a fixed non-zero state). */
void mc_sil_init(mc_sil *s, uint8_t *marks, uint32_t *list, uint32_t capacity, uint32_t seed);

/* From the next call on, each vertex met is projected once a call, into cache (MC_MESH_CACHE_BYTES of
 * the part's vertices) with its bit in seen (MC_SIL_SEEN_WORDS); null for either: none kept. */
void mc_sil_cache(mc_sil *s, mc_xvertex *cache, uint32_t *seen);

/* Every silhouette edge of lod's level seen through x (see the promise); returns how many there are. */
uint32_t mc_sil_exact(mc_sil *s, const mc_pmesh_lod *lod, const mc_xform *x, mc_sil_stats *stats);

/* The bounded search (see the promise); returns the list's count. stats may be null. */
uint32_t mc_sil_search(mc_sil *s, const mc_pmesh_lod *lod, const mc_xform *x, uint32_t budget, uint32_t seeds,
                       mc_sil_stats *stats);

#endif
