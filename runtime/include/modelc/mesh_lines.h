/* Line drawings of a progressive mesh: the silhouettes, creases and borders of the current level of
 * detail (pmesh.h), drawn over its faces with hidden lines removed by the z-buffer.
 *
 * Edges. Each edge of the level once: half-edge h = MC_HALF_EDGE(f, k) of a present face f whose
 * opposite o (mc_pmesh_lod_opposite) is none or lies in a later face. Its kind, first that applies:
 *   border      no face across it;
 *   silhouette  one of its two faces is front-facing and the other is not;
 *   crease      the angle between its faces' normals exceeds the part's crease angle (the bake's
 *               --crease-angle, pmesh.h crease_cos);
 *   plain       none of these (not drawn).
 * Facing: a face is front-facing when its corners, projected by mc_xform_vertex, turn
 * counter-clockwise on the screen (twice the signed area of their 1/16-pixel coordinates, y down,
 * below 0): exactly the faces mc_raster_triangle draws with MC_RASTER_CULL_BACK, so silhouettes run
 * where drawn faces meet culled ones. A face with a corner flagged by the projection (MC_XFORM_NEAR,
 * MC_XFORM_FAR_OUT) is front-facing when the eye lies in front of its plane in view space
 * (mesh_render.h mc_mesh_face_front, xform.h mc_xform_front, exact): the facing mc_mesh_render culls
 * it by, so silhouettes run between a drawn face and a clipped face turned away, and between two
 * clipped faces, as between unclipped ones. mc_mesh_front, mc_mesh_facing and mc_mesh_lines all
 * take facing so.
 *
 * Clipping: an edge with a flagged end is drawn as the segment between its ends' view-space points
 * clipped against the near plane and the band (xform.h mc_xform_clip_segment: the cuts are, bit for
 * bit, the vertices its faces' clipped polygons have on it), the cut ends projected as
 * mc_xform_vertex projects a point, within xform.h's accuracy of the exact cuts. Its pixels are
 * mc_line's Bresenham line between the pixels holding the cut ends (the clipped segment's own line,
 * not the unclipped line cut), with their depths; the ends lie inside the band, so within
 * MC_LINE_COORD_MAX. stats: clipped, those edges drawn so; clipped_away, those of which nothing is
 * left (wholly behind the near plane or beyond one side of the band). An edge with both ends
 * unflagged is drawn whole, whatever its faces' third corners, as in a frame with no flag. No edge
 * is skipped: stats->skipped is always 0.
 * Crease test: on the normals' 15 leading bits, against the cosine in Q14, in 64-bit integers: an
 * edge within a hundredth of a degree of the crease angle may go either way; an edge of a face with
 * no area is not a crease.
 *
 * Hidden lines (z-buffer): the caller draws the faces first (mc_mesh_render, with MC_MESH_DRAW_PAPER for
 * the lines-only style); each line pixel is then drawn where its depth, less an offset, is nearer than
 * the target's (mc_line's depth test, with MC_LINE_WRITE_DEPTH so lines beyond the faces' outline
 * show on an empty background). The offset of an edge is 2 units (the rounding of line and face
 * depths) plus one pixel's worth of the steeper depth slope of its faces (max |dz/dx|, |dz/dy|, as
 * OpenGL's polygon offset), at most MC_LINE_DEPTH_MAX: a line is not hidden by the faces it bounds,
 * and is hidden by any other face more than that offset in front of it. A face with a flagged corner
 * gives the slope of the largest triangle of its clipped polygon's fan (a plane has one slope on the
 * screen), nothing when nothing of it is left.
 *
 * Colours: palette entries after the MC_MESH_SHADES greys (the generator writes them): paper
 * (white), silhouettes black, creases grey, borders dark blue.
 *
 * Order: mc_mesh_lines draws the lines in the order of the half-edges above (face by face, edge k
 * = 0, 1, 2), where lines cross keeping the later one not hidden by the earlier: the order mesh_qi.h
 * lists them in. mc_mesh_lines_sparse offers a silhouette from its front face instead (where lines
 * cross at the same depth, the first offered is kept), so that in a closed part it need not visit
 * the back faces.
 *
 * Work: mc_mesh_lines finds every face's facing (from the vertex cache, or three projections), then
 * visits the faces (mc_mesh_lines_sparse in a closed part only the front faces and those with a
 * crease edge), their edges' neighbours (pmesh.h: a walk across the faces the level lacks, or the
 * state's neighbour table's entry) and, for drawn edges, the line's pixels; when the level changed,
 * the crease tests of the edges around the vertices that moved (a small change) or of every edge
 * (a large one, or the first call). A face with a flagged corner costs its plane test, and a
 * clipping of its polygon for each drawn edge beside it (the slope); an edge with a flagged end, its
 * clipping. The tests of the passes over every face whose outcome is a coin toss (is the face
 * front-facing, does its box hold a centre and an entry) are branches or values as config.h
 * MC_MESH_SELECT chooses; the pixels are the same either way.
 * Memory: the caller's, MC_MESH_LINES_BYTES(faces); no heap, no floating point; bounded stack (the
 * clipping's buffers, about 300 bytes, only below a face with a flagged corner). Freestanding.
 */
#ifndef MODELC_MESH_LINES_H
#define MODELC_MESH_LINES_H

#include <stdint.h>
#include "mesh_render.h"
#include "line.h"

/* palette indices of the lines (after the shades and the paper, mesh_render.h) */
#define MC_LINES_SILHOUETTE_COLOR (MC_MESH_SHADES + 1)
#define MC_LINES_CREASE_COLOR (MC_MESH_SHADES + 2)
#define MC_LINES_BORDER_COLOR (MC_MESH_SHADES + 3)
#define MC_MESH_PALETTE_SIZE (MC_MESH_SHADES + 4)

/* edge kinds, and the flags choosing which to draw */
enum { MC_EDGE_PLAIN = 0, MC_EDGE_SILHOUETTE = 1, MC_EDGE_CREASE = 2, MC_EDGE_BORDER = 4 };
#define MC_LINES_ALL (MC_EDGE_SILHOUETTE | MC_EDGE_CREASE | MC_EDGE_BORDER)
#define MC_LINES_NO_HIDING 8u   /* draw every line whole, hidden or not */

/* Bytes of facing bits for a part of F faces. */
#define MC_MESH_FACING_BYTES(faces) (((uint32_t)(faces) + 7u) / 8u)
/* Bytes of mc_mesh_lines' memory for a part of F faces (aligned for uint32_t): a level tag, the
 * facing bits and four crease bits a face. */
#define MC_MESH_LINES_BYTES(faces) (4u + MC_MESH_FACING_BYTES(faces) + ((uint32_t)(faces) + 1u) / 2u)

typedef struct mc_lines_stats {
    uint32_t edges;         /* edges of the level */
    uint32_t silhouettes;   /* found, drawn or clipped away */
    uint32_t creases;
    uint32_t borders;
    uint32_t skipped;       /* always 0: every line is drawn, clipped where it needs it (the count callers print) */
    uint32_t pixels;        /* pixels of the drawn lines on the target, before the depth test */
    uint32_t clipped;        /* lines of a chosen kind with a flagged end, drawn clipped */
    uint32_t clipped_away;   /* lines of a chosen kind with a flagged end of which clipping left nothing */
} mc_lines_stats;

/* Whether face f (0 .. lod->faces-1) of the level is front-facing seen through x. */
int mc_mesh_front(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f);

/* Whether a face whose corners project to a, b, c, none of them flagged, is front-facing: the sign
 * of its projected area, as mc_mesh_front takes it. Inline for the passes over every face (a
 * cache's entries read in place); a 64-bit core widens each coordinate as it reads it, a 32-bit one
 * subtracts in one step. */
MC_ALWAYS_INLINE int mc_mesh_front_of(const mc_xvertex *a, const mc_xvertex *b, const mc_xvertex *c)
{
#if UINTPTR_MAX > 0xFFFFFFFFu
    return ((int64_t)b->x - a->x) * ((int64_t)c->y - a->y) - ((int64_t)c->x - a->x) * ((int64_t)b->y - a->y) < 0;
#else
    return (int64_t)(b->x - a->x) * (c->y - a->y) - (int64_t)(c->x - a->x) * (b->y - a->y) < 0;
#endif
}

/* Sets facing bit f (0 .. lod->faces-1) for every front-facing face of the level seen through x. */
void mc_mesh_facing(const mc_pmesh_lod *lod, const mc_xform *x, uint8_t *facing);

/* The kind of the edge of half-edge h (a present face's) at the level, whose opposite is o
 * (mc_pmesh_lod_opposite), given facing bits from mc_mesh_facing. */
unsigned mc_mesh_edge_kind(const mc_pmesh_lod *lod, const uint8_t *facing, uint32_t h, uint32_t o);

/* The ends of half-edge h (a present face's, from its corner k to corner k+1) as mc_mesh_lines
 * draws its line, through x: both corners projected by mc_xform_vertex when neither is flagged
 * (returns 0), else the segment clipped (mc_xform_clip_segment: returns 1, or 2 with ends untouched
 * when nothing is left). mesh_qi.h draws its clipped lines from these too. */
int mc_mesh_edge_ends(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t h, mc_raster_vertex ends[2]);

/* Whether two faces with corners a and b (unit-cube Q16) meet at more than the crease angle whose
 * cosine is crease_cos (Q14). */
int mc_mesh_crease(const int32_t a[3][3], const int32_t b[3][3], int32_t crease_cos);

/* Draws the level's edges of the kinds in flags (MC_EDGE_* bits; MC_LINES_NO_HIDING) seen through
 * view into t, whose faces the caller has drawn for hidden-line removal. mem: the caller's
 * MC_MESH_LINES_BYTES(lod->pm->faces) bytes for this part, zeroed before the first call; the crease
 * bits it keeps (creases do not depend on the view) are kept while the level is unchanged, so a
 * frame at an unchanged level tests no crease, and brought over from the last call's level when it
 * is near (under a 16th of the faces changed, a 256th to the full level of a part with stored face
 * bits: only the faces around the vertices the splits between moved are tested), else taken anew
 * (from the stored bits where a face and its neighbour are as in the full mesh, pmesh.h face_bits);
 * either way the same bits, a function of the level. cache:
 * null, or the vertex cache mc_mesh_render filled drawing this level through the same view onto a
 * target of the same size (mesh_render.h; the same lines either way). Returns MC_OK, MC_ERR_ARG (a
 * null argument) or MC_ERR_SIZE (a side over MC_TARGET_MAX; nothing drawn). stats may be null. */
int mc_mesh_lines(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t, uint8_t *mem,
                  const mc_xvertex *cache, mc_lines_stats *stats);

/* Brings mem (as mc_mesh_lines takes it, for a part with its adjacency) to the current level: the
 * crease bits, as the next drawing would first. For a caller that times a level change apart from
 * the frames drawn after it (the host viewer's automatic level of detail). */
void mc_mesh_lines_level(const mc_pmesh_lod *lod, uint8_t *mem);

/* The same lines with hidden lines removed over a sparse depth buffer (sdepth.h) instead of the
 * target's z-buffer, and no faces drawn: each line's pixels (its ends clipped as mc_mesh_lines
 * clips them) are offered to sd (mc_line_sdepth, the same pixels and offset depths as mc_line's
 * test), the nearest kept at a pixel, then the faces mc_mesh_render would draw (the same culling; a
 * face with a flagged corner as the triangles of its clipped fan) empty the entries they hide
 * (mc_raster_triangle_hide). So an entry survives exactly where mc_mesh_lines would draw its line's
 * pixel over those faces; where lines cross, the nearer one is kept (mc_mesh_lines: the later one
 * not hidden by the earlier). The work is the edges' plus, per face, its corners and box; only the
 * faces whose box holds an entry are set up, and their spans visit only the entries. sd: the
 * caller's, over the frame it is drawn on (its colours the target's, its empty colour the paper):
 * what it holds is kept and competes. cache: null, or MC_MESH_CACHE_BYTES of the part's vertices,
 * filled here (mesh_render.h mc_mesh_project). mem, flags, stats, returns: as mc_mesh_lines. */
int mc_mesh_lines_sparse(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, mc_sdepth *sd, uint8_t *mem,
                         mc_xvertex *cache, mc_lines_stats *stats);

#endif
