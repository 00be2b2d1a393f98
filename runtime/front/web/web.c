/* The web viewer's module: the runtime and one bake, compiled for wasm32 with no libc and no
 * emscripten (clang --target=wasm32 -nostdlib, wasm-ld; see the Makefile's web rules), and driven by
 * viewer.js.
 *
 * Promise: the module imports nothing and exports its memory and the mcw_* functions below. mcw_draw
 * draws one frame of the model's points the way the native viewer does (front/host/scene.c: mc_clear,
 * mc_octree_render with the viewer's default options and the given level-of-detail bound, mc_finish
 * with the default fill) and leaves it at mcw_rgba() as RGBA rows for a canvas: for the same view and
 * size, the same pixels as the native viewer's PNG, byte for byte (tests/web). The view comes in the
 * runtime's own integers (angles in MC_ANGLE_FULL units a turn, zoom in Q16, the bound in
 * MC_LOD_PIXEL units), so the page and the native viewer cannot round it differently. All memory is
 * static: the bake's frame buffers (app.h) and one RGBA frame of MC_WEB_MAX_PIXELS pixels, which the
 * build sets to the bake's screen size.
 */
#include <stdint.h>
#include <modelc/app.h>
#include <modelc/modelc.h>
#include "../common/rgb.h"

/* MC_WEB_MAX_PIXELS: the RGBA frame's size in pixels; the build passes the bake's screen
 * (MC_NAME_SCREEN_WIDTH * MC_NAME_SCREEN_HEIGHT from NAME.h). */
#ifndef MC_WEB_MAX_PIXELS
#error "MC_WEB_MAX_PIXELS: define it as the bake's screen width times height (make web does)"
#endif

#define EXPORT(name) __attribute__((export_name(name)))

static uint8_t rgba[4u * (MC_WEB_MAX_PIXELS)];
static mc_stats last;

EXPORT("mcw_max_width") uint32_t mcw_max_width(void) { return mc_app_model.max_width; }
EXPORT("mcw_max_height") uint32_t mcw_max_height(void) { return mc_app_model.max_height; }
EXPORT("mcw_depth") uint32_t mcw_depth(void) { return mc_app_model.model->octree ? mc_app_model.model->octree->depth : 0; }
EXPORT("mcw_name") const char *mcw_name(void) { return mc_app_model.model->name; }
EXPORT("mcw_rgba") const uint8_t *mcw_rgba(void) { return rgba; }
/* the last frame's leaves drawn and the level drawn (mc_stats) */
EXPORT("mcw_drawn") uint32_t mcw_drawn(void) { return last.points; }
EXPORT("mcw_drawn_depth") uint32_t mcw_drawn_depth(void) { return last.depth; }

/* Draws a w x h frame; returns MC_OK, a renderer's MC_ERR_*, or MC_ERR_ARG when the model has no
 * points or w x h exceeds the bake's screen. */
EXPORT("mcw_draw")
int32_t mcw_draw(uint32_t w, uint32_t h, int32_t yaw, int32_t pitch, int32_t zoom, uint32_t max_error)
{
    const mc_octree *octree = mc_app_model.model->octree;
    if (!octree || w < 1 || h < 1 || w > mc_app_model.max_width || h > mc_app_model.max_height ||
        (uint64_t)w * h > (MC_WEB_MAX_PIXELS) || max_error > 0xFFFFu)
        return MC_ERR_ARG;
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)w, (uint16_t)h};
    mc_view v = mc_view_default();
    v.yaw = yaw;
    v.pitch = pitch;
    v.zoom = zoom;
    const mc_octree_options opt = {MC_SPLAT_DEFAULT, (uint16_t)max_error, MC_CULL_DEFAULT};
    mc_stats st = {0, 0, 0, 0, 0};
    mc_clear(&t);
    const int rc = mc_octree_render(octree, &v, octree->depth, &opt, &t, 0, 0, &st);
    last = st;
    if (rc != MC_OK) return rc;
    mc_finish(&t, MC_FILL_DEFAULT);
    mc_front_rgba(&t, octree->palette, 0, w * h, rgba);
    return MC_OK;
}
