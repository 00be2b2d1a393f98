/* Fixed-point arithmetic: the only number type on the rendering path.
 *
 * mc_fix is a signed 32-bit value with MC_FRAC_BITS fraction bits. Every operation here rounds to
 * nearest (ties away from zero) and saturates at MC_FIX_MAX / MC_FIX_MIN instead of wrapping, so a
 * result that cannot be represented is clamped, never turned into a wrong sign.
 */
#ifndef MODELC_FIXED_H
#define MODELC_FIXED_H

#include <stdint.h>
#include "config.h"

typedef int32_t mc_fix;

#define MC_FIX_ONE ((mc_fix)1 << MC_FRAC_BITS)
#define MC_FIX_MAX INT32_MAX
#define MC_FIX_MIN INT32_MIN
/* Largest screen coordinate (in pixels) the renderer lets a point reach: half the mc_fix range,
 * so that adding one more displacement vector can never overflow. */
#define MC_COORD_LIMIT ((int32_t)1 << (30 - MC_FRAC_BITS))

/* Saturate a 64-bit value to the mc_fix range. */
static inline mc_fix mc_fix_sat(int64_t v)
{
    return v > MC_FIX_MAX ? MC_FIX_MAX : v < MC_FIX_MIN ? MC_FIX_MIN : (mc_fix)v;
}

/* Shift right by s (0..63) rounding to nearest, ties away from zero, for any v > INT64_MIN.
 * Works on the magnitude (so -2.5 rounds like 2.5) and adds the last bit shifted out instead of
 * half a unit, so nothing can overflow. */
static inline int64_t mc_round_shift(int64_t v, int s)
{
    if (s <= 0) return v;
    uint64_t m = v >= 0 ? (uint64_t)v : 0u - (uint64_t)v;
    uint64_t q = (m >> s) + ((m >> (s - 1)) & 1u);
    return v >= 0 ? (int64_t)q : -(int64_t)q;
}

/* |v| as an unsigned number, exact for every v (INT64_MIN too), without a branch (the signs of a
 * normal's or an edge's components are a coin toss to a predictor). */
static inline uint64_t mc_mag64(int64_t v)
{
    const uint64_t neg = 0u - ((uint64_t)v >> 63);   /* all ones for v < 0 */
    return ((uint64_t)v ^ neg) - neg;
}

/* n / d rounded to nearest, ties away from zero, for d > 0 and |n| + d / 2 within int64. */
static inline int64_t mc_div_round(int64_t n, int64_t d) { return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d); }

static inline mc_fix mc_fix_from_int(int32_t i) { return mc_fix_sat((int64_t)i * MC_FIX_ONE); }
/* Integer part, rounded toward minus infinity (the pixel a coordinate falls in). */
static inline int32_t mc_fix_floor(mc_fix a) { return a >> MC_FRAC_BITS; }
static inline mc_fix mc_fix_add(mc_fix a, mc_fix b) { return mc_fix_sat((int64_t)a + b); }
static inline mc_fix mc_fix_sub(mc_fix a, mc_fix b) { return mc_fix_sat((int64_t)a - b); }
static inline mc_fix mc_fix_mul(mc_fix a, mc_fix b)
{
    return mc_fix_sat(mc_round_shift((int64_t)a * b, MC_FRAC_BITS));
}
/* a / b; division by zero saturates toward the sign of a (0/0 gives 0). */
mc_fix mc_fix_div(mc_fix a, mc_fix b);

/* (a * b) >> s, exactly rounded, saturated to int64, for a, b anywhere in int64 and s in 0..126.
 * Used once per frame to build the view from Q30 rotations and Q16 scales without losing bits. */
int64_t mc_mul_shift64(int64_t a, int64_t b, int s);

#endif
