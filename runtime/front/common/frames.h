/* The checked point frames: the exact sequence both the firmware and the host viewer's --checksums run.
 *
 * Promise: point frame i (0 <= i < MC_FRONT_FRAME_COUNT) is view i of views.h with the default
 * options for i < MC_FRONT_VIEW_COUNT, then the frames of mc_front_option_frames, each a view with
 * the renderer's options set (culling off, a level-of-detail bound, a magnified view whose leaves are
 * squares), so that the paths they take are checked across machines and measured (make
 * bench-firmware) beside a frame that differs from them in one thing. mc_front_frame renders frame i
 * into the target (mc_clear, mc_octree_render at the given depth with the frame's options,
 * mc_finish_pixel_holes) and hashes the finished colour and depth buffers with FNV-1a (32-bit; colour
 * bytes first, then each depth as its low byte then its high byte, so the hash does not depend on the
 * machine's byte order). MC_FRONT_FRAME_LINE / MC_FRONT_FRAME_ARGS print it as one line, the same on
 * both sides (the view, the options, the level drawn, the leaves drawn and the nodes culled, the
 * hash), so a test compares the firmware's and the host's lines as text. MC_FRONT_MARK(stage) is
 * called between the stages (empty unless the includer defines it: the firmware marks them for
 * instruction counting under QEMU). Header only, freestanding.
 */
#ifndef MODELC_FRONT_FRAMES_H
#define MODELC_FRONT_FRAMES_H

#include <stdint.h>
#include <modelc/modelc.h>
#include "views.h"

#ifndef MC_FRONT_MARK
#define MC_FRONT_MARK(stage) ((void)0)
#endif

/* stages passed to MC_FRONT_MARK */
enum { MC_FRONT_MARK_CLEAR = 0, MC_FRONT_MARK_RENDER = 1, MC_FRONT_MARK_FINISH = 2, MC_FRONT_MARK_DONE = 3 };

/* The point frames after the views of views.h: a view with the renderer's options. Each is measured
 * against the frame that differs from it in one thing (tests/fw/bench.sh pairs them: the same view
 * with other options, or for the squares the same options at zoom 1). The level-of-detail frames'
 * levels at the boards' bakes: zoom 0.25 draws level 6 of 8 at 320x240 and 5 of 7 at 160x128; zoom
 * 0.5 level 7 of 8 and 6 of 7. The squares frame (zoom 1.2) draws bunny00 wholly on either board's
 * screen with 2x2 squares (a leaf spans 1.125 and 1.2 pixels). */
typedef struct mc_front_option_frame {
    mc_front_view view;
    uint16_t max_error;   /* mc_octree_options.max_error: Q4 pixels, 0 = the depth asked */
    uint8_t cull;         /* mc_octree_options.cull (mc_cull) */
} mc_front_option_frame;

static const mc_front_option_frame mc_front_option_frames[] = {
    {{0, 0, 0, 65536, 0, 0, 0}, 0, MC_CULL_OFF},                   /* view 0, back-facing subtrees drawn */
    {{341, 114, 0, 65536, 0, 0, 0}, 0, MC_CULL_OFF},               /* view 1, the same */
    {{341, 114, 0, 16384, 0, 0, 0}, 0, MC_CULL_DEFAULT},           /* zoom 0.25 at the bake's depth */
    {{341, 114, 0, 16384, 0, 0, 0}, MC_LOD_PIXEL, MC_CULL_DEFAULT}, /* the same, level of detail at one pixel */
    {{-700, 300, 0, 32768, 20, -10, 0}, MC_LOD_PIXEL, MC_CULL_DEFAULT}, /* view 6, level of detail at one pixel */
    {{1024, 0, 1024, 78643, 0, 0, 0}, 0, MC_CULL_DEFAULT},         /* side view rolled 90 deg, zoom 1.2: 2x2 squares */
    {{1024, 0, 1024, 65536, 0, 0, 0}, 0, MC_CULL_DEFAULT},         /* the same at zoom 1: one pixel a leaf */
};

#define MC_FRONT_FRAME_COUNT \
    (MC_FRONT_VIEW_COUNT + (unsigned)(sizeof mc_front_option_frames / sizeof mc_front_option_frames[0]))

/* Point frame i's view and options. */
static inline const mc_front_view *mc_front_frame_view(unsigned i)
{
    return i < MC_FRONT_VIEW_COUNT ? &mc_front_views[i] : &mc_front_option_frames[i - MC_FRONT_VIEW_COUNT].view;
}

static inline mc_octree_options mc_front_frame_options(unsigned i)
{
    mc_octree_options o = {MC_SPLAT_DEFAULT, 0, MC_CULL_DEFAULT};
    if (i >= MC_FRONT_VIEW_COUNT) {
        o.max_error = mc_front_option_frames[i - MC_FRONT_VIEW_COUNT].max_error;
        o.cull = (mc_cull)mc_front_option_frames[i - MC_FRONT_VIEW_COUNT].cull;
    }
    return o;
}

typedef struct mc_front_result {
    int rc;              /* mc_octree_render's return value */
    uint32_t points;     /* mc_stats.points */
    uint32_t level;      /* mc_stats.depth: the level drawn */
    uint32_t culled;     /* mc_stats.culled: back-facing nodes skipped */
    uint32_t filled;     /* pixels mc_finish_pixel_holes filled */
    uint32_t hash;       /* FNV-1a of the finished colour and depth buffers */
} mc_front_result;

static inline uint32_t mc_front_fnv1a(const mc_target *t)
{
    const uint32_t n = (uint32_t)t->width * t->height;
    uint32_t h = 2166136261u;
    for (uint32_t i = 0; i < n; i++) h = (h ^ t->color[i]) * 16777619u;
    for (uint32_t i = 0; i < n; i++) {
        h = (h ^ (t->depth[i] & 0xFFu)) * 16777619u;
        h = (h ^ (uint32_t)(t->depth[i] >> 8)) * 16777619u;
    }
    return h;
}

static inline mc_front_result mc_front_frame(const mc_octree *octree, unsigned i, unsigned depth, const mc_target *t)
{
    mc_front_result r;
    mc_stats st;
    mc_view v = mc_front_view_of(mc_front_frame_view(i));
    const mc_octree_options opt = mc_front_frame_options(i);
    MC_FRONT_MARK(MC_FRONT_MARK_CLEAR);
    mc_clear(t);
    MC_FRONT_MARK(MC_FRONT_MARK_RENDER);
    r.rc = mc_octree_render(octree, &v, depth, &opt, t, 0, 0, &st);
    MC_FRONT_MARK(MC_FRONT_MARK_FINISH);
    r.filled = mc_finish_pixel_holes(t);
    MC_FRONT_MARK(MC_FRONT_MARK_DONE);
    r.points = r.rc == MC_OK ? st.points : 0;
    r.level = r.rc == MC_OK ? st.depth : 0;
    r.culled = r.rc == MC_OK ? st.culled : 0;
    r.hash = mc_front_fnv1a(t);
    return r;
}

/* printf(MC_FRONT_FRAME_LINE, MC_FRONT_FRAME_ARGS(i, depth, t, r)): casts to long so that int32_t (long on
 * arm-none-eabi, int on x86-64) prints the same everywhere. */
#define MC_FRONT_FRAME_LINE                                                                                  \
    "frame %u yaw %ld pitch %ld roll %ld zoom %ld tx %ld ty %ld eye %ld error %u cull %s depth %u level %lu "  \
    "size %ux%u rc %d points %lu culled %lu filled %lu fnv1a %08lx\n"
#define MC_FRONT_FRAME_ARGS(i, depth, t, r)                                                                     \
    (i), (long)mc_front_frame_view(i)->yaw, (long)mc_front_frame_view(i)->pitch,                               \
        (long)mc_front_frame_view(i)->roll, (long)mc_front_frame_view(i)->zoom, (long)mc_front_frame_view(i)->tx, \
        (long)mc_front_frame_view(i)->ty, (long)mc_front_frame_view(i)->eye,                                    \
        (unsigned)mc_front_frame_options(i).max_error,                                                          \
        mc_front_frame_options(i).cull == MC_CULL_OFF ? "off" : "on", (depth), (unsigned long)(r).level,        \
        (unsigned)(t)->width, (unsigned)(t)->height, (r).rc, (unsigned long)(r).points,                         \
        (unsigned long)(r).culled, (unsigned long)(r).filled, (unsigned long)(r).hash

#endif
