/* Edge-based tracking: see modelc/track.h. */
#include "modelc/track.h"
#include "modelc/imgedge.h"
#include "modelc/line.h"
#include "modelc/raster.h"
#include "line_walk.h"

uint32_t mc_track_line(mc_sdepth *s, mc_line_vertex a, mc_line_vertex b, uint8_t color, uint16_t depth_offset,
                       const uint8_t *masks, uint8_t want)
{
    if (!s->matched || !masks) return 0;
    return mc_line_walk_sdepth(s, a, b, color, depth_offset, masks, want);
}

/* Camera point of vertex v under pose. */
static void camera_point(const mc_edges *m, const mc_pose *pose, uint32_t v, int32_t c[3])
{
    int32_t p[3];
    mc_edges_position(m, v, p);
    mc_pose_apply(pose, p, c);
}

/* The line from ends e (unflagged, 1/16 pixel) into the buffer; returns its pixels, or 0 with
 * *drawn 0 when it has no orientation. */
static uint32_t draw_line(const mc_track_view *view, const mc_xvertex e[2], uint32_t *drawn)
{
    const int32_t dx = e[1].x - e[0].x, dy = e[1].y - e[0].y;
    *drawn = 0;
    if (!dx && !dy) return 0;
    const unsigned bin = mc_imgedge_bin(-dy, dx);   /* the normal: the image gradient across the edge */
    mc_line_vertex a, b;
    /* 1/16 pixel to the pixel that holds the point (pixel i spans [i, i + 1)) */
    a.x = e[0].x >> MC_XFORM_SUBPIXEL_BITS, a.y = e[0].y >> MC_XFORM_SUBPIXEL_BITS, a.z = e[0].z;
    b.x = e[1].x >> MC_XFORM_SUBPIXEL_BITS, b.y = e[1].y >> MC_XFORM_SUBPIXEL_BITS, b.z = e[1].z;
    *drawn = 1;
    return mc_track_line(view->sd, a, b, (uint8_t)(1u + bin), 0, view->masks, mc_imgedge_bin_mask(bin, view->tolerance));
}

/* One unflagged triangle's face pass, culled from behind when cull. */
static void hide(mc_sdepth *sd, const mc_raster_vertex v[3], int cull)
{
    /* a back face of a closed model hides nothing a front face does not: dropped before its box (the
     * rasterizer's own sign rule: back where twice the signed area is above 0) */
    if (cull && (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y) > 0) return;
    mc_raster_box b;
    if (!mc_raster_centres(v, sd->width, sd->height, &b) ||
        !mc_sdepth_any(sd, (uint32_t)b.i0, (uint32_t)b.i1, (uint32_t)b.j0, (uint32_t)b.j1))
        return;
    const uint64_t off = mc_raster_slope(v) + 2u;
    mc_raster_triangle_hide_offset(sd, v, cull ? MC_RASTER_CULL_BACK : 0u, off > 0xFFFFu ? 0xFFFFu : (uint32_t)off);
}

static void as_raster(const mc_xvertex *x, mc_raster_vertex *r) { r->x = x->x, r->y = x->y, r->z = x->z; }

/* Whether face i of a model with every vertex projected is seen from outside: hide()'s sign rule, so
 * that the shortcut and the face pass cull the same faces. */
static int front(const mc_edges *m, const mc_xvertex *cache, uint32_t i)
{
    uint32_t f[3];
    mc_edges_face(m, i, f);
    const mc_xvertex *a = &cache[f[0]], *b = &cache[f[1]], *c = &cache[f[2]];
    return (int64_t)(b->x - a->x) * (c->y - a->y) - (int64_t)(c->x - a->x) * (b->y - a->y) <= 0;
}

/* A convex model wholly beyond the near plane and inside the band: each line with a face towards the
 * camera goes into the buffer and no face hides any part of it; the others are hidden whole. */
static void convex_lines(const mc_track_view *view, mc_track_score *score)
{
    const mc_edges *m = view->model;
    const mc_xvertex *cache = view->cache;
    for (uint32_t i = 0; i < m->lines; i++) {
        uint32_t f[2], ends[2], drawn;
        mc_edges_line_faces(m, i, f);
        if (!front(m, cache, f[0]) && !front(m, cache, f[1])) continue;
        mc_edges_line(m, i, ends);
        mc_xvertex e[2];
        e[0] = cache[ends[0]], e[1] = cache[ends[1]];
        score->pixels += draw_line(view, e, &drawn);
        score->lines += drawn;
    }
}

int mc_track_score_pose(const mc_track_view *view, const mc_pose *pose, mc_track_score *score)
{
    if (!view || !pose || !score || !view->model || !view->cam || !view->sd || !view->masks || !view->cache)
        return MC_ERR_ARG;
    const mc_edges *m = view->model;
    const mc_camera *cam = view->cam;
    mc_sdepth *sd = view->sd;
    if (!sd->matched || sd->width != cam->width || sd->height != cam->height) return MC_ERR_ARG;
    mc_xvertex *cache = view->cache;
    score->visible = score->matched = score->pixels = score->lines = 0;
    mc_sdepth_forget(sd);   /* every reader below goes by the bits */
    uint32_t flagged = 0;
    for (uint32_t v = 0; v < m->vertices; v++) {
        int32_t c[3];
        camera_point(m, pose, v, c);
        mc_camera_project(cam, c, &cache[v]);
        flagged |= cache[v].flags;
    }
    if (m->convex && !(flagged & (MC_XFORM_NEAR | MC_XFORM_FAR_OUT))) {
        convex_lines(view, score);
        score->visible = mc_sdepth_count(sd);
        score->matched = mc_sdepth_count_matched(sd);
        return MC_OK;
    }
    /* the lines first: their pixels become the buffer's entries */
    for (uint32_t i = 0; i < m->lines; i++) {
        uint32_t ends[2], drawn;
        mc_edges_line(m, i, ends);
        mc_xvertex e[2];
        e[0] = cache[ends[0]], e[1] = cache[ends[1]];
        const uint32_t flags = e[0].flags | e[1].flags;
        if (flags & MC_XFORM_FAR_OUT) continue;
        if (flags & MC_XFORM_NEAR) {
            int32_t a[3], b[3];
            camera_point(m, pose, ends[0], a);
            camera_point(m, pose, ends[1], b);
            if (!mc_camera_clip_segment(cam, a, b, e) || ((e[0].flags | e[1].flags) & MC_XFORM_FAR_OUT)) continue;
        }
        score->pixels += draw_line(view, e, &drawn);
        score->lines += drawn;
    }
    /* then the faces empty the entries they hide */
    for (uint32_t i = 0; i < m->faces; i++) {
        uint32_t f[3];
        mc_edges_face(m, i, f);
        const uint32_t flags = cache[f[0]].flags | cache[f[1]].flags | cache[f[2]].flags;
        if (flags & MC_XFORM_FAR_OUT) continue;
        mc_raster_vertex v[3];
        if (!(flags & MC_XFORM_NEAR)) {
            for (int k = 0; k < 3; k++) as_raster(&cache[f[k]], &v[k]);
            hide(sd, v, m->closed);
            continue;
        }
        int32_t c[3][3];
        mc_xvertex poly[4];
        for (int k = 0; k < 3; k++) camera_point(m, pose, f[k], c[k]);
        const unsigned n = mc_camera_clip_triangle(cam, (const int32_t(*)[3])c, poly);
        uint32_t pf = 0;
        for (unsigned k = 0; k < n; k++) pf |= poly[k].flags;
        if (pf & MC_XFORM_FAR_OUT) continue;
        for (unsigned k = 1; k + 1 < n; k++) {
            as_raster(&poly[0], &v[0]), as_raster(&poly[k], &v[1]), as_raster(&poly[k + 1], &v[2]);
            hide(sd, v, m->closed);
        }
    }
    score->visible = mc_sdepth_count(sd);
    score->matched = mc_sdepth_count_matched(sd);
    return MC_OK;
}
