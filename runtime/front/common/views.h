/* The fixed list of views that the firmware renders and the host viewer's --checksums renders too.
 *
 * Promise: both front ends read this one table, in runtime units only (angles MC_ANGLE_FULL per
 * turn, zoom Q16, translation in pixels), so they draw exactly the same views with no floating
 * point conversion on either side. The list covers the hot path (wholly on screen), the clipped
 * path (zoomed past the screen edge), translation, roll and perspective (64-bit division and
 * mc_mul_shift64), so a checksum mismatch on any of them shows an architecture-dependent result.
 * The point frames are these views with the default options, then frames.h's views with the
 * renderer's options set (culling off, level of detail, squares); the mesh frames are these views.
 * Header only, freestanding (<stdint.h> and the runtime's headers).
 */
#ifndef MODELC_FRONT_VIEWS_H
#define MODELC_FRONT_VIEWS_H

#include <stdint.h>
#include <modelc/xform.h>

typedef struct mc_front_view {
    int32_t yaw, pitch, roll;   /* MC_ANGLE_FULL (4096) units per turn */
    int32_t zoom;               /* Q16 */
    int32_t tx, ty;             /* pixels */
    int32_t eye;                /* Q16 cube sides; 0 = orthographic */
} mc_front_view;

static const mc_front_view mc_front_views[] = {
    {0, 0, 0, 65536, 0, 0, 0},               /* frontal, as the source paper measures */
    {341, 114, 0, 65536, 0, 0, 0},           /* yaw ~30 deg, pitch ~10 deg */
    {1024, 0, 0, 65536, 0, 0, 0},            /* side */
    {2048, -228, 0, 65536, 0, 0, 0},         /* back, from below */
    {512, 0, 512, 65536, 0, 0, 0},           /* rolled 45 deg */
    {200, 50, 0, 114688, 0, 0, 0},           /* zoom 1.75: reaches off screen (clipped path) */
    {-700, 300, 0, 32768, 20, -10, 0},       /* zoom 0.5, translated */
    {-400, 150, 0, 65536, 0, 0, 131072},     /* perspective, eye 2 cube sides away */
    {900, -100, 0, 52429, 0, 0, 49152},      /* perspective, eye 0.75: the near plane cuts */
};

#define MC_FRONT_VIEW_COUNT ((unsigned)(sizeof mc_front_views / sizeof mc_front_views[0]))

/* The view whose frame the firmware writes out (and the host --checksums --ppm writes). */
#define MC_FRONT_PPM_VIEW 1u

/* The runtime's view of a table entry. */
static inline mc_view mc_front_view_of(const mc_front_view *f)
{
    mc_view v = mc_view_default();
    v.yaw = f->yaw;
    v.pitch = f->pitch;
    v.roll = f->roll;
    v.zoom = f->zoom;
    v.tx = f->tx;
    v.ty = f->ty;
    if (f->eye) {
        v.projection = MC_PERSPECTIVE;
        v.eye = f->eye;
    }
    return v;
}

static inline mc_view mc_front_view_get(unsigned i) { return mc_front_view_of(&mc_front_views[i]); }

#endif
