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
 *
 * A bake with a mesh part (--as both) is drawn as a mesh too: mcw_draw_mesh draws one frame of it in
 * a style (shaded, lines, shaded + lines) at a level of detail through the same sequence as the
 * native viewer's mesh modes (front/common/mesh_frame.h: mc_front_mesh_frame over the app binding's
 * level-of-detail memory, the level set by mc_pmesh_lod_set), so for the same view, style, level
 * and size, the same pixels as the native viewer's --mode STYLE --lod LEVEL. The level state is the
 * module's: a level reached from any other is the same bytes (pmesh.h).
 *
 * Built with MC_WEB_STREAM_BYTES (the stream page, build.sh), the module holds no bake: the model
 * arrives as a stream (modelc/stream.h) that viewer.js copies piece by piece into mcw_scratch() and
 * hands to mcw_feed, into a static receive buffer of MC_WEB_STREAM_BYTES (the bake's
 * MC_NAME_STREAM_BYTES); mcw_draw then draws the deepest complete level, exactly as the native
 * viewer draws the bake at that depth, and keeps drawing it after the stream fails. The frame
 * buffers are its own, MC_WEB_MAX_WIDTH x MC_WEB_MAX_HEIGHT. For a bake with a mesh part build.sh
 * also passes its level-of-detail sizes (MC_WEB_PMESH_*: NAME.h's), and the streamed mesh is drawn
 * as it comes: mcw_draw_mesh clamps the level to the splits that have come (mcw_mesh_cap), and the
 * line styles draw shaded until the adjacency has (as the native viewer's --stream).
 */
#include <stdint.h>
#include <modelc/modelc.h>
#include "../common/rgb.h"
#ifdef MC_WEB_STREAM_BYTES
#include <modelc/stream.h>
#else
#include <modelc/app.h>
#endif
#include "../common/mesh_frames.h"

/* MC_WEB_MAX_PIXELS: the RGBA frame's size in pixels; the build passes the bake's screen
 * (MC_NAME_SCREEN_WIDTH * MC_NAME_SCREEN_HEIGHT from NAME.h). */
#ifndef MC_WEB_MAX_PIXELS
#error "MC_WEB_MAX_PIXELS: define it as the bake's screen width times height (make web does)"
#endif

#define EXPORT(name) __attribute__((export_name(name)))

static uint8_t rgba[4u * (MC_WEB_MAX_PIXELS)];
static mc_stats last;

#ifdef MC_WEB_STREAM_BYTES
#if !defined MC_WEB_MAX_WIDTH || !defined MC_WEB_MAX_HEIGHT
#error "MC_WEB_MAX_WIDTH, MC_WEB_MAX_HEIGHT: the bake's screen (build.sh passes them with MC_WEB_STREAM_BYTES)"
#endif
/* a fetch delivers pieces of any size; viewer.js copies them here at most this much at a time */
#define SCRATCH_BYTES 65536u
static uint8_t stream_buf[MC_WEB_STREAM_BYTES];
static uint8_t scratch[SCRATCH_BYTES];
static uint8_t frame_color[(MC_WEB_MAX_WIDTH) * (MC_WEB_MAX_HEIGHT)];
static uint16_t frame_depth[(MC_WEB_MAX_WIDTH) * (MC_WEB_MAX_HEIGHT)];
static mc_stream reader;
static int reader_ready;

static mc_stream *stream(void)
{
    if (!reader_ready) {   /* no start-up code without libc: set up on first use */
        mc_stream_init(&reader, stream_buf, MC_WEB_STREAM_BYTES);
        reader_ready = 1;
    }
    return &reader;
}
#define MODEL_OCTREE mc_stream_octree(stream())
#define MAX_WIDTH (MC_WEB_MAX_WIDTH)
#define MAX_HEIGHT (MC_WEB_MAX_HEIGHT)
#define FRAME_COLOR frame_color
#define FRAME_DEPTH frame_depth

EXPORT("mcw_scratch") uint8_t *mcw_scratch(void) { return scratch; }
EXPORT("mcw_scratch_bytes") uint32_t mcw_scratch_bytes(void) { return SCRATCH_BYTES; }
/* Feeds the first n bytes of the scratch area; the reader's MC_STREAM_* code (sticky). */
EXPORT("mcw_feed") int32_t mcw_feed(uint32_t n)
{
    return n <= SCRATCH_BYTES ? mc_stream_feed(stream(), scratch, n) : MC_STREAM_ERR_ARG;
}
/* The input ended: MC_STREAM_OK when the stream was complete, else its error. */
EXPORT("mcw_end") int32_t mcw_end(void) { return mc_stream_end(stream()); }
/* where the stream is: the bytes in the buffer, the header's total (0 until read) and depth D,
 * the first error and the byte offset where it was found, and the buffer's size */
EXPORT("mcw_stream_len") uint32_t mcw_stream_len(void) { return stream()->len; }
EXPORT("mcw_stream_total") uint32_t mcw_stream_total(void) { return stream()->total; }
EXPORT("mcw_stream_levels") uint32_t mcw_stream_levels(void) { return stream()->depth; }
EXPORT("mcw_stream_error") int32_t mcw_stream_error(void) { return stream()->error; }
EXPORT("mcw_stream_error_at") uint32_t mcw_stream_error_at(void) { return stream()->error_at; }
EXPORT("mcw_stream_error_name") const char *mcw_stream_error_name(int32_t error) { return mc_stream_error_name(error); }
EXPORT("mcw_stream_cap") uint32_t mcw_stream_cap(void) { return MC_WEB_STREAM_BYTES; }
#else
#define MODEL_OCTREE mc_app_model.model->octree
#define MAX_WIDTH mc_app_model.max_width
#define MAX_HEIGHT mc_app_model.max_height
#define FRAME_COLOR mc_app_model.color
#define FRAME_DEPTH mc_app_model.depth
#endif

EXPORT("mcw_max_width") uint32_t mcw_max_width(void) { return MAX_WIDTH; }
EXPORT("mcw_max_height") uint32_t mcw_max_height(void) { return MAX_HEIGHT; }
/* the model's depth: the bake's, or the stream's deepest complete level (0: nothing drawable) */
EXPORT("mcw_depth") uint32_t mcw_depth(void) { return MODEL_OCTREE ? MODEL_OCTREE->depth : 0; }
#ifndef MC_WEB_STREAM_BYTES
EXPORT("mcw_name") const char *mcw_name(void) { return mc_app_model.model->name; }
#endif
EXPORT("mcw_rgba") const uint8_t *mcw_rgba(void) { return rgba; }
/* the last frame's leaves drawn and the level drawn (mc_stats) */
EXPORT("mcw_drawn") uint32_t mcw_drawn(void) { return last.points; }
EXPORT("mcw_drawn_depth") uint32_t mcw_drawn_depth(void) { return last.depth; }

/* The w x h target over the frame buffers and the view (the default one turned and zoomed); 0 when
 * w x h is empty or exceeds the screen. */
static int frame(uint32_t w, uint32_t h, int32_t yaw, int32_t pitch, int32_t zoom, mc_target *t, mc_view *v)
{
    if (w < 1 || h < 1 || w > MAX_WIDTH || h > MAX_HEIGHT || (uint64_t)w * h > (MC_WEB_MAX_PIXELS)) return 0;
    t->color = FRAME_COLOR, t->depth = FRAME_DEPTH, t->width = (uint16_t)w, t->height = (uint16_t)h;
    *v = mc_view_default();
    v->yaw = yaw, v->pitch = pitch, v->zoom = zoom;
    return 1;
}

/* Draws a w x h frame; returns MC_OK, a renderer's MC_ERR_*, or MC_ERR_ARG when the model has no
 * points (a stream: nothing drawable yet) or w x h exceeds the bake's screen. */
EXPORT("mcw_draw")
int32_t mcw_draw(uint32_t w, uint32_t h, int32_t yaw, int32_t pitch, int32_t zoom, uint32_t max_error)
{
    const mc_octree *octree = MODEL_OCTREE;
    mc_target t;
    mc_view v;
    if (!octree || max_error > 0xFFFFu || !frame(w, h, yaw, pitch, zoom, &t, &v)) return MC_ERR_ARG;
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

/* ---- the mesh part ---- */
#ifdef MC_WEB_STREAM_BYTES
#ifdef MC_WEB_PMESH_VERTICES
/* the level-of-detail memory of the bake's mesh part (build.sh passes its sizes), as its app
 * binding declares it; a streamed mesh larger than it is not drawn */
static uint32_t pmesh_anc[(MC_WEB_PMESH_LOD_BYTES + 3u) / 4u];
static uint32_t pmesh_facing[(MC_WEB_PMESH_FACING_BYTES + 3u) / 4u];
static mc_xvertex pmesh_cache[MC_WEB_PMESH_VERTICES];
static uint32_t pmesh_sdepth[MC_SDEPTH_WORDS(MC_WEB_MAX_WIDTH, MC_WEB_MAX_HEIGHT)];
#define PMESH_ANC pmesh_anc
#define PMESH_FACING ((uint8_t *)pmesh_facing)
#define PMESH_CACHE pmesh_cache
#define PMESH_SDEPTH pmesh_sdepth
#define PMESH_NBR 0
static const mc_pmesh *mesh_part(void)
{
    const mc_pmesh *pm = mc_stream_pmesh(stream());
    return pm && mc_front_mesh_fits(pm, MC_WEB_PMESH_VERTICES, MC_WEB_PMESH_LOD_BYTES, MC_WEB_PMESH_FACING_BYTES) ? pm
                                                                                                               : 0;
}
/* the levels that have come */
static uint32_t mesh_cap(void) { return mc_stream_mesh_level(stream()); }
#else
#define PMESH_ANC 0
#define PMESH_FACING 0
#define PMESH_CACHE 0
#define PMESH_SDEPTH 0
#define PMESH_NBR 0
static const mc_pmesh *mesh_part(void) { return 0; }   /* a points bake's stream page */
static uint32_t mesh_cap(void) { return 0; }
#endif
#else
#define PMESH_ANC mc_app_model.pmesh_anc
#define PMESH_FACING mc_app_model.pmesh_facing
#define PMESH_CACHE mc_app_model.pmesh_cache
#define PMESH_SDEPTH mc_app_model.pmesh_sdepth
#define PMESH_NBR mc_app_model.pmesh_nbr   /* (a bake with --mesh-neighbours; else none) */
static const mc_pmesh *mesh_part(void)
{
    const mc_pmesh *pm = mc_app_model.model->pmesh;
    return pm && mc_app_model.pmesh_anc && mc_app_model.pmesh_facing ? pm : 0;
}
static uint32_t mesh_cap(void) { return mc_app_model.model->pmesh ? mc_app_model.model->pmesh->vertices : 0; }
#endif

static mc_pmesh_lod lod;
static mc_front_mesh_stats mesh_last;

/* the mesh part with its level of detail set up (null: none, or a stream's not yet come) */
static const mc_pmesh *mesh(void)
{
    const mc_pmesh *pm = mesh_part();
    if (pm && lod.pm != pm) {   /* at the finest level that has come, as the native viewer starts */
        mc_pmesh_lod_init(&lod, pm, PMESH_ANC);
        mc_pmesh_lod_neighbours(&lod, PMESH_NBR);
        mc_pmesh_lod_set(&lod, mesh_cap() < pm->vertices ? mesh_cap() : pm->vertices);
    }
    return pm;
}

/* the mesh's vertices, full and base (0: no mesh part), the finest level that has come (a stream's;
 * the full mesh for a bake), whether the line styles can draw (a stream's adjacency has come), and
 * the level drawn last: its vertices and faces; the last frame's faces that covered a pixel and line
 * pixels before the depth test */
EXPORT("mcw_mesh_vertices") uint32_t mcw_mesh_vertices(void) { return mesh() ? mesh()->vertices : 0; }
EXPORT("mcw_mesh_base_vertices") uint32_t mcw_mesh_base_vertices(void) { return mesh() ? mesh()->base_vertices : 0; }
EXPORT("mcw_mesh_cap") uint32_t mcw_mesh_cap(void) { return mesh() ? mesh_cap() : 0; }
/* the vertices of a stream's mesh that came but does not fit this page's mesh memory (a stream of
 * another bake; 0: it fits, or none came) */
EXPORT("mcw_mesh_refused") uint32_t mcw_mesh_refused(void)
{
#ifdef MC_WEB_STREAM_BYTES
    const mc_pmesh *pm = mc_stream_pmesh(stream());
    return pm && !mesh_part() ? pm->vertices : 0;
#else
    return 0;
#endif
}
EXPORT("mcw_mesh_lines_ready") uint32_t mcw_mesh_lines_ready(void) { return mesh() && mesh()->opposite; }
EXPORT("mcw_mesh_level") uint32_t mcw_mesh_level(void) { return mesh() ? lod.level : 0; }
EXPORT("mcw_mesh_faces") uint32_t mcw_mesh_faces(void) { return mesh() ? lod.faces : 0; }
EXPORT("mcw_mesh_drawn") uint32_t mcw_mesh_drawn(void) { return mesh_last.faces.drawn; }
EXPORT("mcw_mesh_line_pixels") uint32_t mcw_mesh_line_pixels(void) { return mesh_last.lines.pixels; }

/* Draws a w x h frame of the mesh in style (1 shaded, 2 lines, 3 shaded + lines, mesh_frame.h) at
 * `level` vertices, clamped to the base and to the finest level that has come; a line style draws
 * shaded until a stream's adjacency has come (as the native viewer). Returns MC_OK, a renderer's
 * MC_ERR_*, or MC_ERR_ARG when there is no mesh (yet), the style is none of these or w x h exceeds
 * the screen. */
EXPORT("mcw_draw_mesh")
int32_t mcw_draw_mesh(uint32_t w, uint32_t h, int32_t yaw, int32_t pitch, int32_t zoom, uint32_t style, uint32_t level)
{
    const mc_pmesh *pm = mesh();
    mc_target t;
    mc_view v;
    if (!pm || style < MC_FRONT_SHADED || style > MC_FRONT_SHADED_LINES || !frame(w, h, yaw, pitch, zoom, &t, &v))
        return MC_ERR_ARG;
    const uint32_t cap = mesh_cap() < pm->vertices ? mesh_cap() : pm->vertices;
    mc_pmesh_lod_set(&lod, level < pm->base_vertices ? pm->base_vertices : level > cap ? cap : level);
    if (!pm->opposite) style = MC_FRONT_SHADED;
    const int rc = mc_front_mesh_frame(&lod, PMESH_FACING, PMESH_CACHE, PMESH_SDEPTH, &v, (mc_front_style)style, &t,
                                       &mesh_last);
    if (rc != MC_OK) return rc;
    mc_front_rgba(&t, pm->palette, 0, w * h, rgba);
    return MC_OK;
}
