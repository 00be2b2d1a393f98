/* The checked frames of a model's mesh part: the sequence both the firmware and the host viewer's
 * --checksums run after the point frames (frames.h), when the bake has a mesh part (--as both).
 *
 * Promise: mc_front_mesh_check draws view i of views.h (i < MC_FRONT_VIEW_COUNT) in style
 * mc_front_mesh_style(i) at the level mc_front_mesh_budget(pm, i) gives, through mc_front_mesh_frame
 * (mesh_frame.h), and hashes the target with mc_front_fnv1a (frames.h). The schedule cycles the three
 * styles (shaded, lines, shaded+lines) over the views and sets the level with mc_pmesh_lod_fit on a
 * face budget of F0 + (F - F0) k / 8 for the view's k in mc_front_mesh_eighths: the base level
 * (k = 0), the full mesh (k = 8) and levels between, each style at more than one of them. The fit
 * depends only on the part's arrays, and a level's state is the same bytes however it was reached
 * (pmesh.h), so every machine draws the same levels. MC_FRONT_MESH_LINE / MC_FRONT_MESH_ARGS print
 * the result as one line naming the view, style and level; lines start with "mesh frame " so that
 * they never mix with the point frames' "frame " lines. MC_FRONT_MARK(stage) is called before the
 * level is set, before the frame is drawn and after it (MC_FRONT_MESH_MARK_*): the firmware counts
 * instructions between them under QEMU. Header only, freestanding.
 */
#ifndef MODELC_FRONT_MESH_FRAMES_H
#define MODELC_FRONT_MESH_FRAMES_H

#include <stdint.h>
#include <modelc/modelc.h>
#include "frames.h"
#include "mesh_frame.h"

/* stages passed to MC_FRONT_MARK by a mesh frame */
enum { MC_FRONT_MESH_MARK_LOD = 0, MC_FRONT_MESH_MARK_DRAW = 1, MC_FRONT_MESH_MARK_DONE = 2 };

/* Per view, the face budget in eighths of the way from the base mesh to the full one. With the
 * styles' cycle of three: shaded at 8, 4, 2; lines at 8, 0, 6; shaded+lines at 0, 8, 3. */
static const uint8_t mc_front_mesh_eighths[] = {8, 8, 0, 4, 0, 8, 2, 6, 3};

/* one entry per view: a view added to views.h needs its level here too */
typedef char mc_front_mesh_eighths_per_view[sizeof mc_front_mesh_eighths == MC_FRONT_VIEW_COUNT ? 1 : -1];

static inline mc_front_style mc_front_mesh_style(unsigned i) { return (mc_front_style)(1u + i % 3u); }

static inline const char *mc_front_mesh_style_name(mc_front_style s)
{
    return s == MC_FRONT_SHADED ? "shaded" : s == MC_FRONT_LINES ? "lines" : "shaded+lines";
}

/* The face budget of view i: F0 + (F - F0) k / 8, rounded down (F < 2^29: no overflow). */
static inline uint32_t mc_front_mesh_budget(const mc_pmesh *pm, unsigned i)
{
    return pm->base_faces + ((pm->faces - pm->base_faces) * (uint32_t)mc_front_mesh_eighths[i]) / 8u;
}

typedef struct mc_front_mesh_result {
    int rc;                     /* mc_front_mesh_frame's return value */
    mc_front_style style;
    uint32_t level, faces;      /* the level drawn: vertices and faces present */
    mc_front_mesh_stats st;     /* its faces' and lines' statistics */
    uint32_t hash;              /* FNV-1a of the colour and depth buffers, as frames.h */
} mc_front_mesh_result;

/* Whether a mesh part (a stream's, stream.h) fits level-of-detail memory sized for a bake's: a vertex
 * cache of `vertices` entries, an ancestor map of lod_bytes (aligned for 4-byte entries) and line
 * memory of lines_bytes (MC_NAME_PMESH_VERTICES, _LOD_BYTES, _FACING_BYTES). */
static inline int mc_front_mesh_fits(const mc_pmesh *pm, uint32_t vertices, uint32_t lod_bytes, uint32_t lines_bytes)
{
    return pm->vertices <= vertices && MC_PMESH_LOD_BYTES(pm->vertices, pm->index_bytes) <= lod_bytes &&
           MC_MESH_LINES_BYTES(pm->faces) <= lines_bytes;
}

/* The check of a mesh part of which only the levels up to max_level have come (a stream's, stream.h),
 * and whose line styles can draw only when lines is non-zero (its adjacency has come): the level
 * fitted within max_level too (mc_pmesh_lod_fit_to), the line styles drawn shaded without lines.
 * With max_level the full mesh and lines set, mc_front_mesh_check's frame. */
static inline mc_front_mesh_result mc_front_mesh_check_to(mc_pmesh_lod *lod, uint8_t *facing, mc_xvertex *cache,
                                                          uint32_t *sdepth, unsigned i, const mc_target *t,
                                                          uint32_t max_level, int lines)
{
    mc_front_mesh_result r;
    const mc_view v = mc_front_view_get(i);
    r.style = lines ? mc_front_mesh_style(i) : MC_FRONT_SHADED;
    MC_FRONT_MARK(MC_FRONT_MESH_MARK_LOD);
    r.level = mc_pmesh_lod_fit_to(lod, mc_front_mesh_budget(lod->pm, i), max_level);
    r.faces = lod->faces;
    MC_FRONT_MARK(MC_FRONT_MESH_MARK_DRAW);
    r.rc = mc_front_mesh_frame(lod, facing, cache, sdepth, &v, r.style, t, &r.st);
    MC_FRONT_MARK(MC_FRONT_MESH_MARK_DONE);
    r.hash = mc_front_fnv1a(t);
    return r;
}

/* lod: initialized on the model's part (mc_pmesh_lod_init), at any level; facing, cache and sdepth: the
 * app binding's (app.h; cache and sdepth may be null). */
static inline mc_front_mesh_result mc_front_mesh_check(mc_pmesh_lod *lod, uint8_t *facing, mc_xvertex *cache,
                                                       uint32_t *sdepth, unsigned i, const mc_target *t)
{
    return mc_front_mesh_check_to(lod, facing, cache, sdepth, i, t, lod->pm->vertices, 1);
}

/* printf(MC_FRONT_MESH_LINE, MC_FRONT_MESH_ARGS(i, pm, t, r)); longs for the reason frames.h gives.
 * drawn: faces that covered a pixel; clipped: faces and lines with a corner at the near plane or the
 * guard band, cut there (mesh_render.h, mesh_lines.h), those of which nothing was left included;
 * line-pixels: pixels of the drawn lines before the depth test. */
#define MC_FRONT_MESH_LINE                                                                                   \
    "mesh frame %u style %s level %lu of %lu faces %lu of %lu size %ux%u rc %d drawn %lu clipped %lu "      \
    "line-pixels %lu fnv1a %08lx\n"
#define MC_FRONT_MESH_ARGS(i, pm, t, r)                                                                      \
    (i), mc_front_mesh_style_name((r).style), (unsigned long)(r).level, (unsigned long)(pm)->vertices,        \
        (unsigned long)(r).faces, (unsigned long)(pm)->faces, (unsigned)(t)->width, (unsigned)(t)->height,  \
        (r).rc, (unsigned long)(r).st.faces.drawn,                                                           \
        (unsigned long)((r).st.faces.clipped + (r).st.faces.clipped_away + (r).st.lines.clipped +              \
                        (r).st.lines.clipped_away),                                                          \
        (unsigned long)(r).st.lines.pixels, (unsigned long)(r).hash

#endif
