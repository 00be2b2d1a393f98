/* The turn every mesh benchmark draws (mesh_frames.c, osmesa_mesh.c): frame i of n at yaw
 * i * MC_ANGLE_FULL / n, orthographic, zoom 1, no pitch or roll, as the viewer starts. One
 * definition, so that modelc and Mesa are always given the same views. */
#ifndef MODELC_BENCH_TURN_H
#define MODELC_BENCH_TURN_H

#include <stdint.h>
#include "modelc/xform.h"

static inline mc_view bench_turn_view(int32_t yaw)
{
    mc_view v = mc_view_default();
    v.yaw = yaw;
    v.pitch = 0;
    v.roll = 0;
    v.zoom = MC_ZOOM_ONE;
    v.projection = MC_ORTHOGRAPHIC;
    return v;
}

static inline int32_t bench_turn_yaw(int i, int n) { return (int32_t)((int64_t)MC_ANGLE_FULL * i / n); }

#endif
