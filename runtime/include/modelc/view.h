/* A view of a model: rotation, zoom, translation and projection.
 *
 * The model's bounding cube is centred on the screen; at zoom 1 its side spans the shorter side of
 * the target. Screen x grows to the right, y downwards; the model's +y is up and +z faces the viewer
 * at yaw = pitch = roll = 0. Rotation is R = Rz(roll) * Rx(pitch) * Ry(yaw), rebuilt from the integer
 * angles every frame.
 *
 * Any values are accepted. Values the fixed-point format cannot represent are clamped, never wrapped
 * (see mc_view_clamp): zoom to [1/64, 64] and to a screen extent of at most MC_COORD_LIMIT / 2 pixels,
 * translations to +-MC_COORD_LIMIT / 4 pixels, the perspective eye distance to [1/16, 256] cube sides.
 */
#ifndef MODELC_VIEW_H
#define MODELC_VIEW_H

#include <stdint.h>
#include "fixed.h"
#include "trig.h"

typedef enum mc_projection { MC_ORTHOGRAPHIC = 0, MC_PERSPECTIVE = 1 } mc_projection;

typedef struct mc_view {
    int32_t yaw, pitch, roll;   /* MC_ANGLE_FULL units per turn */
    int32_t zoom;               /* Q16: 65536 = 1 */
    int32_t tx, ty;             /* pixels, applied after projection */
    mc_projection projection;
    int32_t eye;                /* perspective only: eye distance from the model centre, Q16 cube sides */
} mc_view;

#define MC_ZOOM_ONE 65536
#define MC_ZOOM_MIN (MC_ZOOM_ONE / 64)
#define MC_ZOOM_MAX (MC_ZOOM_ONE * 64)
#define MC_EYE_MIN (MC_ZOOM_ONE / 16)
#define MC_EYE_MAX (MC_ZOOM_ONE * 256)

/* Frontal, zoom 1, orthographic, eye 2 cube sides away. */
mc_view mc_view_default(void);

/* The view the renderer really draws for a target of width x height pixels: v with every field
 * clamped to what the fixed-point format represents. */
mc_view mc_view_clamp(const mc_view *v, uint32_t width, uint32_t height);

/* Rotation matrix for the view's angles, Q30 entries (row-major r[row][col]). */
void mc_view_rotation(const mc_view *v, int32_t r[3][3]);

#endif
