/* One frame of a model's mesh part in a drawing style: the sequence the host viewer and the
 * firmware both run, so their frames are the same bytes.
 *
 * Promise: mc_front_mesh_frame clears the target and draws lod's current level through view:
 *   shaded        flat-shaded faces (mesh_render.h);
 *   lines         silhouettes, creases and borders (mesh_lines.h) on paper: every pixel that holds
 *                 no visible line is colour MC_MESH_PAPER, depth MC_DEPTH_FILLED. With sdepth
 *                 (MC_SDEPTH_WORDS of the target's size, sdepth.h) the hidden lines are removed
 *                 over a sparse depth buffer in the target's own buffers (mc_mesh_lines_sparse: no
 *                 face drawn, a line pixel's depth is its depth less its offset); without, the faces
 *                 are drawn in paper into the z-buffer first (mc_mesh_render, mc_mesh_lines) and the
 *                 empty pixels made paper. The line pixels that show are the same either way except
 *                 where two lines cross (the sparse buffer keeps the nearer, the z-buffer the later
 *                 unless hidden by the earlier);
 *   shaded+lines  the shaded faces, then the lines over them.
 * Back faces are culled when the part is closed (pmesh.h closed: they are hidden anyway).
 * facing: mc_mesh_lines' memory, MC_MESH_LINES_BYTES of the part's faces, zeroed at first; cache: null or MC_MESH_CACHE_BYTES of its
 * vertices (mesh_render.h; the same frame either way); sdepth: null or the sparse depth buffer's bits;
 * all three the app binding's (app.h). Freestanding, no heap.
 */
#ifndef MODELC_FRONT_MESH_FRAME_H
#define MODELC_FRONT_MESH_FRAME_H

#include <stdint.h>
#include <modelc/mesh_lines.h>

typedef enum mc_front_style {
    MC_FRONT_SHADED = 1,
    MC_FRONT_LINES = 2,
    MC_FRONT_SHADED_LINES = 3
} mc_front_style;

typedef struct mc_front_mesh_stats {
    mc_mesh_stats faces;
    mc_lines_stats lines;   /* all zero for the shaded style */
} mc_front_mesh_stats;

/* Returns MC_OK or the first renderer error. stats may be null. */
int mc_front_mesh_frame(const mc_pmesh_lod *lod, uint8_t *facing, mc_xvertex *cache, uint32_t *sdepth,
                        const mc_view *view, mc_front_style style, const mc_target *t, mc_front_mesh_stats *stats);

#endif
