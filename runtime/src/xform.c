/* View defaults, clamping and the rotation matrix: see modelc/xform.h. */
#include "modelc/xform.h"

mc_view mc_view_default(void)
{
    /* field by field: an aggregate initialiser or copy of this size becomes a memset/memcpy call
     * at -O0, which a freestanding build does not have */
    mc_view v;
    v.yaw = v.pitch = v.roll = 0;
    v.zoom = MC_ZOOM_ONE;
    v.tx = v.ty = 0;
    v.projection = MC_ORTHOGRAPHIC;
    v.eye = 2 * MC_ZOOM_ONE;
    return v;
}

static int32_t clamp32(int32_t v, int32_t lo, int32_t hi) { return v < lo ? lo : v > hi ? hi : v; }

mc_view mc_view_clamp(const mc_view *v, uint32_t width, uint32_t height)
{
    mc_view c;
    c.yaw = v->yaw;
    c.pitch = v->pitch;
    c.roll = v->roll;
    uint32_t side = width < height ? width : height;
    if (side == 0) side = 1;
    /* the cube's screen extent is zoom * side; its bounding sphere (extent * sqrt(3)/2) plus half the
     * screen plus the translation must stay below MC_COORD_LIMIT, and a mesh vertex's projection
     * below 2^62: cap the extent at MC_VIEW_EXTENT_MAX */
    int64_t zmax = ((int64_t)MC_VIEW_EXTENT_MAX * MC_ZOOM_ONE) / side;
    if (zmax > MC_ZOOM_MAX) zmax = MC_ZOOM_MAX;
    if (zmax < 1) zmax = 1;
    c.zoom = clamp32(v->zoom, zmax < MC_ZOOM_MIN ? (int32_t)zmax : MC_ZOOM_MIN, (int32_t)zmax);
    c.tx = clamp32(v->tx, -MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4);
    c.ty = clamp32(v->ty, -MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4);
    c.eye = clamp32(v->eye, MC_EYE_MIN, MC_EYE_MAX);
    c.projection = v->projection == MC_PERSPECTIVE ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    return c;
}

/* Q30 product of two Q30 3x3 matrices, rounded. */
static void matmul(int32_t a[3][3], int32_t b[3][3], int32_t out[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int64_t s = 0;
            for (int k = 0; k < 3; k++) s += (int64_t)a[i][k] * b[k][j];  /* |s| <= 3 * 2^60 */
            out[i][j] = (int32_t)mc_round_shift(s, 30);
        }
}

void mc_view_rotation(const mc_view *v, int32_t r[3][3])
{
    int32_t sy = mc_sin(v->yaw), cy = mc_cos(v->yaw);
    int32_t sp = mc_sin(v->pitch), cp = mc_cos(v->pitch);
    int32_t sr = mc_sin(v->roll), cr = mc_cos(v->roll);
    int32_t ry[3][3] = {{cy, 0, sy}, {0, MC_TRIG_ONE, 0}, {-sy, 0, cy}};
    int32_t rx[3][3] = {{MC_TRIG_ONE, 0, 0}, {0, cp, -sp}, {0, sp, cp}};
    int32_t rz[3][3] = {{cr, -sr, 0}, {sr, cr, 0}, {0, 0, MC_TRIG_ONE}};
    int32_t t[3][3];
    matmul(rx, ry, t);
    matmul(rz, t, r);
}
