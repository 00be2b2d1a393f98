/* What the host viewer draws: the model's octree as points, or its mesh part in a style, at a level
 * of detail. Shared by the one-shot outputs (PNG, PPM, bench) and the interactive terminal.
 *
 * Promise: mc_host_scene_draw fills a target with one frame of the scene's mode seen through a view:
 * points as the point renderer and mc_finish draw them, the mesh styles as
 * runtime/front/common/mesh_frame.h draws them (so the firmware's frames are the same bytes), at the
 * scene's current level of detail; mc_host_scene_palette is the palette its pixels index. The mesh
 * modes need a bake with a mesh part (--as both); the level-of-detail state lives in the app
 * binding's static memory (app.h).
 *
 * Automatic level of detail (mesh modes, target_ms > 0): lod_auto.h decides before each frame whether
 * to move the level and to what face budget, and learns from the frame's time; the level is set to
 * the finest within the budget (mc_pmesh_lod_fit: the same level on every machine for the same
 * budget), capped for a streamed mesh at the level that has come (mc_pmesh_lod_fit_to). The change
 * (the level set and, in the line styles, its crease bits brought over: mc_mesh_lines_level) is
 * timed apart from the frame. What was learned is dropped when the style changes (a level's time
 * in one style says nothing of another's).
 */
#ifndef MODELC_HOST_SCENE_H
#define MODELC_HOST_SCENE_H

#include <stdint.h>
#include <modelc/app.h>
#include <modelc/modelc.h>
#include "../common/mesh_frame.h"
#include "lod_auto.h"

typedef enum mc_host_mode {
    MC_HOST_POINTS = 0,
    MC_HOST_SHADED = MC_FRONT_SHADED,
    MC_HOST_LINES = MC_FRONT_LINES,
    MC_HOST_SHADED_LINES = MC_FRONT_SHADED_LINES
} mc_host_mode;

typedef struct mc_host_scene {
    const mc_app *app;
    const mc_octree *octree; /* points: what they draw, the model's octree unless a stream's level */
    mc_host_mode mode;
    mc_octree_options opt;   /* points */
    unsigned drawn_depth;    /* points: the level the last frame drew (opt.max_error may draw shallower) */
    uint32_t culled;         /* points: the back-facing nodes it skipped (opt.cull) */
    mc_fill fill;            /* points */
    mc_pmesh_lod lod;        /* the mesh part's level of detail (when the model has one; a stream's:
                                lod.pm NULL until its base has come) */
    uint32_t lod_want;       /* the level asked for (--lod, the keys); drawn as far as it has come */
    uint32_t lod_cap;        /* a streamed mesh: the finest level that has come (0: the whole mesh) */
    double target_ms;        /* > 0: automatic level of detail for this frame time */
    mc_host_lod_auto lod_auto;   /* what it has learned (lod_auto.h), in which style */
} mc_host_scene;

/* "points", "shaded", "lines", "shaded+lines" -> mode; returns -1 for anything else. */
int mc_host_mode_parse(const char *s, mc_host_mode *mode);
const char *mc_host_mode_name(mc_host_mode mode);

/* Sets the scene up in `mode` at the mesh's finest level. Returns 0, or -1 when the mode needs a
 * mesh part the model lacks. */
int mc_host_scene_init(mc_host_scene *s, const mc_app *app, mc_host_mode mode, const mc_octree_options *opt,
                       mc_fill fill);

/* Turns the automatic level of detail on (target_ms > 0) or off, from the current level's faces. */
void mc_host_scene_auto(mc_host_scene *s, double target_ms);

/* Whether the model has a mesh part. */
int mc_host_scene_has_mesh(const mc_host_scene *s);

/* Sets the mesh's level of detail as asked (clamped to what the mesh has, and for a streamed mesh
 * to what has come). */
void mc_host_scene_set_level(mc_host_scene *s, uint32_t level);

/* Draws a streamed mesh (stream.h) instead of the bake's in the mesh modes: pm, whose levels up to
 * `level` have come (pm NULL: nothing yet; the mesh modes then draw an empty frame). Call it again
 * as more comes. Until pm has its adjacency the line styles draw shaded. Not with --lod auto, whose
 * search moves past what has come. */
void mc_host_scene_stream_mesh(mc_host_scene *s, const mc_pmesh *pm, uint32_t level);

/* Gives lod the app binding's neighbour table (a bake with --mesh-neighbours; pmesh.h
 * mc_pmesh_lod_neighbours) when it has none yet, lod's mesh has its adjacency (a streamed mesh's comes
 * last) and the table fits the bake's room for it. The same frames with or without it. */
void mc_host_mesh_neighbours(mc_pmesh_lod *lod, const mc_app *app);

/* Draws one frame into t; depth: the octree depth (points). *drawn: points (points) or faces drawn
 * (mesh). abort: polled by the point renderer only. Returns the renderer's MC_OK or MC_ERR_*; 1 when
 * the point renderer gave up (abort). */
int mc_host_scene_draw(mc_host_scene *s, const mc_view *v, unsigned depth, mc_abort_fn abort, const mc_target *t,
                       uint32_t *drawn);

const uint8_t *mc_host_scene_palette(const mc_host_scene *s);

#endif
