/* One frame of a mesh part in a style: see mesh_frame.h. */
#include "mesh_frame.h"

#include <modelc/finish.h>   /* MC_DEPTH_FILLED */

int mc_front_mesh_frame(const mc_pmesh_lod *lod, uint8_t *facing, mc_xvertex *cache, uint32_t *sdepth,
                        const mc_view *view, mc_front_style style, const mc_target *t, mc_front_mesh_stats *stats)
{
    mc_front_mesh_stats st;
    st.faces.faces = st.faces.drawn = st.faces.skipped = st.faces.pixels = st.faces.clipped = st.faces.clipped_away = 0;
    st.lines.edges = st.lines.silhouettes = st.lines.creases = st.lines.borders = st.lines.skipped = 0;
    st.lines.pixels = st.lines.clipped = st.lines.clipped_away = 0;
    if (!lod || !lod->pm || !t) return MC_ERR_ARG;
    if (style == MC_FRONT_LINES && sdepth) {
        mc_sdepth sd;
        int rc = mc_sdepth_init(&sd, t->width, t->height, sdepth, t->depth, t->color, MC_DEPTH_FILLED, MC_MESH_PAPER);
        if (rc == MC_OK) rc = mc_mesh_lines_sparse(lod, view, MC_LINES_ALL, &sd, facing, cache, &st.lines);
        if (stats) *stats = st;
        return rc;
    }
    const unsigned cull = lod->pm->closed ? MC_MESH_CULL_BACK : 0u;
    mc_clear(t);
    int rc = mc_mesh_render(lod, view, cull | (style == MC_FRONT_LINES ? MC_MESH_DRAW_PAPER : 0u), t, cache, &st.faces);
    if (rc == MC_OK && style != MC_FRONT_SHADED) rc = mc_mesh_lines(lod, view, MC_LINES_ALL, t, facing, cache, &st.lines);
    if (rc == MC_OK && style == MC_FRONT_LINES) {
        const uint32_t n = (uint32_t)t->width * t->height;
        for (uint32_t i = 0; i < n; i++)
            if (t->depth[i] == MC_DEPTH_EMPTY) t->color[i] = MC_MESH_PAPER, t->depth[i] = MC_DEPTH_FILLED;
    }
    if (stats) *stats = st;
    return rc;
}
