/* Single-precision float screen positions for the renderer: the "float build" of make
 * bench-accuracy and of the float checks in tests/render and tests/stress. It implements the
 * interface of runtime/src/pos.h (read that first) and is selected with
 *   -DMC_POS_HEADER='"pos_single.h"' -Itests/accuracy -DMC_FLOAT=1
 * (MC_FLOAT tells the test programs, which receive float pixels from MC_PLOT_HOOK). It lives here,
 * beside the benchmark, because the runtime itself has no floating point (DESIGN.md). Positions are
 * pixels; the walk, culling, depth test and footprints are octree_render.c's, unchanged. Views are still
 * clamped to MC_COORD_LIMIT, which keeps every conversion to an integer defined.
 */
#ifndef MODELC_POS_SINGLE_H
#define MODELC_POS_SINGLE_H

typedef float mc_pos;                      /* pixels */
typedef float mc_pos_wide;                 /* products and distances: the same float */
typedef struct mc_pos2 { float x, y; } mc_pos2;
typedef float mc_pos_mag;

#define POS_FRAC 0
#define POS_EPSILON 0x1p-16f
/* Float sums round: a leaf reached through d additions may lie up to d half-spacings of float
 * beyond its exact position. Coordinates stay below MC_COORD_LIMIT, where floats are spaced at most
 * MC_COORD_LIMIT * 2^-23, so widening every reach by MC_MAX_DEPTH + 2 such half-spacings keeps
 * "wholly on screen" (no bounds checks) true of the computed positions. */
#define POS_REACH_SLACK ((MC_MAX_DEPTH + 2) * (float)MC_COORD_LIMIT * 0x1p-24f)
/* float sums round: (a + b) + c is not a + (b + c) */
#define POS_EXACT_SUMS 0

#define POS2(x, y) ((mc_pos2){(x), (y)})
#define POS2_ADD(a, b) ((mc_pos2){(a).x + (b).x, (a).y + (b).y})
#define POS2_X(p) ((p).x)
#define POS2_Y(p) ((p).y)
#define POS2_COL(p) ((intptr_t)(p).x)      /* on screen: non-negative, truncation is the floor */
#define POS2_ROW(p) ((intptr_t)(p).y)
#define POS_PIXELS(n) ((float)(n))
#define POS_HALF_PIXELS(n) ((float)(n) * 0.5f)

static inline int32_t pos_floor(mc_pos v)
{
    int32_t i = (int32_t)v;
    return i - (v < (float)i);
}

static inline mc_pos_wide pos_units(int64_t a, int64_t b, int s)
{
    float p = (float)a * (float)b;         /* then exact scaling by powers of two */
    for (; s >= 31; s -= 31) p *= 0x1p-31f;
    for (; s <= -31; s += 31) p *= 0x1p31f;
    return s >= 0 ? p / (float)(1u << s) : p * (float)(1u << -s);
}

static inline mc_pos pos_centre(int32_t size, int32_t t) { return (float)size * 0.5f + (float)t; }

static inline int32_t pos_footprint(mc_pos_wide side)
{
    if (!(side < MC_SPLAT_MAX)) return MC_SPLAT_MAX;   /* before converting: side may be huge */
    int32_t s = (int32_t)side;
    s += (float)s < side;
    return s < 1 ? 1 : s;
}

static inline mc_pos_mag pos_magnification(mc_pos_wide eye, mc_pos_wide dist) { return eye / dist; }
static inline mc_pos_wide pos_magnify(mc_pos_wide v, mc_pos_mag q) { return v * q; }

/* the sum is tested, not the offset: centre + offset rounds, and may round onto the far edge */
static inline int pos_place(mc_pos centre, mc_pos_wide offset, mc_pos size, mc_pos *out)
{
    *out = centre + offset;
    return *out >= 0 && *out < size;
}

/* perspective linearised about a node's centre (pos.h): no range to guard in float */
static inline int pos_linear_setup(mc_pos x, mc_pos y, mc_pos_mag q, mc_pos_wide dist, mc_pos_mag *gx, mc_pos_mag *gy)
{
    *gx = x * q / dist;
    *gy = y * q / dist;
    return 1;
}
static inline int pos_linear_ok(mc_pos r, mc_pos_wide o, mc_pos_wide eye, mc_pos_wide dist, int32_t eps)
{
    return dist > r && r * r * (o + eye + o * o / (2.0f * eye)) <= (float)eps / 128.0f * dist * (dist - r);
}
static inline mc_pos_wide pos_project(mc_pos x, mc_pos_mag q) { return x * q; }
static inline mc_pos pos_linear_step(mc_pos v, mc_pos vz, mc_pos_mag q, mc_pos_mag g) { return v * q - vz * g; }
#define POS2_HALF(p) ((mc_pos2){(p).x * 0.5f, (p).y * 0.5f})
static inline mc_pos pos_depth_units(mc_pos z, unsigned zshift)
{
    return z * ((float)(1u << MC_FRAC_BITS) / (float)(1u << zshift));
}

/* depth-buffer units are the fixed build's, 2^(F - zshift) per pixel, so both resolve depth alike */
static inline uint16_t pos_depth(mc_pos z, unsigned zshift)
{
    return (uint16_t)(z * ((float)(1u << MC_FRAC_BITS) / (float)(1u << zshift)));
}

#endif
