/* The host viewer's scene: see scene.h. */
#define _POSIX_C_SOURCE 200809L
#include "scene.h"

#include <string.h>

#include "timing.h"

static const char *const names[] = {"points", "shaded", "lines", "shaded+lines"};

int mc_host_mode_parse(const char *s, mc_host_mode *mode)
{
    for (int i = 0; i < 4; i++)
        if (!strcmp(s, names[i])) { *mode = (mc_host_mode)i; return 0; }
    return -1;
}

const char *mc_host_mode_name(mc_host_mode mode) { return (unsigned)mode < 4u ? names[mode] : "?"; }

int mc_host_scene_has_mesh(const mc_host_scene *s)
{
    return s->app->model->pmesh && s->app->pmesh_anc && s->app->pmesh_facing;
}

int mc_host_scene_init(mc_host_scene *s, const mc_app *app, mc_host_mode mode, const mc_octree_options *opt,
                       mc_fill fill)
{
    memset(s, 0, sizeof *s);
    s->app = app;
    s->octree = app->model->octree;
    s->mode = mode;
    s->opt = *opt;
    s->drawn_depth = 0;
    s->culled = 0;
    s->fill = fill;
    s->lod_want = UINT32_MAX;
    if (mc_host_scene_has_mesh(s)) {
        mc_pmesh_lod_init(&s->lod, app->model->pmesh, app->pmesh_anc);
        mc_pmesh_lod_set(&s->lod, app->model->pmesh->vertices);
    }
    return mode == MC_HOST_POINTS || mc_host_scene_has_mesh(s) ? 0 : -1;
}

static void set_level(mc_host_scene *s)
{
    if (!s->lod.pm) return;
    uint32_t level = s->lod_want;
    if (s->lod_cap && level > s->lod_cap) level = s->lod_cap;
    mc_pmesh_lod_set(&s->lod, level);
}

void mc_host_scene_set_level(mc_host_scene *s, uint32_t level)
{
    s->lod_want = level;
    set_level(s);
}

void mc_host_mesh_neighbours(mc_pmesh_lod *lod, const mc_app *app)
{
    const mc_pmesh *pm = lod->pm, *bake = app->model->pmesh;
    if (!lod->nbr && app->pmesh_nbr && pm && pm->opposite && bake &&
        MC_PMESH_NEIGHBOUR_BYTES(pm->faces, pm->half_bytes) <= MC_PMESH_NEIGHBOUR_BYTES(bake->faces, bake->half_bytes))
        mc_pmesh_lod_neighbours(lod, app->pmesh_nbr);
}

void mc_host_scene_stream_mesh(mc_host_scene *s, const mc_pmesh *pm, uint32_t level)
{
    if (!pm) {
        s->lod.pm = NULL;
        return;
    }
    const int first = s->lod.pm != pm;
    if (first) mc_pmesh_lod_init(&s->lod, pm, s->app->pmesh_anc);
    s->lod_cap = level;
    /* the first frame draws the finest level that has come; the automatic level of detail then
     * moves within it (mc_host_scene_draw) */
    if (first || s->target_ms <= 0) set_level(s);
}

void mc_host_scene_auto(mc_host_scene *s, double target_ms)
{
    s->target_ms = mc_host_scene_has_mesh(s) ? target_ms : 0;
    mc_host_lod_auto_init(&s->lod_auto, s->target_ms);
}

int mc_host_scene_draw(mc_host_scene *s, const mc_view *v, unsigned depth, mc_abort_fn abort, const mc_target *t,
                       uint32_t *drawn)
{
    if (s->mode == MC_HOST_POINTS) {
        mc_stats st = {0, 0, 0, 0, 0};
        mc_clear(t);
        int rc = mc_octree_render(s->octree, v, depth, &s->opt, t, abort, NULL, &st);
        if (st.aborted) return 1;
        s->drawn_depth = st.depth;
        s->culled = st.culled;
        mc_finish(t, s->fill);
        *drawn = st.points;
        return rc;
    }
    mc_front_mesh_stats st;
    if (!s->lod.pm) {   /* a streamed mesh whose base has not come */
        mc_clear(t);
        *drawn = 0;
        return MC_OK;
    }
    mc_front_style style = (mc_front_style)s->mode;
    if (!s->lod.pm->opposite) style = MC_FRONT_SHADED;   /* a streamed mesh before its adjacency */
    /* the neighbour table only while lines are drawn: shaded frames do not read it, and every level
     * change keeps it at a cost */
    if (style == MC_FRONT_SHADED) mc_pmesh_lod_neighbours(&s->lod, NULL);
    else mc_host_mesh_neighbours(&s->lod, s->app);
    const uint32_t level = s->lod.level;
    if (s->target_ms > 0) {
        mc_host_lod_auto_style(&s->lod_auto, (int)style);
        const mc_host_lod_plan plan = mc_host_lod_auto_plan(&s->lod_auto, s->lod.faces);
        if (plan.move) mc_pmesh_lod_fit_to(&s->lod, plan.max_faces, s->lod_cap ? s->lod_cap : UINT32_MAX);
        /* the change apart from the frame (lod_auto.h): the line styles' crease bits are part of it */
        if (s->lod.level != level && style != MC_FRONT_SHADED) mc_mesh_lines_level(&s->lod, s->app->pmesh_facing);
    }
    const double t0 = mc_host_now_ms();
    int rc = mc_front_mesh_frame(&s->lod, s->app->pmesh_facing, s->app->pmesh_cache, s->app->pmesh_sdepth, v,
                                 style, t, &st);
    if (s->target_ms > 0) mc_host_lod_auto_frame(&s->lod_auto, s->lod.faces, mc_host_now_ms() - t0);
    *drawn = st.faces.drawn;
    return rc;
}

const uint8_t *mc_host_scene_palette(const mc_host_scene *s)
{
    return s->mode == MC_HOST_POINTS ? s->octree->palette : s->lod.pm ? s->lod.pm->palette : s->app->model->pmesh->palette;
}
