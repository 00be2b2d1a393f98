/* Vertex projection for meshes and edge models: see modelc/xform.h. Apart from xform.c so that a
 * program drawing only points links none of it, and the budget counts it only for bakes with a mesh. */
#include "modelc/xform.h"
#include "modelc/target.h"   /* MC_DEPTH_EMPTY: the depths vertices may take */

/* sqrt(3)/2 in Q24, rounded up: the farthest a unit-cube point gets from the centre along any axis */
#define HALF_SQRT3_Q24 INT64_C(14529496)
#define DEPTH_TOP (MC_DEPTH_EMPTY - 2u)

void mc_xform_init(mc_xform *x, const mc_view *view, uint32_t width, uint32_t height)
{
    const mc_view v = mc_view_clamp(view, width, height);
    const uint32_t side = width < height ? width : height;
    mc_view_rotation(&v, x->r);
    x->scale = (int64_t)v.zoom * side;
    const int64_t unit = (int64_t)1 << MC_XFORM_SUBPIXEL_BITS;   /* (a translation may be negative) */
    x->cx = (int64_t)width * (unit / 2) + (int64_t)v.tx * unit;
    x->cy = (int64_t)height * (unit / 2) + (int64_t)v.ty * unit;
    x->perspective = v.projection == MC_PERSPECTIVE;
    x->eye = (int64_t)v.eye << 14;
    /* depth = DEPTH_TOP * k * (d - dmin) / d, k = dmax / (dmax - dmin): 0 at the nearest a point can
     * be (dmin, the near plane when the eye is inside the model's sphere), DEPTH_TOP at the farthest */
    const int64_t eye24 = (int64_t)v.eye << 8;
    int64_t dmin = eye24 - HALF_SQRT3_Q24;
    if (dmin < ((int64_t)1 << 24) / 64) dmin = ((int64_t)1 << 24) / 64;
    const int64_t dmax = eye24 + HALF_SQRT3_Q24;
    x->dmin = dmin;
    x->za = ((int64_t)DEPTH_TOP * dmax << 8) / (dmax - dmin);   /* DEPTH_TOP * k, Q8 */
}

/* round(n / d) for d > 0, ties away from zero */
static int64_t div_round(int64_t n, int64_t d) { return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d); }

static int32_t band(int64_t v, uint32_t *flags)
{
    const int64_t lim = (int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
    if (v > lim) { *flags |= MC_XFORM_FAR_OUT; return (int32_t)lim; }
    if (v < -lim) { *flags |= MC_XFORM_FAR_OUT; return (int32_t)-lim; }
    return (int32_t)v;
}

void mc_xform_vertex(const mc_xform *x, const int32_t p[3], mc_xvertex *out)
{
    int64_t q[3];   /* R p, Q30: |q| < 2^30 */
    for (int i = 0; i < 3; i++)
        q[i] = mc_round_shift((int64_t)x->r[i][0] * p[0] + (int64_t)x->r[i][1] * p[1] + (int64_t)x->r[i][2] * p[2], 16);
    out->flags = 0;
    if (!x->perspective) {
        /* S q in 1/16 pixel: Q16 * Q30 >> 42 */
        out->x = band(x->cx + mc_round_shift(x->scale * q[0], 42), &out->flags);
        out->y = band(x->cy - mc_round_shift(x->scale * q[1], 42), &out->flags);
        out->z = (uint32_t)mc_round_shift(((int64_t)7 << 27) - q[2], 15);   /* (7/8 - q.z) * 2^15 */
        return;
    }
    const int64_t d30 = x->eye - q[2];                      /* distance from the eye, Q30 */
    const int64_t d24 = mc_round_shift(d30, 6);
    if (d30 < ((int64_t)1 << 30) / 64) {
        out->flags = MC_XFORM_NEAR;
        out->x = out->y = 0;
        out->z = 0;
        return;
    }
    /* S q eye / d in 1/16 pixel: S q eye (Q16 * Q30 * Q16) >> 28 is pixels in Q34 (|S q eye| < 2^22
     * pixels), then / d (Q30); d unrounded, as near the eye its rounding would be magnified */
    const int64_t eye16 = x->eye >> 14;
    for (int i = 0; i < 2; i++) {
        int64_t n = mc_mul_shift64(x->scale * q[i], eye16, 28);   /* pixels, Q34 */
        int64_t o = div_round(n, d30);                            /* pixels, Q4 */
        if (i == 0) out->x = band(x->cx + o, &out->flags);
        else out->y = band(x->cy - o, &out->flags);
    }
    int64_t t = d24 > x->dmin ? (int64_t)(((uint64_t)(d24 - x->dmin) << 30) / (uint64_t)d24) : 0;   /* Q30 */
    int64_t z = mc_round_shift(x->za * t, 38);
    out->z = z > (int64_t)DEPTH_TOP ? DEPTH_TOP : (uint32_t)z;
}
