/* The progressive mesh drawn as flat-shaded triangles: the current level of detail (pmesh.h) through
 * the vertex projection (xform.h) into the rasterizer (raster.h).
 *
 * Promise: mc_mesh_render draws every face of the level into the target with the depth test, in
 * the face's palette index, in stored face order; nothing else is written. A face whose corners the
 * projection leaves unflagged is drawn exactly as mc_raster_triangle draws the triangle of its three
 * corners projected by mc_xform_vertex; a face with a flagged corner, clipped (below). With
 * MC_MESH_CULL_BACK, faces turned away from the viewer are not drawn (for closed meshes, whose back
 * faces are always hidden). With MC_MESH_DRAW_PAPER every face is drawn in MC_MESH_PAPER: the hidden
 * surface of a line drawing.
 *
 * Clipping. A face with a corner the projection flags (MC_XFORM_NEAR: nearer the eye than the near
 * plane; MC_XFORM_FAR_OUT: beyond the guard band; at the default MC_FRAC_BITS only in perspective,
 * with the eye near or inside the model) is drawn as mc_mesh_clip_face gives it: its corners'
 * view-space triangle clipped against the near plane and the band (xform.h mc_xform_clip_triangle),
 * a convex polygon v0 .. v(n-1) of up to MC_XFORM_CLIP_MAX vertices projected as mc_xform_vertex
 * projects a point, drawn as the fan of triangles (v0, vi, vi+1), i = 1 .. n-2, each by
 * mc_raster_triangle without culling, in the face's palette index. So:
 *   - its depths are the face's plane (depth is affine in 1/distance, xform.h), each vertex's within
 *     1 unit of the exact depth there;
 *   - each vertex is within the accuracy xform.h states of the exact cut: at the default
 *     MC_FRAC_BITS within 1/16 pixel where its edge crosses the plane's line at more than a hair's
 *     angle (2^-22 radian), and every vertex lies inside the band, unflagged near: the rasterizer's
 *     coordinate limit holds;
 *   - the fan's triangles share their diagonals, so they cover each pixel centre of the polygon once
 *     (raster.h's top-left rule) as long as rounding to 1/16 pixel leaves the polygon convex; a vertex
 *     within about a unit of the line through its neighbours (a cut beside a corner) can fold it and
 *     cover a centre twice or none along that sliver, as rounding can fold the nearly degenerate
 *     triangles of any mesh;
 *   - faces sharing an edge cut it at the same points, and an edge between two unflagged corners is
 *     never cut, so a clipped face meets its neighbours, clipped or not, edge on edge as unclipped
 *     faces do (short of a cut within rounding of a second plane, which can make one face's polygon
 *     cut again where the other's is not).
 * Its facing, for MC_MESH_CULL_BACK, is its plane's (mc_mesh_face_front: the unclipped face's, in
 * view space, exact), so culling does not change where a face is cut; an unflagged face's is
 * raster.h's sign rule on its projected corners, which the plane test agrees with except for faces
 * within rounding of edge-on. Counts (stats): clipped, the faces with a flagged corner drawn so;
 * clipped_away, those of which nothing is left (wholly behind the near plane, wholly beyond one side
 * of the band, or a polygon past MC_XFORM_CLIP_MAX vertices, which needs a vertex within a few
 * 2^-30 cube side of two clip planes at once); culled faces are in neither, so without
 * MC_MESH_CULL_BACK the two add up to the faces with a flagged corner. No face is skipped:
 * stats->skipped is always 0.
 *
 * Vertex cache: with a cache (the caller's memory, MC_MESH_CACHE_BYTES of the part's V vertices),
 * every vertex present at the level (mc_pmesh_lod_vertex(lod, v) == v) is projected once per call,
 * into cache[v], and each face takes its corners' projections from there; without one (null) each
 * face projects its three corners itself, so a vertex is projected once for every face around it
 * (about six times on a closed mesh). The target, the stats and the return value are the same
 * bytes either way. The cache is V mc_xvertex of RAM, and each call scans the V entries of the
 * ancestor map for the present vertices: it saves work unless the level keeps fewer than about a
 * fiftieth of the part's vertices (bunny00's 37706: level 800).
 *
 * Shade: mesh_face.h (a frontal light fixed to the model, MC_MESH_SHADES greys). A face the level
 * has as the full mesh has it (each corner its own ancestor) takes the shade the generator stored
 * for it when the part has them (pmesh.h face_bits); any other face's is worked out from its
 * corners. The same index either way.
 *
 * No heap, no floating point; the stack holds a few words per face, and xform.h's clipping buffers
 * (about 300 bytes) for a face with a flagged corner. No 64-bit division here (the clipper's cuts
 * divide in xform_vertex.c, as the projection does). Freestanding.
 */
#ifndef MODELC_MESH_RENDER_H
#define MODELC_MESH_RENDER_H

#include <stdint.h>
#include "pmesh.h"
#include "raster.h"
#include "target.h"
#include "xform.h"
#include "mesh_face.h"   /* MC_MESH_SHADES, the stored face bits */

/* palette index of the paper: faces of a lines-only drawing (mesh_lines.h), white */
#define MC_MESH_PAPER MC_MESH_SHADES

/* flags */
#define MC_MESH_CULL_BACK 1u
#define MC_MESH_DRAW_PAPER 2u   /* every face in MC_MESH_PAPER instead of its shade */

typedef struct mc_mesh_stats {
    uint32_t faces;     /* faces of the level */
    uint32_t drawn;     /* faces that covered a pixel of the target */
    uint32_t skipped;   /* always 0: every face is drawn, clipped where it needs it (the count callers print) */
    uint32_t pixels;    /* pixels the drawn faces covered, before the depth test */
    uint32_t clipped;        /* faces with a flagged corner drawn clipped */
    uint32_t clipped_away;   /* faces with a flagged corner of which clipping left nothing */
} mc_mesh_stats;

/* Bytes of vertex cache mc_mesh_render takes for a part of `vertices` vertices (pmesh.h V): one
 * mc_xvertex each, aligned as an mc_xvertex. */
#define MC_MESH_CACHE_BYTES(vertices) ((uint32_t)(vertices) * (uint32_t)sizeof(mc_xvertex))

/* Draws lod's current level seen through view into t. cache: null, or MC_MESH_CACHE_BYTES of the
 * part's vertices, the caller's scratch memory: what it holds on entry does not matter; after MC_OK,
 * cache[v] is mc_xform_vertex's projection of each vertex v present at the level (the other entries
 * are left as they were). Returns MC_OK, MC_ERR_ARG for a null argument other than cache and stats,
 * MC_ERR_SIZE for a target side over MC_TARGET_MAX (then writes nothing, not even to cache). stats
 * may be null. */
int mc_mesh_render(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t,
                   mc_xvertex *cache, mc_mesh_stats *stats);

/* Projects every vertex v present at lod's current level through x into cache[v] (MC_MESH_CACHE_BYTES
 * of the part's vertices), as mc_mesh_render does with a cache. Returns their MC_XFORM_* flags,
 * or-ed: 0 when no vertex of the level is flagged. */
uint32_t mc_mesh_project(const mc_pmesh_lod *lod, const mc_xform *x, mc_xvertex *cache);

/* Face f of lod's current level as mc_mesh_render draws it: its corners' unit-cube positions p (Q16,
 * pmesh.h) and their projections through x in v; returns its corners' MC_XFORM_* flags, or-ed (not
 * 0: the face is drawn clipped, mc_mesh_clip_face). */
uint32_t mc_mesh_face(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f, int32_t p[3][3], mc_raster_vertex v[3]);

/* The face with corners p (unit-cube Q16) clipped as mc_mesh_render draws a face with a flagged
 * corner: the polygon's vertices in v, their number returned (0: nothing left; else 3 or more). */
unsigned mc_mesh_clip_face(const mc_xform *x, const int32_t p[3][3], mc_raster_vertex v[MC_XFORM_CLIP_MAX]);

/* 1 when the face with corners p (unit-cube Q16) faces the eye by its plane in view space
 * (xform.h mc_xform_front): the facing of a face with a flagged corner, in mc_mesh_render's culling
 * and mesh_lines.h's classification. */
int mc_mesh_face_front(const mc_xform *x, const int32_t p[3][3]);

/* The palette index of a face with corners p0, p1, p2 (unit-cube Q16, pmesh.h). */
unsigned mc_mesh_shade(const int32_t p0[3], const int32_t p1[3], const int32_t p2[3]);

#endif
