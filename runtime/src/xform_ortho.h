/* The orthographic vertex projection as one inline step (private to the runtime): for the loop that
 * projects every vertex of a level (mesh_render.c mc_mesh_project, which the line styles share) and
 * for mc_xform_vertex itself, so that a vertex projected in the loop lands exactly where
 * mc_xform_vertex puts it.
 *
 * Promise: with mc_xform_ortho_init(&o, x) for an orthographic x, mc_xform_ortho_point(&o, p, out)
 * sets *out as mc_xform_vertex(x, p, out) does (xform.h), bit for bit; the rotation and the scale are
 * copied into o so that a loop keeps them in registers (a store through out could alias x).
 */
#ifndef MODELC_XFORM_ORTHO_H
#define MODELC_XFORM_ORTHO_H

#include <stdint.h>
#include "modelc/bits.h"
#include "modelc/xform.h"

MC_ALWAYS_INLINE int32_t ortho_band(int64_t v, uint32_t *flags)
{
    const int64_t lim = (int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS;
    /* inside: one unsigned compare (|v| <= lim), the usual case */
    if ((uint64_t)v + (uint64_t)lim <= 2u * (uint64_t)lim) return (int32_t)v;
    *flags |= MC_XFORM_FAR_OUT;
    return (int32_t)(v > 0 ? lim : -lim);
}

/* mc_round_shift(v, s) (v / 2^s to nearest, ties away from zero) for |v| < 2^62 and 1 <= s <= 62,
 * without a branch (the vertices' signs are a coin toss to a predictor): floor((v + 2^(s-1) -
 * [v < 0]) / 2^s), the floor an arithmetic shift (config.h MC_ASR_CHECK). */
MC_ALWAYS_INLINE int64_t ortho_round_shift_small(int64_t v, unsigned s)
{
    return (v + ((int64_t)1 << (s - 1)) - (int64_t)((uint64_t)v >> 63)) >> s;
}

/* a * b for |a| <= 2^30 and |b| <= 2^15: on a 32-bit core taken as 32-bit values, so that it
 * multiplies them in one step (a 64 x 64 product is three); on a 64-bit one as the 64-bit values
 * the rotation is kept in (ortho_coef), with no widening before each product. */
#if UINTPTR_MAX > 0xFFFFFFFFu
typedef int64_t ortho_coef;
#define ORTHO_MUL(a, b) ((int64_t)(a) * (int64_t)(b))
#else
typedef int32_t ortho_coef;
#define ORTHO_MUL(a, b) ((int64_t)(int32_t)(a) * (int64_t)(int32_t)(b))
#endif
/* R p, Q30: |q| < 2^30 (sums below 3 * 2^45 before the shift) */
#define ORTHO_ROTATE(x, row, p0, p1, p2) \
    ortho_round_shift_small(ORTHO_MUL((x)->r[row][0], p0) + ORTHO_MUL((x)->r[row][1], p1) + ORTHO_MUL((x)->r[row][2], p2), 16)

/* The orthographic projection of q = R p: S q in 1/16 pixel, Q16 * Q30 >> 42 (|S q| < 2^16 * 2^16 *
 * 2^30: mc_view_clamp keeps S within MC_VIEW_EXTENT_MAX pixels, xform.h) */
MC_ALWAYS_INLINE void ortho_project(int64_t scale, int64_t cx, int64_t cy, int64_t q0, int64_t q1, int64_t q2,
                                   mc_xvertex *out)
{
    uint32_t flags = 0;
    out->x = ortho_band(cx + ortho_round_shift_small(scale * q0, 42), &flags);
    out->y = ortho_band(cy - ortho_round_shift_small(scale * q1, 42), &flags);
    out->z = (uint32_t)ortho_round_shift_small(((int64_t)7 << 27) - q2, 15);   /* (7/8 - q.z) * 2^15 */
    out->flags = flags;
}

typedef struct mc_xform_ortho {
    ortho_coef r[3][3];      /* x->r */
    int64_t scale, cx, cy;
} mc_xform_ortho;

MC_ALWAYS_INLINE void mc_xform_ortho_init(mc_xform_ortho *o, const mc_xform *x)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) o->r[i][j] = x->r[i][j];
    o->scale = x->scale, o->cx = x->cx, o->cy = x->cy;
}

/* mc_xform_ortho_point of the point (p0, p1, p2) */
MC_ALWAYS_INLINE void mc_xform_ortho_xyz(const mc_xform_ortho *o, int64_t p0, int64_t p1, int64_t p2, mc_xvertex *out)
{
    ortho_project(o->scale, o->cx, o->cy, ORTHO_ROTATE(o, 0, p0, p1, p2), ORTHO_ROTATE(o, 1, p0, p1, p2),
                  ORTHO_ROTATE(o, 2, p0, p1, p2), out);
}

MC_ALWAYS_INLINE void mc_xform_ortho_point(const mc_xform_ortho *o, const int32_t p[3], mc_xvertex *out)
{
    mc_xform_ortho_xyz(o, p[0], p[1], p[2], out);
}

#endif
