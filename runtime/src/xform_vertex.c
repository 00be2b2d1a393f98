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

static inline int32_t band(int64_t v, uint32_t *flags)
{
    const int64_t lim = (int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
    if (v > lim) { *flags |= MC_XFORM_FAR_OUT; return (int32_t)lim; }
    if (v < -lim) { *flags |= MC_XFORM_FAR_OUT; return (int32_t)-lim; }
    return (int32_t)v;
}

/* mc_round_shift(v, s) (v / 2^s to nearest, ties away from zero) without a branch (the vertices'
 * signs are a coin toss to a predictor) and without shifting a negative number: that is
 * floor((v + 2^(s-1) - [v < 0]) / 2^s), taken on u = v + 2^63 in unsigned arithmetic (2^63 is a
 * multiple of 2^s). round_shift: for 2 <= s <= 62 and any v > INT64_MIN, u's low s bits and the
 * rest apart so that nothing carries out; round_shift_small: for |v| < 2^62, at once. */
static inline int64_t round_shift(int64_t v, unsigned s)
{
    const uint64_t u = (uint64_t)v ^ ((uint64_t)1 << 63);
    const uint64_t low = (u & (((uint64_t)1 << s) - 1u)) + ((uint64_t)1 << (s - 1)) - (uint64_t)(v < 0);
    return (int64_t)((u >> s) + (low >> s)) - ((int64_t)1 << (63 - s));
}

static inline int64_t round_shift_small(int64_t v, unsigned s)
{
    const uint64_t u = ((uint64_t)v ^ ((uint64_t)1 << 63)) + ((uint64_t)1 << (s - 1)) - (uint64_t)(v < 0);
    return (int64_t)(u >> s) - ((int64_t)1 << (63 - s));
}

/* The perspective projection of q = R p (apart: the orthographic path, every frame of the usual
 * view, keeps its registers) */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void perspective(const mc_xform *x, const int64_t q[3], mc_xvertex *out)
{
    out->flags = 0;
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

void mc_xform_vertex(const mc_xform *x, const int32_t p[3], mc_xvertex *out)
{
    /* R p, Q30: |q| < 2^30 (sums below 3 * 2^45 before the shift) */
    const int64_t p0 = p[0], p1 = p[1], p2 = p[2];
    const int64_t q0 = round_shift_small(x->r[0][0] * p0 + x->r[0][1] * p1 + x->r[0][2] * p2, 16);
    const int64_t q1 = round_shift_small(x->r[1][0] * p0 + x->r[1][1] * p1 + x->r[1][2] * p2, 16);
    const int64_t q2 = round_shift_small(x->r[2][0] * p0 + x->r[2][1] * p1 + x->r[2][2] * p2, 16);
    if (x->perspective) {
        const int64_t q[3] = {q0, q1, q2};
        perspective(x, q, out);
        return;
    }
    /* S q in 1/16 pixel: Q16 * Q30 >> 42 */
    uint32_t flags = 0;
    out->x = band(x->cx + round_shift(x->scale * q0, 42), &flags);
    out->y = band(x->cy - round_shift(x->scale * q1, 42), &flags);
    out->z = (uint32_t)round_shift_small(((int64_t)7 << 27) - q2, 15);   /* (7/8 - q.z) * 2^15 */
    out->flags = flags;
}
