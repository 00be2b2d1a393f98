/* One checked frame: the exact sequence both the firmware and the host viewer's --checksums run.
 *
 * Promise: mc_front_frame renders view i of views.h into the target (mc_clear, mc_octree_render at
 * the given depth with the default options, mc_finish_pixel_holes) and hashes the finished colour and
 * depth buffers with FNV-1a (32-bit; colour bytes first, then each depth as its low byte then its
 * high byte, so the hash does not depend on the machine's byte order). MC_FRONT_FRAME_LINE /
 * MC_FRONT_FRAME_ARGS print it as one line, the same on both sides, so a test compares the
 * firmware's and the host's lines as text. MC_FRONT_MARK(stage) is called between the stages (empty
 * unless the includer defines it: the firmware marks them for instruction counting under QEMU).
 * Header only, freestanding.
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

typedef struct mc_front_result {
    int rc;              /* mc_octree_render's return value */
    uint32_t points;     /* mc_stats.points */
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
    mc_view v = mc_front_view_get(i);
    MC_FRONT_MARK(MC_FRONT_MARK_CLEAR);
    mc_clear(t);
    MC_FRONT_MARK(MC_FRONT_MARK_RENDER);
    r.rc = mc_octree_render(octree, &v, depth, 0, t, 0, 0, &st);
    MC_FRONT_MARK(MC_FRONT_MARK_FINISH);
    r.filled = mc_finish_pixel_holes(t);
    MC_FRONT_MARK(MC_FRONT_MARK_DONE);
    r.points = r.rc == MC_OK ? st.points : 0;
    r.hash = mc_front_fnv1a(t);
    return r;
}

/* printf(MC_FRONT_FRAME_LINE, MC_FRONT_FRAME_ARGS(i, depth, t, r)): casts to long so that int32_t (long on
 * arm-none-eabi, int on x86-64) prints the same everywhere. */
#define MC_FRONT_FRAME_LINE "frame %u yaw %ld pitch %ld roll %ld zoom %ld tx %ld ty %ld eye %ld depth %u size %ux%u rc %d points %lu filled %lu fnv1a %08lx\n"
#define MC_FRONT_FRAME_ARGS(i, depth, t, r)                                                              \
    (i), (long)mc_front_views[i].yaw, (long)mc_front_views[i].pitch, (long)mc_front_views[i].roll,            \
        (long)mc_front_views[i].zoom, (long)mc_front_views[i].tx, (long)mc_front_views[i].ty,                 \
        (long)mc_front_views[i].eye, (depth), (unsigned)(t)->width, (unsigned)(t)->height, (r).rc,      \
        (unsigned long)(r).points, (unsigned long)(r).filled, (unsigned long)(r).hash

#endif
