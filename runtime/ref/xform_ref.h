/* Double-precision reference of the vertex projection (modelc/xform.h mc_xform_vertex), for tests
 * only: the same clamped view and Q30 rotation, everything after it in doubles. */
#ifndef MODELC_XFORM_REF_H
#define MODELC_XFORM_REF_H

#include <stdint.h>
#include <modelc/xform.h>

typedef struct mc_ref_vertex {
    double x, y, z, d;   /* pixels; depth units; distance from the eye (cube sides) */
    int near, out;       /* before the near plane (no position); beyond the guard band */
} mc_ref_vertex;

/* p: unit-cube Q16 coordinates (pmesh.h), seen through view on a w x h target. */
mc_ref_vertex mc_ref_project(const mc_view *view, uint32_t w, uint32_t h, const int32_t p[3]);

#endif
