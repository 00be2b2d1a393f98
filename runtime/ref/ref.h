/* Double-precision reference renderer of a baked octree, for tests and benchmarks only: never
 * linked into a viewer or firmware. It follows the conventions of modelc/xform.h exactly (same
 * clamped view, same integer angles, same screen mapping), computing every leaf's position from its
 * integer cell coordinates in double precision instead of by fixed-point additions. */
#ifndef MODELC_REF_H
#define MODELC_REF_H

#include <modelc/octree_render.h>

typedef struct mc_ref_point {
    double sx, sy;          /* screen position in pixels (pixel i covers [i, i+1)) */
    double depth;           /* in cube sides, offset by 1 like the runtime's; smaller is nearer */
    const uint8_t *color;   /* the leaf's palette index, the same pointer the runtime's hook sees */
    int on_screen;          /* 0 for points off the target or at/behind the perspective near plane */
} mc_ref_point;

typedef void (*mc_ref_fn)(const mc_ref_point *p, void *user);

/* The view's rotation R = Rz(roll) * Rx(pitch) * Ry(yaw) (modelc/xform.h) in double precision, from
 * the already clamped view v. Shared by the reference renderers. */
void mc_ref_rotation(const mc_view *v, double r[3][3]);

/* Calls fn for every leaf at `depth`, in stored order. */
void mc_ref_points(const mc_octree *scene, const mc_view *view, unsigned depth, unsigned width,
                   unsigned height, mc_ref_fn fn, void *user);

/* Z-buffered one-pixel-per-leaf image: fills t->color, and t->depth with 0 where a point landed and
 * MC_DEPTH_EMPTY elsewhere; the nearest point wins on exact double depth. zbuf: width * height
 * doubles of scratch. */
void mc_ref_render(const mc_octree *scene, const mc_view *view, unsigned depth, const mc_target *t,
                   double *zbuf);

#endif
