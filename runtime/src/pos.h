/* Screen positions of the octree renderer (octree_render.c): the one place that knows their number type.
 *
 * The renderer moves points by adding displacement vectors and reads a pixel off each position.
 * A position is Q MC_FRAC_BITS fixed point in an int32, and the hot loop packs x and y into one
 * int64 (x * 2^32 + y: on screen both are non-negative, so one 64-bit addition moves a point in
 * both axes). octree_render.c uses positions only through the types and operations below, so that the
 * accuracy benchmark can build the same renderer with another number type: config.h's
 * MC_POS_HEADER names a header that replaces this one with the same interface
 * (tests/accuracy/pos_single.h). Viewers, libraries and firmware never set it.
 *
 * Depths go through the same type: orthographic depths are kept in depth-buffer units and stored
 * with a conversion to uint16_t.
 */
#ifndef MODELC_POS_H
#define MODELC_POS_H

#include <stdint.h>
#include "modelc/config.h"
#include "modelc/depth.h"
#include "modelc/fixed.h"

#define F MC_FRAC_BITS

#ifdef MC_POS_HEADER
#include MC_POS_HEADER
#else

typedef int32_t mc_pos;                    /* Q F pixels */
typedef int64_t mc_pos_wide;               /* Q F pixels, with room for products */
typedef int64_t mc_pos2;                   /* x * 2^32 + y, each Q F */
typedef int64_t mc_pos_mag;                /* a perspective magnification, Q24 */

/* Fraction bits a position's value carries: a position is its length in pixels times 2^POS_FRAC. */
#define POS_FRAC F
/* The smallest positive distance (perspective: the near plane is never closer) */
#define POS_EPSILON 1
/* How far a computed sum of vectors may lie from the exact one beyond what the reaches cover: the
 * sums of integers are exact, so nothing. */
#define POS_REACH_SLACK 0
/* Whether adding vectors in another grouping gives the same positions (the renderer then sums two
 * levels' vectors once a frame): integers, yes. */
#define POS_EXACT_SUMS 1

#define POS2(x, y) ((int64_t)(x) * 4294967296 + (y))
#define POS2_ADD(a, b) ((a) + (b))
#define POS2_Y(p) ((int32_t)(uint32_t)(p))
#define POS2_X(p) ((int32_t)(((p) - POS2_Y(p)) >> 32))   /* exact for a negative y too */
/* pixel column / row of a position known to be on screen (non-negative) */
#define POS2_COL(p) ((intptr_t)((p) >> (32 + F)))
#define POS2_ROW(p) ((intptr_t)((uint32_t)(p) >> F))
/* n pixels, and n half pixels, as a position */
#define POS_PIXELS(n) ((int32_t)(n) << F)
#define POS_HALF_PIXELS(n) ((int32_t)(n) << (F - 1))

/* The pixel a position falls in, rounded toward minus infinity. */
static inline int32_t pos_floor(mc_pos v) { return v >> F; }

/* a * b / 2^s in units of the position type, rounded to nearest (s may be negative): builds
 * vectors, depths and distances once per frame from the Q30 rotation and the Q16 scale. */
static inline mc_pos_wide pos_units(int64_t a, int64_t b, int s)
{
    return s >= 0 ? mc_mul_shift64(a, b, s) : mc_mul_shift64(a, b * ((int64_t)1 << -s), 0);
}

/* The root's centre on screen: the middle of `size` pixels plus a translation of t pixels. */
static inline mc_pos pos_centre(int32_t size, int32_t t)
{
    return (int32_t)(((int64_t)size << (F - 1)) + (int64_t)t * ((int64_t)1 << F));
}

/* Footprint side in pixels of a leaf of side `side`: rounded up, 1..MC_SPLAT_MAX. */
static inline int32_t pos_footprint(mc_pos_wide side)
{
    int64_t s = (side + (((int64_t)1 << F) - 1)) >> F;
    return s < 1 ? 1 : s > MC_SPLAT_MAX ? MC_SPLAT_MAX : (int32_t)s;
}

/* Perspective: the magnification eye / dist (dist >= the near plane), and v magnified by it,
 * exact and saturating (near the eye the magnification reaches 2^14). */
static inline mc_pos_mag pos_magnification(mc_pos_wide eye, mc_pos_wide dist) { return (eye << 24) / dist; }
static inline mc_pos_wide pos_magnify(mc_pos_wide v, mc_pos_mag q) { return mc_mul_shift64(v, q, 24); }

/* Perspective: the screen position centre + offset in *out, if it lies in [0, size); tested before
 * the sum, which could overflow. */
static inline int pos_place(mc_pos centre, mc_pos_wide offset, mc_pos size, mc_pos *out)
{
    if (offset < -centre || offset >= size - centre) return 0;
    *out = (mc_pos)(centre + offset);
    return 1;
}

/* Perspective, linearised about a node's centre (octree_render.c, linear_frame). A leaf at x + dx,
 * dist + dz from the eye lands at q x + q (dx - x dz / dist), q = eye / dist, to first order:
 * g = q x / dist is the slope of the second term. Both stay below 2^31 (Q24), so that the products
 * in pos_linear_step fit 64 bits; 0 where they would not (the node is then projected leaf by leaf). */
static inline int pos_linear_setup(mc_pos x, mc_pos y, mc_pos_mag q, mc_pos_wide dist, mc_pos_mag *gx, mc_pos_mag *gy)
{
    const int64_t lim = (int64_t)1 << 31;
    if (q >= lim) return 0;
    *gx = ((int64_t)x * q) / dist;
    *gy = ((int64_t)y * q) / dist;
    return *gx > -lim && *gx < lim && *gy > -lim && *gy < lim;
}

/* q x rounded, for |x| < 2^31 and 0 < q < 2^31 (pos_linear_setup's range): a linear frame's
 * centre, without pos_magnify's general product. */
static inline mc_pos_wide pos_project(mc_pos x, mc_pos_mag q) { return ((int64_t)x * q + ((int64_t)1 << 23)) >> 24; }

/* Whether the first-order projection about a node's centre is within eps / 256 pixel of the exact one
 * for every point within r of that centre (all Q F pixels; o: the centre's offset from the view
 * axis on screen, the larger axis; dist > 0). The error on one axis is
 *     q dz (u dz - dx) / (1 + dz / dist),   q = eye / dist, u = x / dist = o / eye
 * (exact minus first order). Over |(dx, dz)| <= r, |dz (u dz - dx)| is at most
 * r^2 (|u| + sqrt(u^2 + 1)) / 2 <= r^2 (|u| + 1 + u^2 / 2) / 2, so the error is at most
 *     r^2 (o + eye + o^2 / (2 eye)) / (2 dist (dist - r)).
 * Evaluated in Q4 pixels, every rounding towards failing the test:
 *     8 r^2 (o + eye + o^2 / (2 eye)) <= eps dist (dist - r)   (r, o, eye rounded up, dist down). */
static inline int pos_linear_ok(mc_pos r, mc_pos_wide o, mc_pos_wide eye, mc_pos_wide dist, int32_t eps)
{
    const int s = F - 4;
    const int64_t up = ((int64_t)1 << s) - 1;
    const int64_t r4 = ((int64_t)r + up) >> s, o4 = (o + up) >> s, e4 = ((eye + up) >> s) + 1, d4 = dist >> s;
    const int64_t dr = d4 - r4;
    if (dr <= 0) return 0;
    const int64_t t = (8 * r4 * r4 + dr - 1) / dr;     /* r4 < 2^20: no overflow */
    const int64_t w = o4 + e4 + (o4 * o4 + 2 * e4 - 1) / (2 * e4);   /* o4 < 2^17 (o < 2^28) */
    return t <= ((int64_t)eps * d4) / w;
}

/* The linearised image q v - g vz of one displacement (v across, vz away from the eye), rounded to
 * a multiple of 4 units of Q F (2 units off at most, 2^-(F-1) pixel), so that the two levels below
 * a linear frame's top halve its vectors exactly (POS2_HALF). */
static inline mc_pos pos_linear_step(mc_pos v, mc_pos vz, mc_pos_mag q, mc_pos_mag g)
{
    return (mc_pos)((((int64_t)v * q - (int64_t)vz * g + ((int64_t)1 << 25)) >> 26) * 4);
}
/* Half of a packed pair whose halves are both even: exact (an arithmetic shift, as pos_floor's). */
#define POS2_HALF(p) ((p) >> 1)

/* Perspective: a depth kept as a position (Q F pixels) in depth-buffer units, as a position. */
static inline mc_pos pos_depth_units(mc_pos z, unsigned zshift) { return z >> zshift; }

/* Perspective: the depth-buffer value of a depth kept as a position (Q F pixels). */
static inline uint16_t pos_depth(mc_pos z, unsigned zshift) { return (uint16_t)((uint32_t)z >> zshift); }

#endif

#endif
