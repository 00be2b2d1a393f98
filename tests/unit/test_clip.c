/* Long because the long-double reference clipper, its error budget and the checks that share them
 * are one piece (tests/gen/clip_check.c includes the reference part).
 *
 * Clipping at the near plane and the guard band (xform.h mc_xform_clip_triangle,
 * mc_xform_clip_segment, mc_xform_front; mesh_render.h mc_mesh_clip_face) against a reference in
 * long doubles: the same five planes (near d >= 1/64; |x|, |y| < MC_XFORM_BAND + 1/32 pixel) as real
 * half-spaces, the same Sutherland-Hodgman cuts in real numbers from the same Q30 corners, projected
 * as runtime/ref/xform_ref.c projects (x = cx + S eye q.x / d, y = cy - S eye q.y / d, depth affine
 * in 1/d):
 *   - mc_xform_project(mc_xform_view(p)) is mc_xform_vertex(p), bit for bit, both projections;
 *   - a point is outside a plane exactly when mc_xform_vertex flags it, on and beside the band's
 *     rounding boundary and the near plane (the triangle and the segment of one point);
 *   - the reference's projection of a point is mc_ref_project's (runtime/ref/xform_ref.c), to 1e-6;
 *   - random triangles (eye inside and near the model, zoom up to the clamp, translations, some made
 *     in view space across the band and behind the eye): the same vertex count as the reference and
 *     each vertex within xform.h's bound of its exact cut (1/32 pixel of rounding plus the
 *     view-space error's image, plus its edge's end errors over the sine of the angle it crosses the
 *     plane's line at), within 1/16 pixel where the edge joins two corners and crosses at more than
 *     2^-22 radian, a band cut exactly on the band across it, depth within 1 + 1/64 unit of the
 *     exact mapping plus its slope times that error; every vertex inside the band, unflagged NEAR;
 *   - a segment's cut ends are its triangle's cut vertices on that edge, and two triangles sharing
 *     an edge cut it at the same points, bit for bit;
 *   - mc_xform_front equals the exact sign (128-bit integers, __int128 here) and, for triangles
 *     wholly inside, the sign of their projected area wherever that is not within rounding of 0;
 *   - a planar grid of triangles through the near plane, clipped and drawn as fans
 *     (mc_raster_triangle): no pixel centre covered twice, every centre covered where the reference
 *     polygon of the whole grid (clipped in real numbers) covers it by 1/8 pixel, none where it is
 *     that far outside; except beside a fan triangle that rounding to 1/16 pixel folded (turned
 *     against its face: a cut within about a unit of the line through two other vertices), where a
 *     centre may be covered twice or not at all, as beside any folded sliver of a mesh (counted).
 * The largest errors found are printed. Random numbers: PCG32 (modelc/rng.h), fixed seeds.
 * tests/gen/clip_check.c includes the reference part (up to the views) with CLIP_REFERENCE_ONLY.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifndef CLIP_REFERENCE_ONLY
#include <cmocka.h>
#endif

#include <modelc/mesh_render.h>
#include <modelc/raster.h>
#include <modelc/rng.h>
#include <modelc/target.h>
#include <modelc/xform.h>

typedef long double real;

#define UNIT 16.0L                               /* 1/16 pixel a pixel */
#define NEARD (1.0L / 64)
#define Q30 1073741824.0L
#define BANDPX ((real)MC_XFORM_BAND)

static int32_t rnd(mc_rng *g, int32_t lo, int32_t hi) { return lo + (int32_t)(mc_rng_next(g) % (uint32_t)(hi - lo + 1)); }

/* ---- the reference ---------------------------------------------------------------------------- */

typedef struct refview {
    mc_view v;           /* clamped */
    uint32_t w, h;
    real s, cx, cy, eye, mag, dmin, dmax;
    int persp;
} refview;

static refview ref_view(const mc_view *view, uint32_t w, uint32_t h)
{
    refview r;
    r.v = mc_view_clamp(view, w, h);
    r.w = w, r.h = h;
    r.s = r.v.zoom / 65536.0L * (w < h ? w : h);
    r.cx = w / 2.0L + r.v.tx, r.cy = h / 2.0L + r.v.ty;
    r.eye = r.v.eye / 65536.0L;
    r.persp = r.v.projection == MC_PERSPECTIVE;
    r.mag = r.persp ? r.eye : 1;
    const real half = 14529496.0L / 16777216.0L;
    r.dmin = r.eye - half < NEARD ? NEARD : r.eye - half;
    r.dmax = r.eye + half;
    return r;
}

static real dist(const refview *r, const real q[3]) { return r->persp ? r->eye - q[2] : 1; }

/* plane k's linear function (cube sides times pixels), inside where > 0 (near: >= 0) */
static real ref_plane(const refview *r, int k, const real q[3])
{
    const real d = dist(r, q), b = BANDPX + 1.0L / 32;
    switch (k) {
    case 0: return r->persp ? d - NEARD : 1;
    case 1: return (b + r->cx) * d + r->s * r->mag * q[0];
    case 2: return (b - r->cx) * d - r->s * r->mag * q[0];
    case 3: return (b + r->cy) * d - r->s * r->mag * q[1];
    default: return (b - r->cy) * d + r->s * r->mag * q[1];
    }
}
static int ref_inside(int k, real f) { return k == 0 ? f >= 0 : f > 0; }

typedef struct rvert {
    real q[3];            /* view space, cube sides */
    real x, y, z;         /* projected: pixels, depth units */
    real err;             /* the runtime's error budget beyond its own rounding, 1/16 pixel */
    int plane;            /* -1: a corner; else the plane that made it */
    int simple;           /* a cut of an edge between two corners */
    real sine;            /* sin of the angle its edge crosses the plane's line at (1 for near cuts) */
} rvert;

static void ref_project(const refview *r, rvert *v)
{
    const real d = dist(r, v->q);
    v->x = r->cx + r->s * r->mag * v->q[0] / d;
    v->y = r->cy - r->s * r->mag * v->q[1] / d;
    if (r->persp) {
        v->z = (MC_DEPTH_EMPTY - 2.0L) * r->dmax / (r->dmax - r->dmin) * (d - r->dmin) / d;
        if (v->z < 0) v->z = 0;
    } else {
        v->z = (0.875L - v->q[2]) * 32768.0L;
    }
}

/* how far an error of e cube sides along each axis moves the projection, in 1/16 pixel */
static real view_error(const refview *r, const rvert *v, real e)
{
    const real d = dist(r, v->q);
    const real ox = fabsl(v->x - r->cx), oy = fabsl(v->y - r->cy);
    return UNIT * e * (r->s * r->mag + (r->persp ? (ox > oy ? ox : oy) : 0)) / d;
}

/* the reference cut of a (inside) - b (outside) at plane k */
static rvert ref_cut(const refview *r, int k, const rvert *a, const rvert *b, real fa, real fb)
{
    rvert c;
    const real t = fa / (fa - fb);
    real span = 0;
    for (int i = 0; i < 3; i++) {
        c.q[i] = a->q[i] + t * (b->q[i] - a->q[i]);
        if (fabsl(b->q[i] - a->q[i]) > span) span = fabsl(b->q[i] - a->q[i]);
    }
    ref_project(r, &c);
    c.plane = k;
    c.simple = a->plane < 0 && b->plane < 0;
    /* the cut's own view-space error (t to 2^-31, Q30 rounding), then for band planes the plane's
     * rounding and the ends' errors along the edge over the crossing angle's sine */
    const real own = view_error(r, &c, span * 0x1p-31L + 0x1p-31L);
    if (k == 0) {
        c.sine = 1;
        c.err = own + (a->err > b->err ? a->err : b->err);
    } else {
        const real dx = b->x - a->x, dy = b->y - a->y, len = sqrtl(dx * dx + dy * dy);
        c.sine = len > 0 ? fabsl(k <= 2 ? dx : dy) / len : 0;
        const real ends = a->err > b->err ? a->err : b->err;
        c.err = c.sine > 0 ? own + (0x1p-24L + ends) / c.sine : 1e30L;
    }
    return c;
}

/* Sutherland-Hodgman in real numbers, as xform.h states it; returns the vertex count */
static int ref_clip(const refview *r, const int32_t q[3][3], rvert out[16])
{
    rvert poly[2][16];
    int n = 3, cur = 0;
    unsigned any = 0, all = ~0u;
    for (int i = 0; i < 3; i++) {
        rvert *v = &poly[0][i];
        for (int j = 0; j < 3; j++) v->q[j] = q[i][j] / Q30;
        ref_project(r, v);
        v->err = 0, v->plane = -1, v->simple = 0, v->sine = 1;
        unsigned code = 0;
        for (int k = r->persp ? 0 : 1; k < 5; k++) code |= (unsigned)!ref_inside(k, ref_plane(r, k, v->q)) << k;
        any |= code, all &= code;
    }
    if (all) return 0;
    for (int k = 0; k < 5; k++) {
        if (!(any >> k & 1u)) continue;
        real f[16];
        int m = 0;
        for (int i = 0; i < n; i++) f[i] = ref_plane(r, k, poly[cur][i].q);
        for (int i = 0; i < n; i++) {
            const int j = (i + 1) % n, ins = ref_inside(k, f[i]);
            if (ins && m < 16) poly[cur ^ 1][m++] = poly[cur][i];
            if (ins != ref_inside(k, f[j]) && m < 16)
                poly[cur ^ 1][m++] = ins ? ref_cut(r, k, &poly[cur][i], &poly[cur][j], f[i], f[j])
                                         : ref_cut(r, k, &poly[cur][j], &poly[cur][i], f[j], f[i]);
        }
        if (m < 3) return 0;
        n = m, cur ^= 1;
    }
    for (int i = 0; i < n; i++) out[i] = poly[cur][i];
    return n;
}

#ifndef CLIP_REFERENCE_ONLY   /* tests/gen/clip_check.c takes the reference above and no more */

#include "../../runtime/ref/xform_ref.h"

static real unif(mc_rng *g) { return mc_rng_next(g) / 4294967296.0L; }

/* ---- views and points ------------------------------------------------------------------------- */

/* a perspective view with the eye near or inside the model (or, one in `ortho`, orthographic) */
static mc_view random_view(mc_rng *g, uint32_t *w, uint32_t *h, int ortho)
{
    mc_view v = mc_view_default();
    v.yaw = rnd(g, 0, 4095), v.pitch = rnd(g, 0, 4095), v.roll = rnd(g, 0, 4095);
    v.projection = ortho && mc_rng_below(g, (uint32_t)ortho) == 0 ? MC_ORTHOGRAPHIC : MC_PERSPECTIVE;
    switch (mc_rng_below(g, 4)) {
    case 0: v.eye = MC_EYE_MIN; break;
    case 1: v.eye = rnd(g, MC_EYE_MIN, 65536); break;
    case 2: v.eye = rnd(g, 50000, 70000); break;   /* around the bounding sphere */
    default: v.eye = rnd(g, MC_EYE_MIN, 65536 * 3); break;
    }
    v.zoom = mc_rng_below(g, 3) == 0 ? rnd(g, 65536 * 8, MC_ZOOM_MAX) : rnd(g, MC_ZOOM_MIN, 65536 * 4);
    v.tx = mc_rng_below(g, 4) == 0 ? rnd(g, -MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4) : rnd(g, -40, 40);
    v.ty = mc_rng_below(g, 4) == 0 ? rnd(g, -MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4) : rnd(g, -40, 40);
    *w = (uint32_t)rnd(g, 1, 640), *h = (uint32_t)rnd(g, 1, 480);
    if (mc_rng_below(g, 8) == 0) *w = MC_TARGET_MAX, *h = (uint32_t)rnd(g, 1, MC_TARGET_MAX);
    return v;
}

static void random_p(mc_rng *g, int32_t p[3])
{
    for (int i = 0; i < 3; i++) p[i] = rnd(g, -32768, 32767);
}

/* a point of the cube near the eye's axis at distance d in front of it (view space, then back into
 * the model through R^T in long doubles, rounded to Q16 and clamped to the cube) */
static void p_near_eye(mc_rng *g, const mc_xform *x, const refview *r, int32_t p[3])
{
    const real d = NEARD * (0.25L + 8 * unif(g) * unif(g));
    real q[3] = {(unif(g) - 0.5L) * 0.4L, (unif(g) - 0.5L) * 0.4L, r->eye - d};
    for (int i = 0; i < 3; i++) {
        real s = 0;
        for (int j = 0; j < 3; j++) s += x->r[j][i] / Q30 * q[j];
        long v = lroundl(s * 65536);
        p[i] = (int32_t)(v < -32768 ? -32768 : v > 32767 ? 32767 : v);
    }
}

/* ---- tests ------------------------------------------------------------------------------------- */

static void test_project_is_vertex(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 1, 1);
    for (int k = 0; k < 2000; k++) {
        uint32_t w, h;
        const mc_view v = random_view(&g, &w, &h, 3);
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        const refview r = ref_view(&v, w, h);
        for (int i = 0; i < 50; i++) {
            int32_t p[3], q[3];
            mc_xvertex a, b;
            random_p(&g, p);
            mc_xform_vertex(&x, p, &a);
            mc_xform_view(&x, p, q);
            mc_xform_project(&x, q, &b);
            if (a.x != b.x || a.y != b.y || a.z != b.z || a.flags != b.flags)
                fail_msg("view %d point %d: mc_xform_vertex (%d %d %u %u), project(view) (%d %d %u %u)", k, i, a.x, a.y, a.z,
                         a.flags, b.x, b.y, b.z, b.flags);
            /* the reference's projection of a view-space point is runtime/ref/xform_ref.c's */
            rvert e;
            for (int j = 0; j < 3; j++)
                e.q[j] = ((real)x.r[j][0] * p[0] + (real)x.r[j][1] * p[1] + (real)x.r[j][2] * p[2]) / (Q30 * 65536);
            const mc_ref_vertex f = mc_ref_project(&v, w, h, p);
            if (f.near) continue;
            ref_project(&r, &e);
            if (fabsl(e.x - f.x) > 1e-6L * (1 + fabsl(f.x)) || fabsl(e.y - f.y) > 1e-6L * (1 + fabsl(f.y)) || fabsl(e.z - f.z) > 1e-6L)
                fail_msg("view %d point %d: the reference projects to (%.6Lf %.6Lf %.6Lf), mc_ref_project (%.6f %.6f %.6f)", k, i,
                         e.x, e.y, e.z, f.x, f.y, f.z);
        }
    }
}

/* A point alone (the triangle and the segment of one point): all of it is left exactly when the
 * projection flags nothing, and then it is the projection. */
static void check_point(const mc_xform *x, const int32_t q[3], unsigned long *inside, unsigned long *outside)
{
    mc_xvertex pr, out[MC_XFORM_CLIP_MAX], seg[2];
    mc_xform_project(x, q, &pr);
    const int32_t t[3][3] = {{q[0], q[1], q[2]}, {q[0], q[1], q[2]}, {q[0], q[1], q[2]}};
    const unsigned n = mc_xform_clip_triangle(x, t, out);
    const int s = mc_xform_clip_segment(x, q, q, seg);
    if (pr.flags) {
        if (n != 0 || s != 0) fail_msg("q (%d %d %d) flagged %u, clipping leaves %u vertices, segment %d", q[0], q[1], q[2], pr.flags, n, s);
        ++*outside;
        return;
    }
    if (n != 3 || s != 1) fail_msg("q (%d %d %d) unflagged at (%d, %d), clipping leaves %u vertices, segment %d", q[0], q[1], q[2], pr.x, pr.y, n, s);
    for (unsigned i = 0; i < 3; i++)
        if (out[i].x != pr.x || out[i].y != pr.y || out[i].z != pr.z || out[i].flags != 0)
            fail_msg("q (%d %d %d) unflagged: a vertex moved", q[0], q[1], q[2]);
    for (int i = 0; i < 2; i++)
        if (seg[i].x != pr.x || seg[i].y != pr.y || seg[i].z != pr.z || seg[i].flags != 0)
            fail_msg("q (%d %d %d) unflagged: a segment end moved", q[0], q[1], q[2]);
    ++*inside;
}

static void test_planes_are_the_flags(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 2, 2);
    unsigned long inside = 0, outside = 0, boundary = 0, near = 0;
    for (int k = 0; k < 8000; k++) {
        uint32_t w, h;
        mc_view v = random_view(&g, &w, &h, 4);
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        const refview r = ref_view(&v, w, h);
        for (int i = 0; i < 40; i++) {
            int32_t q[3];
            /* a distance: near the near plane, or anywhere in front of the eye within the cube */
            real d = r.persp ? (mc_rng_below(&g, 2) ? NEARD * (0.5L + 3 * unif(&g)) : r.eye + 0.9L * (unif(&g) * 2 - 1)) : 1;
            real qz = r.persp ? r.eye - d : (unif(&g) - 0.5L) * 1.8L;
            if (qz > 0.99L || qz < -0.99L) qz = (unif(&g) - 0.5L) * 1.8L;
            q[2] = (int32_t)lroundl(qz * Q30);
            const real dd = r.persp ? r.eye - q[2] / Q30 : 1;
            /* one axis aimed at the band's rounding edge (1/32 pixel beyond it) on a random side, give
             * or take 3/64 pixel; the other anywhere */
            const int axis = (int)mc_rng_below(&g, 2);
            const real scr = (mc_rng_below(&g, 2) ? 1 : -1) * (BANDPX + (32 + rnd(&g, -48, 48)) / 1024.0L);
            const real off = axis ? r.cy - scr : scr - r.cx;
            real qa = dd > 0 ? off * dd / (r.s * r.mag) : 2;
            if (qa >= 0.99L || qa <= -0.99L) qa = (unif(&g) - 0.5L) * 1.8L;
            else boundary++;
            q[axis] = (int32_t)lroundl(qa * Q30) + rnd(&g, -2, 2);
            q[1 - axis] = rnd(&g, -900000000, 900000000);
            check_point(&x, q, &inside, &outside);
            /* and at the near plane itself, give or take 2^-30 */
            if (r.persp && r.eye < 0.9L) {
                const int32_t qn[3] = {rnd(&g, -200000, 200000), rnd(&g, -200000, 200000),
                                       (int32_t)(((int64_t)r.v.eye << 14) - (1 << 24) + rnd(&g, -2, 2))};
                check_point(&x, qn, &inside, &outside);
                near++;
            }
        }
    }
    print_message("# info: %lu points inside, %lu outside; %lu aimed at the band's rounding edge, %lu at the near plane\n",
                  inside, outside, boundary, near);
    if (inside < 10000 || outside < 10000) fail_msg("too few points on one side: %lu inside, %lu outside", inside, outside);
}

typedef struct errstats {
    unsigned long polys, verts, cuts, simple_cuts, ill, count_diff, empty, by_plane[5], chained, sizes[MC_XFORM_CLIP_MAX + 1], ortho;
    real max_simple, max_any, max_z;
} errstats;

/* the runtime's polygon of q against the reference's */
static void compare_polygon(const mc_xform *x, const refview *r, const int32_t q[3][3], errstats *es, const char *what)
{
    mc_xvertex out[MC_XFORM_CLIP_MAX];
    rvert ref[16];
    const unsigned n = mc_xform_clip_triangle(x, q, out);
    const int m = ref_clip(r, q, ref);
    for (unsigned i = 0; i < n; i++) {
        if (out[i].flags & MC_XFORM_NEAR) fail_msg("%s: vertex %u flagged near", what, i);
        const int32_t lim = MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
        if (out[i].x < -lim || out[i].x > lim || out[i].y < -lim || out[i].y > lim) fail_msg("%s: vertex %u outside the band", what, i);
        if (out[i].z > MC_DEPTH_EMPTY - 2u) fail_msg("%s: vertex %u depth %u", what, i, out[i].z);
    }
    if (n > MC_XFORM_CLIP_MAX || (n != 0 && n < 3)) fail_msg("%s: %u vertices", what, n);
    if ((int)n != m) {
        es->count_diff++;
        /* a vertex within rounding of a plane: allowed, rare (checked by the caller) */
        return;
    }
    if (n == 0) { es->empty++; return; }
    es->polys++;
    es->sizes[n]++;
    for (unsigned i = 0; i < n; i++) {
        const rvert *e = &ref[i];
        const real ex = fabsl(out[i].x - e->x * UNIT), ey = fabsl(out[i].y - e->y * UNIT);
        const real err = ex > ey ? ex : ey;
        es->verts++;
        if (e->plane < 0) {
            if (err > 0.5L + 1e-6L) fail_msg("%s: corner %u off by %.4Lf", what, i, err);
            continue;
        }
        es->cuts++;
        es->by_plane[e->plane]++;
        es->ortho += !r->persp;
        if (e->plane > 0) {   /* a band cut lands on the band across it (xform.h) */
            const int32_t lim = MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
            const int32_t across = e->plane <= 2 ? out[i].x : out[i].y, want = e->plane % 2 ? -lim : lim;
            if (across != want) fail_msg("%s: cut %u at band plane %d lies at %d across it, not %d", what, i, e->plane, across, want);
        }
        es->chained += !e->simple;
        const real tol = 0.5L + e->err + 1e-6L;
        if (err > tol)
            fail_msg("%s: cut %u (plane %d, simple %d, sine %.3Lg) off by %.4Lf units, budget %.4Lf: runtime (%d, %d), exact (%.4Lf, %.4Lf)",
                     what, i, e->plane, e->simple, e->sine, err, tol, out[i].x, out[i].y, e->x * UNIT, e->y * UNIT);
        if (err > es->max_any) es->max_any = err;
        if (e->simple && e->sine > 0x1p-22L) {
            es->simple_cuts++;
            if (err > 1) fail_msg("%s: cut %u of an edge between corners off by %.4Lf units (1/16 pixel promised)", what, i, err);
            if (err > es->max_simple) es->max_simple = err;
        }
        if (e->err > 0.3L) { es->ill++; continue; }
        /* depth: the mapping's unit, 1/64 for the point's error, and the edge's slope times the
         * rest of the error along it */
        const unsigned j = (i + n - 1) % n, k2 = (i + 1) % n;
        const real sx = ref[k2].x - ref[j].x, sy = ref[k2].y - ref[j].y, sl = sqrtl(sx * sx + sy * sy) * UNIT;
        const real slope = sl > 0 ? fabsl(ref[k2].z - ref[j].z) / sl : 0;
        const real ez = fabsl(out[i].z - e->z), ztol = 1 + 1.0L / 64 + slope * (e->err + 0.5L) * 2 + 1e-6L;
        if (ez > ztol) fail_msg("%s: cut %u depth %u, exact %.4Lf (tolerance %.4Lf)", what, i, out[i].z, e->z, ztol);
        if (ez - slope * (e->err + 0.5L) * 2 > es->max_z) es->max_z = ez - slope * (e->err + 0.5L) * 2;
    }
}

static void test_reference_polygons(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 3, 3);
    errstats es;
    memset(&es, 0, sizeof es);
    unsigned long tries = 0;
    for (int k = 0; k < 4000; k++) {
        uint32_t w, h;
        mc_view v = random_view(&g, &w, &h, 16);
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        const refview r = ref_view(&v, w, h);
        for (int i = 0; i < 60; i++) {
            int32_t p[3][3], q[3][3];
            /* corners: anywhere in the cube, or near the eye (through the near plane), or one far;
             * or (mode 4) made in view space: a distance (behind the eye, about the near plane, or
             * in front) and a screen position within three bands either way */
            const unsigned mode = mc_rng_below(&g, 8) < 3 ? 4 : mc_rng_below(&g, 4);
            if (mode == 4) {
                for (int c = 0; c < 3; c++) {
                    for (;;) {
                        const unsigned dk = mc_rng_below(&g, 3);
                        const real d = !r.persp ? 1 : dk == 0 ? -0.3L * unif(&g) : dk == 1 ? NEARD * (0.5L + 2 * unif(&g)) : r.eye * unif(&g) + 0.1L;
                        const real X = (unif(&g) * 2 - 1) * 2 * BANDPX, Y = (unif(&g) * 2 - 1) * 2 * BANDPX;
                        const real qq[3] = {(X - r.cx) * d / (r.s * r.mag), -(Y - r.cy) * d / (r.s * r.mag), r.persp ? r.eye - d : (unif(&g) - 0.5L)};
                        if (fabsl(qq[0]) > 0.99L || fabsl(qq[1]) > 0.99L || fabsl(qq[2]) > 0.99L) {
                            if (mc_rng_below(&g, 4) == 0) {   /* too far out: any point of the cube instead */
                                random_p(&g, p[c]);
                                mc_xform_view(&x, p[c], q[c]);
                                break;
                            }
                            continue;
                        }
                        for (int j = 0; j < 3; j++) q[c][j] = (int32_t)lroundl(qq[j] * Q30);
                        break;
                    }
                }
            }
            for (int c = 0; c < 3 && mode < 4; c++) {
                if (mode == 0 || (mode == 1 && c == 0)) random_p(&g, p[c]);
                else if (r.persp) p_near_eye(&g, &x, &r, p[c]);
                else random_p(&g, p[c]);
                if (mode == 3 && c > 0) {   /* a small triangle near the first corner */
                    for (int j = 0; j < 3; j++) {
                        const int32_t t = p[0][j] + rnd(&g, -300, 300);
                        p[c][j] = t < -32768 ? -32768 : t > 32767 ? 32767 : t;
                    }
                }
                mc_xform_view(&x, p[c], q[c]);
            }
            tries++;
            char what[160];
            snprintf(what, sizeof what, "view %d (eye %d zoom %d tx %d ty %d %ux%u %s) triangle %d", k, r.v.eye, r.v.zoom, r.v.tx,
                     r.v.ty, w, h, r.persp ? "perspective" : "orthographic", i);
            compare_polygon(&x, &r, (const int32_t(*)[3])q, &es, what);
        }
    }
    print_message("# info: %lu triangles: %lu clipped polygons compared (%lu cuts: near %lu, band %lu %lu %lu %lu; %lu of an "
                  "edge an earlier plane made, %lu between corners crossing at over 2^-22 rad), %lu empty, %lu with another vertex "
                  "count, %lu cuts in orthographic views; largest error %.3Lf of 1/16 pixel (between corners %.3Lf), depth beyond the slope's share %.3Lf; %lu "
                  "cuts ill-conditioned (budget over 0.3); polygons of 3..8 vertices: %lu %lu %lu %lu %lu %lu\n",
                  tries, es.polys, es.cuts, es.by_plane[0], es.by_plane[1], es.by_plane[2], es.by_plane[3], es.by_plane[4], es.chained,
                  es.simple_cuts, es.empty, es.count_diff, es.ortho, es.max_any, es.max_simple, es.max_z, es.ill, es.sizes[3], es.sizes[4],
                  es.sizes[5], es.sizes[6], es.sizes[7], es.sizes[8]);
    if (es.count_diff * 1000 > tries) fail_msg("%lu of %lu triangles with another vertex count", es.count_diff, tries);
    if (es.simple_cuts < 1000 || es.cuts < 5000) fail_msg("too few cuts compared");
}

/* segments against their triangle's cuts; shared edges */
static int has_vertex(const mc_xvertex *v, unsigned n, const mc_xvertex *e)
{
    for (unsigned i = 0; i < n; i++)
        if (v[i].x == e->x && v[i].y == e->y && v[i].z == e->z) return 1;
    return 0;
}

static void test_segments_and_shared_edges(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 4, 4);
    unsigned long cut_ends = 0, shared = 0;
    for (int k = 0; k < 1500; k++) {
        uint32_t w, h;
        mc_view v = random_view(&g, &w, &h, 16);
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        const refview r = ref_view(&v, w, h);
        for (int i = 0; i < 40; i++) {
            int32_t p[4][3], q[4][3];
            for (int c = 0; c < 4; c++) {
                if (r.persp && mc_rng_below(&g, 2)) p_near_eye(&g, &x, &r, p[c]);
                else random_p(&g, p[c]);
                mc_xform_view(&x, p[c], q[c]);
            }
            /* triangles a b c and b a d share the edge a b */
            const int32_t t1[3][3] = {{q[0][0], q[0][1], q[0][2]}, {q[1][0], q[1][1], q[1][2]}, {q[2][0], q[2][1], q[2][2]}};
            const int32_t t2[3][3] = {{q[1][0], q[1][1], q[1][2]}, {q[0][0], q[0][1], q[0][2]}, {q[3][0], q[3][1], q[3][2]}};
            mc_xvertex a[MC_XFORM_CLIP_MAX], b[MC_XFORM_CLIP_MAX], s[2], s2[2], c0, c1;
            const unsigned na = mc_xform_clip_triangle(&x, t1, a), nb = mc_xform_clip_triangle(&x, t2, b);
            const int ns = mc_xform_clip_segment(&x, q[0], q[1], s), ns2 = mc_xform_clip_segment(&x, q[1], q[0], s2);
            mc_xform_project(&x, q[0], &c0);
            mc_xform_project(&x, q[1], &c1);
            if (ns != ns2) fail_msg("view %d: segment a b and b a differ", k);
            if (ns && (s[0].x != s2[1].x || s[0].y != s2[1].y || s[0].z != s2[1].z || s[1].x != s2[0].x || s[1].y != s2[0].y ||
                       s[1].z != s2[0].z))
                fail_msg("view %d: segment a b and b a cut at other points", k);
            for (int e = 0; e < 2 && ns; e++) {
                const mc_xvertex *corner = e ? &c1 : &c0;
                const int is_corner = !corner->flags && s[e].x == corner->x && s[e].y == corner->y && s[e].z == corner->z;
                if (is_corner) continue;
                cut_ends++;
                /* a cut end lies on both polygons, where something of them is left */
                if (na && !has_vertex(a, na, &s[e])) fail_msg("view %d triangle %d: segment end %d (%d, %d) not a vertex of a b c", k, i, e, s[e].x, s[e].y);
                if (nb && !has_vertex(b, nb, &s[e])) fail_msg("view %d triangle %d: segment end %d (%d, %d) not a vertex of b a d", k, i, e, s[e].x, s[e].y);
                if (na && nb) shared++;
            }
            /* and the segment's ends against the reference's cuts */
            if (ns) {
                rvert ref[16];
                const int32_t deg[3][3] = {{q[0][0], q[0][1], q[0][2]}, {q[1][0], q[1][1], q[1][2]}, {q[1][0], q[1][1], q[1][2]}};
                const int m = ref_clip(&r, deg, ref);
                for (int e = 0; e < 2 && m >= 3; e++) {
                    real best = 1e30L;
                    for (int j = 0; j < m; j++) {
                        const real ex = fabsl(s[e].x - ref[j].x * UNIT), ey = fabsl(s[e].y - ref[j].y * UNIT);
                        const real d = (ex > ey ? ex : ey) - 0.5L - ref[j].err;
                        if (d < best) best = d;
                    }
                    if (best > 1e-6L) fail_msg("view %d: segment end %d (%d, %d) beyond every reference cut's budget by %.4Lf", k, e, s[e].x, s[e].y, best);
                }
            }
        }
    }
    print_message("# info: %lu cut segment ends found on their triangles, %lu on both triangles of a shared edge\n", cut_ends, shared);
    if (shared < 1000) fail_msg("too few shared cuts: %lu", shared);
}

/* exact sign of (e - q0) . ((q1 - q0) x (q2 - q0)) */
static int exact_front(const mc_xform *x, const int32_t q[3][3])
{
    __int128 a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = (__int128)q[1][i] - q[0][i], b[i] = (__int128)q[2][i] - q[0][i];
    const __int128 n0 = a[1] * b[2] - a[2] * b[1], n1 = a[2] * b[0] - a[0] * b[2], n2 = a[0] * b[1] - a[1] * b[0];
    if (!x->perspective) return n2 > 0;
    const __int128 s = ((__int128)x->eye - q[0][2]) * n2 - (__int128)q[0][0] * n0 - (__int128)q[0][1] * n1;
    return s > 0;
}

static void test_facing(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 5, 5);
    unsigned long n = 0, screen = 0, front = 0;
    for (int k = 0; k < 1000; k++) {
        uint32_t w, h;
        mc_view v = random_view(&g, &w, &h, 4);
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        const refview r = ref_view(&v, w, h);
        for (int i = 0; i < 100; i++) {
            int32_t p[3][3], q[3][3];
            mc_xvertex pv[3];
            for (int c = 0; c < 3; c++) {
                if (r.persp && mc_rng_below(&g, 3) == 0) p_near_eye(&g, &x, &r, p[c]);
                else random_p(&g, p[c]);
                if (i % 10 == 0) for (int j = 0; j < 3; j++) q[c][j] = rnd(&g, -1073741823, 1073741823);   /* extremes */
                else mc_xform_view(&x, p[c], q[c]);
                mc_xform_project(&x, q[c], &pv[c]);
            }
            const int got = mc_xform_front(&x, (const int32_t(*)[3])q);
            if (got != exact_front(&x, (const int32_t(*)[3])q)) fail_msg("view %d triangle %d: mc_xform_front %d, exact sign says otherwise", k, i, got);
            if (i % 10 != 0 && mc_mesh_face_front(&x, (const int32_t(*)[3])p) != got) fail_msg("view %d: mc_mesh_face_front differs", k);
            n++, front += got;
            if (pv[0].flags | pv[1].flags | pv[2].flags) continue;
            /* wholly inside: the sign of the projected area wherever rounding (1/2 unit a corner) cannot flip it */
            const real ax = pv[1].x - pv[0].x, ay = pv[1].y - pv[0].y, bx = pv[2].x - pv[0].x, by = pv[2].y - pv[0].y;
            const real area = ax * by - bx * ay, slack = 2 * (fabsl(ax) + fabsl(ay) + fabsl(bx) + fabsl(by)) + 4;
            if (fabsl(area) <= slack) continue;
            screen++;
            if ((area < 0) != got) fail_msg("view %d triangle %d: front %d, projected area %.1Lf", k, i, got, area);
        }
    }
    print_message("# info: %lu triangles (%lu front), %lu compared with their projected area\n", n, front, screen);
    if (screen < 10000) fail_msg("too few triangles wholly inside: %lu", screen);
}

/* A grid of triangles in one plane, through the near plane: drawn as clipped fans, no centre twice
 * (but beside folds), and the reference polygon of the whole grid covered. */
static int inside_poly(const rvert *p, int n, real px, real py, real margin)
{
    /* a convex polygon, turning either way: inside when the signed distances to its edges' lines
     * all exceed the margin with one sign */
    real mn = 1e30L, mx = -1e30L;
    for (int i = 0; i < n; i++) {
        const rvert *a = &p[i], *b = &p[(i + 1) % n];
        const real ex = b->x - a->x, ey = b->y - a->y, len = sqrtl(ex * ex + ey * ey);
        if (len == 0) continue;
        const real s = (ex * (py - a->y) - ey * (px - a->x)) / len;
        if (s < mn) mn = s;
        if (s > mx) mx = s;
    }
    return mn > margin || mx < -margin;
}

static void test_grid_tiles(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 6, 6);
    enum { W = 96, H = 72, N = 6 };
    uint8_t *count = malloc(W * H), *col = malloc(W * H);
    uint16_t *dep = malloc(2 * W * H);
    assert_non_null(count);
    unsigned long grids = 0, sure_in = 0, sure_out = 0, clipped_grids = 0, folds = 0, by_folds = 0;
    for (int k = 0; k < 300; k++) {
        mc_view v = mc_view_default();
        v.projection = MC_PERSPECTIVE;
        v.yaw = rnd(&g, 0, 4095), v.pitch = rnd(&g, 0, 4095), v.roll = rnd(&g, 0, 4095);
        v.eye = rnd(&g, MC_EYE_MIN, 65536);
        v.zoom = mc_rng_below(&g, 2) ? rnd(&g, 65536, MC_ZOOM_MAX) : rnd(&g, 16384, 65536 * 2);
        mc_xform x;
        mc_xform_init(&x, &v, W, H);
        const refview r = ref_view(&v, W, H);
        /* a plane through a point in front of the eye, spanned by two random directions: a grid of
         * N x N squares, corners in view space, some behind the eye */
        const real o[3] = {(unif(&g) - 0.5L) * 0.05L, (unif(&g) - 0.5L) * 0.05L, r.eye - NEARD * (0.5L + 4 * unif(&g))};
        real u[3], t[3];
        for (int i = 0; i < 3; i++) u[i] = unif(&g) - 0.5L, t[i] = unif(&g) - 0.5L;
        real span = 0.05L + 0.5L * unif(&g);
        for (int i = 0; i < 3; i++) {   /* every corner inside |q| < 0.99 (view space is Q30) */
            const real room = 0.99L - fabsl(o[i]), reach = (fabsl(u[i]) + fabsl(t[i])) / 2;
            if (span * reach > room) span = room / reach;
        }
        int32_t c[N + 1][N + 1][3];
        for (int a = 0; a <= N; a++)
            for (int b = 0; b <= N; b++)
                for (int i = 0; i < 3; i++)
                    c[a][b][i] = (int32_t)lroundl((o[i] + span * ((a - N / 2.0L) / N * u[i] + (b - N / 2.0L) / N * t[i])) * Q30);
        /* the reference region: the grid's outline (a planar quadrilateral; its corners rounded
         * stay within 2^-30 of the plane), split as two triangles clipped in real numbers */
        const int32_t qa[3][3] = {{c[0][0][0], c[0][0][1], c[0][0][2]}, {c[N][0][0], c[N][0][1], c[N][0][2]},
                                  {c[N][N][0], c[N][N][1], c[N][N][2]}};
        const int32_t qb[3][3] = {{c[0][0][0], c[0][0][1], c[0][0][2]}, {c[N][N][0], c[N][N][1], c[N][N][2]},
                                  {c[0][N][0], c[0][N][1], c[0][N][2]}};
        rvert ra[16], rb[16];
        const int na = ref_clip(&r, qa, ra), nb = ref_clip(&r, qb, rb);
        memset(count, 0, W * H);
        int any_clip = 0, nfold = 0;
        int32_t fold[64][4];   /* folded triangles' boxes, pixels, a pixel wider */
        for (int a = 0; a < N; a++)
            for (int b = 0; b < N; b++)
                for (int tri = 0; tri < 2; tri++) {
                    const int32_t(*c0)[3] = &c[a][b], (*c1)[3] = tri ? &c[a + 1][b + 1] : &c[a + 1][b],
                                  (*c2)[3] = tri ? &c[a][b + 1] : &c[a + 1][b + 1];
                    const int32_t q[3][3] = {{(*c0)[0], (*c0)[1], (*c0)[2]}, {(*c1)[0], (*c1)[1], (*c1)[2]}, {(*c2)[0], (*c2)[1], (*c2)[2]}};
                    mc_xvertex pv[3], out[MC_XFORM_CLIP_MAX];
                    uint32_t fl = 0;
                    for (int i = 0; i < 3; i++) mc_xform_project(&x, q[i], &pv[i]), fl |= pv[i].flags;
                    unsigned n;
                    if (fl) {
                        any_clip = 1;
                        n = mc_xform_clip_triangle(&x, q, out);
                    } else {
                        n = 3;
                        for (int i = 0; i < 3; i++) out[i] = pv[i];
                    }
                    const int front = mc_xform_front(&x, q);
                    for (unsigned i = 1; i + 1 < n; i++) {
                        mc_raster_vertex rv[3] = {{out[0].x, out[0].y, out[0].z}, {out[i].x, out[i].y, out[i].z},
                                                  {out[i + 1].x, out[i + 1].y, out[i + 1].z}};
                        mc_target tg = {col, dep, W, H};
                        mc_clear(&tg);
                        if (mc_raster_triangle(&tg, rv, 1, 0))
                            for (int p = 0; p < W * H; p++) count[p] += dep[p] != MC_DEPTH_EMPTY;
                        /* rounding to 1/16 pixel folded it (turned against its face): it may overlap a
                         * neighbour and leave a sliver empty, as any nearly degenerate triangles may */
                        const int64_t area = (int64_t)(rv[1].x - rv[0].x) * (rv[2].y - rv[0].y) -
                                             (int64_t)(rv[2].x - rv[0].x) * (rv[1].y - rv[0].y);
                        if (area != 0 && (area < 0) != front) {
                            if (nfold == 64) fail_msg("grid %d: more than 64 folded triangles", k);
                            int32_t *f = fold[nfold++];
                            f[0] = f[2] = rv[0].x, f[1] = f[3] = rv[0].y;
                            for (int j = 1; j < 3; j++) {
                                if (rv[j].x < f[0]) f[0] = rv[j].x;
                                if (rv[j].x > f[2]) f[2] = rv[j].x;
                                if (rv[j].y < f[1]) f[1] = rv[j].y;
                                if (rv[j].y > f[3]) f[3] = rv[j].y;
                            }
                            f[0] = (f[0] >> 4) - 1, f[1] = (f[1] >> 4) - 1, f[2] = (f[2] >> 4) + 1, f[3] = (f[3] >> 4) + 1;
                        }
                    }
                }
        grids++;
        clipped_grids += any_clip;
        folds += (unsigned long)nfold;
        for (int py = 0; py < H; py++)
            for (int px = 0; px < W; px++) {
                const int cnt = count[py * W + px];
                int folded = 0;
                for (int i = 0; i < nfold; i++)
                    folded |= px >= fold[i][0] && px <= fold[i][2] && py >= fold[i][1] && py <= fold[i][3];
                if (folded) { by_folds += cnt > 1; continue; }
                if (cnt > 1) fail_msg("grid %d: pixel (%d, %d) covered %d times", k, px, py, cnt);
                const real cxp = px + 0.5L, cyp = py + 0.5L, margin = 2.0L / 16;
                /* inside either half of the reference by the margin; outside both by it */
                const int in = (na >= 3 && inside_poly(ra, na, cxp, cyp, margin)) || (nb >= 3 && inside_poly(rb, nb, cxp, cyp, margin));
                const int near_a = na >= 3 && inside_poly(ra, na, cxp, cyp, -margin);
                const int near_b = nb >= 3 && inside_poly(rb, nb, cxp, cyp, -margin);
                if (in) {
                    sure_in++;
                    if (cnt != 1) fail_msg("grid %d: pixel (%d, %d) inside the clipped grid, covered %d times", k, px, py, cnt);
                } else if (!near_a && !near_b) {
                    sure_out++;
                    if (cnt != 0) fail_msg("grid %d: pixel (%d, %d) outside the clipped grid, covered", k, px, py);
                }
            }
    }
    print_message("# info: %lu grids (%lu with clipped triangles): %lu centres surely inside, %lu surely outside; %lu "
                  "triangles folded by rounding, %lu centres beside them covered twice\n", grids, clipped_grids, sure_in,
                  sure_out, folds, by_folds);
    if (clipped_grids < 200 || sure_in < 100000) fail_msg("too few clipped grids or covered centres");
    free(count), free(col), free(dep);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_project_is_vertex),
        cmocka_unit_test(test_planes_are_the_flags),
        cmocka_unit_test(test_reference_polygons),
        cmocka_unit_test(test_segments_and_shared_edges),
        cmocka_unit_test(test_facing),
        cmocka_unit_test(test_grid_tiles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

#endif
