/* Vertex projection for meshes and edge models, and the clipping of their faces and lines with a
 * flagged corner: see modelc/xform.h. Apart from xform.c so that a program drawing only points links
 * none of it, and the budget counts it only for bakes with a mesh. */
#include "modelc/xform.h"
#include "modelc/bits.h"     /* mc_clz32 */
#include "modelc/target.h"   /* MC_DEPTH_EMPTY: the depths vertices may take */
#include "xform_ortho.h"      /* the orthographic step, the rounding */

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
        int64_t o = mc_div_round(n, d30);                            /* pixels, Q4 */
        if (i == 0) out->x = ortho_band(x->cx + o, &out->flags);
        else out->y = ortho_band(x->cy - o, &out->flags);
    }
    int64_t t = d24 > x->dmin ? (int64_t)(((uint64_t)(d24 - x->dmin) << 30) / (uint64_t)d24) : 0;   /* Q30 */
    int64_t z = mc_round_shift(x->za * t, 38);
    out->z = z > (int64_t)DEPTH_TOP ? DEPTH_TOP : (uint32_t)z;
}

void mc_xform_vertex(const mc_xform *x, const int32_t p[3], mc_xvertex *out)
{
    const int64_t p0 = p[0], p1 = p[1], p2 = p[2];
    const int64_t q0 = ORTHO_ROTATE(x, 0, p0, p1, p2), q1 = ORTHO_ROTATE(x, 1, p0, p1, p2);
    const int64_t q2 = ORTHO_ROTATE(x, 2, p0, p1, p2);
    if (x->perspective) {
        const int64_t q[3] = {q0, q1, q2};
        perspective(x, q, out);
        return;
    }
    ortho_project(x->scale, x->cx, x->cy, q0, q1, q2, out);
}

/* The least and greatest of r . p over the box lo .. hi: each term at the end its coefficient's sign
 * picks (ORTHO_ROTATE before its rounding) */
static void form_range(const int32_t r[3], const int32_t lo[3], const int32_t hi[3], int64_t *least, int64_t *most)
{
    int64_t a = 0, b = 0;
    for (int k = 0; k < 3; k++) {
        const int64_t l = (int64_t)r[k] * lo[k], h = (int64_t)r[k] * hi[k];
        a += l < h ? l : h, b += l < h ? h : l;
    }
    *least = a, *most = b;
}

int mc_xform_box_bound(const mc_xform *x, const int32_t lo[3], const int32_t hi[3], mc_xform_box *b)
{
    if (x->perspective) return 0;
    int64_t q[3][2];   /* each q_i's least and greatest, rounded as mc_xform_vertex rounds it */
    for (int i = 0; i < 3; i++) {
        int64_t a, c;
        form_range(x->r[i], lo, hi, &a, &c);
        q[i][0] = ortho_round_shift_small(a, 16), q[i][1] = ortho_round_shift_small(c, 16);
    }
    /* x grows with q0, y falls with q1, z falls with q2 (S > 0) */
    const int64_t lim = (int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
    const int64_t x0 = x->cx + ortho_round_shift_small(x->scale * q[0][0], 42);
    const int64_t x1 = x->cx + ortho_round_shift_small(x->scale * q[0][1], 42);
    const int64_t y0 = x->cy - ortho_round_shift_small(x->scale * q[1][1], 42);
    const int64_t y1 = x->cy - ortho_round_shift_small(x->scale * q[1][0], 42);
    if (x0 < -lim || x1 > lim || y0 < -lim || y1 > lim) return 0;
    b->x0 = (int32_t)x0, b->x1 = (int32_t)x1, b->y0 = (int32_t)y0, b->y1 = (int32_t)y1;
    b->z0 = (uint32_t)ortho_round_shift_small(((int64_t)7 << 27) - q[2][1], 15);
    return 1;
}

void mc_xform_view(const mc_xform *x, const int32_t p[3], int32_t q[3])
{
    const int64_t p0 = p[0], p1 = p[1], p2 = p[2];
    q[0] = (int32_t)ORTHO_ROTATE(x, 0, p0, p1, p2);
    q[1] = (int32_t)ORTHO_ROTATE(x, 1, p0, p1, p2);
    q[2] = (int32_t)ORTHO_ROTATE(x, 2, p0, p1, p2);
}

void mc_xform_project(const mc_xform *x, const int32_t q[3], mc_xvertex *out)
{
    if (x->perspective) {
        const int64_t w[3] = {q[0], q[1], q[2]};
        perspective(x, w, out);
        return;
    }
    ortho_project(x->scale, x->cx, x->cy, q[0], q[1], q[2], out);
}

/* ---- Clipping: see modelc/xform.h ------------------------------------------------------------
 * Plane k's function f_k, linear in q up to the rounding of S eye q (under 2 units of f):
 *   near: f = d - 2^24 (Q30: d >= 1/64 cube side), inside where f >= 0;
 *   band: f = (2 L_k + 1) w - 2 m, inside where f > 0, with w = d (Q30; orthographic 2^30), L_k the
 *         band's distance from the screen centre on that side (1/16 pixel) and m the centre's offset
 *         towards that side (1/16 pixel times w) as the projection rounds it: perspective
 *         s S eye q (mc_mul_shift64, as perspective() above), orthographic floor(s S q / 2^12)
 *         (S q / 2^42 is round_shift's argument), s = +1 or -1 by side.
 * f / (2 w) is the distance to x = L_k + 1/2 in 1/16 pixel. A corner is outside a band plane exactly
 * when its projection, rounded, passes the band on that side: for a rounding to nearest with halves
 * away from zero (div_round, round_shift) and an integer L, round(m / w) > L holds exactly when
 * 2 m >= (2 L + 1) w, whatever the parity of w. */
#define NEAR_Q30 ((int64_t)1 << 24)
enum { PLANE_NEAR, PLANE_LEFT, PLANE_RIGHT, PLANE_TOP, PLANE_BOTTOM, PLANES };

/* floor(v / 2^12), shifting nothing negative */
static int64_t floor_shift12(int64_t v) { return v >= 0 ? v / 4096 : -((-v + 4095) / 4096); }

static int64_t plane_value(const mc_xform *x, unsigned k, const int32_t q[3])
{
    const int64_t w = x->perspective ? x->eye - q[2] : (int64_t)1 << 30;
    if (k == PLANE_NEAR) return w - NEAR_Q30;
    const int64_t lim = (int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
    /* the side's distance from the centre and the sign taking the centre's offset towards it
     * (screen y grows downwards: y = cy - offset) */
    const int64_t l = k == PLANE_LEFT ? lim + x->cx : k == PLANE_RIGHT ? lim - x->cx : k == PLANE_TOP ? lim + x->cy
                                                                                                       : lim - x->cy;
    const int neg = k == PLANE_LEFT || k == PLANE_BOTTOM;
    const int64_t v = x->scale * q[k <= PLANE_RIGHT ? 0 : 1];   /* Q46 pixels */
    int64_t m;
    if (x->perspective) {
        m = mc_mul_shift64(v, x->eye >> 14, 28);
        if (neg) m = -m;
    } else {
        m = floor_shift12(neg ? -v : v);
    }
    return (2 * l + 1) * w - 2 * m;
}

static int plane_inside(unsigned k, int64_t f) { return k == PLANE_NEAR ? f >= 0 : f > 0; }

static unsigned outcode(const mc_xform *x, const int32_t q[3])
{
    unsigned code = 0;
    for (unsigned k = x->perspective ? PLANE_NEAR : PLANE_LEFT; k < PLANES; k++)
        code |= (unsigned)!plane_inside(k, plane_value(x, k, q)) << k;
    return code;
}

/* The cut c = a + (b - a) fa / (fa - fb) of the edge from a (inside, fa >= 0) to b (outside,
 * fb <= 0, fa - fb > 0). The fraction is taken to 32 bits: fa and fa - fb shifted right together
 * until the divisor fits 32 bits (t then within 2^-31 of fa / (fa - fb)); each coordinate is
 * a + round(|b - a| t) with the sign of b - a: it lies between a's and b's (t <= 1), and
 * |b - a| < 2^31 with t's numerator below 2^32 keeps the product below 2^63. */
static void cut(const int32_t a[3], const int32_t b[3], int64_t fa, int64_t fb, int32_t c[3])
{
    uint64_t num = (uint64_t)fa, den = (uint64_t)fa - (uint64_t)fb;   /* fa - fb < 2^63 */
    const uint32_t high = (uint32_t)(den >> 32);
    if (high) {
        const unsigned s = 32u - mc_clz32(high);
        num >>= s, den >>= s;
    }
    for (int i = 0; i < 3; i++) {
        const int64_t delta = (int64_t)b[i] - a[i];
        const uint64_t r = (mc_mag64(delta) * num + den / 2u) / den;   /* the one division: 64 by 32 bits */
        c[i] = (int32_t)(delta < 0 ? (int64_t)a[i] - (int64_t)r : (int64_t)a[i] + (int64_t)r);
    }
}

/* The cut of edge a-b against plane k whose values there are fa, fb (one inside, one outside),
 * always from the inside end so that either direction gives the same point. */
static void cut_edge(unsigned k, const int32_t a[3], const int32_t b[3], int64_t fa, int64_t fb, int32_t c[3])
{
    if (plane_inside(k, fa)) cut(a, b, fa, fb, c);
    else cut(b, a, fb, fa, c);
}

unsigned mc_xform_clip_triangle(const mc_xform *x, const int32_t q[3][3], mc_xvertex out[MC_XFORM_CLIP_MAX])
{
    int32_t poly[2][MC_XFORM_CLIP_MAX][3];
    int64_t f[MC_XFORM_CLIP_MAX];
    unsigned any = 0, all = ~0u, n = 3, cur = 0;
    for (unsigned i = 0; i < 3; i++) {
        const unsigned code = outcode(x, q[i]);
        any |= code, all &= code;
        poly[0][i][0] = q[i][0], poly[0][i][1] = q[i][1], poly[0][i][2] = q[i][2];
    }
    if (all) return 0;   /* wholly outside one plane */
    for (unsigned k = 0; k < PLANES; k++) {
        if (!(any >> k & 1u)) continue;   /* no corner outside it: neither is any point of the face */
        int32_t(*in)[3] = poly[cur];
        int32_t(*o)[3] = poly[cur ^ 1u];
        for (unsigned i = 0; i < n; i++) f[i] = plane_value(x, k, in[i]);
        unsigned m = 0;
        for (unsigned i = 0; i < n; i++) {
            const unsigned j = i + 1u < n ? i + 1u : 0u;
            const int ins = plane_inside(k, f[i]);
            if (ins) {
                if (m == MC_XFORM_CLIP_MAX) return 0;
                o[m][0] = in[i][0], o[m][1] = in[i][1], o[m][2] = in[i][2], m++;
            }
            if (ins != plane_inside(k, f[j])) {
                if (m == MC_XFORM_CLIP_MAX) return 0;
                cut_edge(k, in[i], in[j], f[i], f[j], o[m++]);
            }
        }
        if (m < 3) return 0;
        n = m, cur ^= 1u;
    }
    for (unsigned i = 0; i < n; i++) mc_xform_project(x, poly[cur][i], &out[i]);
    return n;
}

int mc_xform_clip_segment(const mc_xform *x, const int32_t a[3], const int32_t b[3], mc_xvertex out[2])
{
    int32_t e[2][3];
    for (int i = 0; i < 3; i++) e[0][i] = a[i], e[1][i] = b[i];
    const unsigned any = outcode(x, a) | outcode(x, b);
    for (unsigned k = 0; k < PLANES; k++) {
        if (!(any >> k & 1u)) continue;
        const int64_t fa = plane_value(x, k, e[0]), fb = plane_value(x, k, e[1]);
        const int ia = plane_inside(k, fa), ib = plane_inside(k, fb);
        if (!ia && !ib) return 0;
        if (ia != ib) {
            int32_t c[3];
            cut_edge(k, e[0], e[1], fa, fb, c);
            int32_t *keep = ia ? e[1] : e[0];
            keep[0] = c[0], keep[1] = c[1], keep[2] = c[2];
        }
    }
    mc_xform_project(x, e[0], &out[0]);
    mc_xform_project(x, e[1], &out[1]);
    return 1;
}

/* (hi, lo) += a b, a 128-bit two's complement sum, the product made of 32-bit halves */
static void mac128(uint64_t *hi, uint64_t *lo, int64_t a, int64_t b)
{
    const uint64_t ua = mc_mag64(a), ub = mc_mag64(b);
    const uint64_t al = ua & 0xFFFFFFFFu, ah = ua >> 32, bl = ub & 0xFFFFFFFFu, bh = ub >> 32;
    const uint64_t ll = al * bl, lh = al * bh, hl = ah * bl, hh = ah * bh;
    const uint64_t mid = (ll >> 32) + (lh & 0xFFFFFFFFu) + (hl & 0xFFFFFFFFu);
    uint64_t plo = (ll & 0xFFFFFFFFu) | (mid << 32), phi = hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
    if ((a < 0) != (b < 0)) {
        phi = ~phi + (plo == 0u);
        plo = 0u - plo;
    }
    *lo += plo;
    *hi += phi + (*lo < plo);
}

int mc_xform_front(const mc_xform *x, const int32_t q[3][3])
{
    int64_t a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = (int64_t)q[1][i] - q[0][i], b[i] = (int64_t)q[2][i] - q[0][i];
    /* |a_i|, |b_i| < 2^31 (|q_i| < 2^30): each product below 2^62, each component of the normal
     * below 2^63 */
    const int64_t n0 = a[1] * b[2] - a[2] * b[1], n1 = a[2] * b[0] - a[0] * b[2], n2 = a[0] * b[1] - a[1] * b[0];
    if (!x->perspective) return n2 > 0;
    /* (e - q0) . n with e = (0, 0, eye): products below 2^39 2^63, their sum in 128 bits */
    uint64_t hi = 0, lo = 0;
    mac128(&hi, &lo, x->eye - q[0][2], n2);
    mac128(&hi, &lo, -(int64_t)q[0][0], n0);
    mac128(&hi, &lo, -(int64_t)q[0][1], n1);
    return (int64_t)hi > 0 || (hi == 0 && lo != 0);
}
