/* Point-octree renderer: see modelc/octree_render.h for what it promises.
 *
 * Long because the walk is one concern with several hot paths (one pixel a leaf, unclipped squares,
 * clipped and perspective leaves, culled subtrees) that share the walk's context and cursors; split
 * into files, each path would need that context exported and the compiler could no longer inline
 * them into the walk. */
#include "modelc/octree_render.h"
#include "modelc/bits.h"
#include "modelc/chunk.h"
#include "child_bits.h"
#include "pos.h"

/* Depth: offset so the model's bounding sphere spans [0, 2 * radius] and never goes negative. The
 * depth buffer keeps z >> zshift, zshift chosen per frame so that the span fits 16 bits. In
 * perspective z is in the same Q F pixels as x and y (so the division by the distance is as exact
 * as the position it scales) and shifted per point; orthographic depth vectors are built already
 * shifted, so the hot loop stores z as it is. */

/* sqrt(3)/2 in Q30 and Q16, rounded up, for bounding spheres that are never too small */
#define HALF_SQRT3_Q30 929887697
#define HALF_SQRT3_Q16 56756

/* Displacement from the centre of a node at one level to that of its child k, as one packed pair
 * (pos.h) and a depth. Kept together so that the hot loop reaches all of a level's vectors from one
 * base register. */
typedef struct levelvec {
    mc_pos2 xy[8];
    mc_pos z[8];
} levelvec;

/* The same displacements apart, depth in Q F: what perspective divides (leaves_perspective). */
typedef struct exactvec {
    mc_pos x[8], y[8], z[8];
} exactvec;

/* FLAT_SQUARES: orthographic 2x2 squares walked flat (config.h MC_FLAT_SQUARES), where positions are
 * exact sums (POS_EXACT_SUMS, pos.h): the walk adds the last two levels' vectors first. Else
 * draw_inside_squares draws them: the same pixels. */
#define FLAT_SQUARES (MC_FLAT_SQUARES && POS_EXACT_SUMS)

#if FLAT_SQUARES
/* Orthographic squares of two pixels (draw_squares2): from the centre of a level d-2 node to that
 * of each of its 64 possible leaves, leaf 8 j + k being child k of its child j: the sums of the last
 * two levels' vectors, set per frame. */
typedef struct leafvec {
    mc_pos2 xy[64];
    mc_pos z[64];
} leafvec;
#endif

typedef struct ctx {
    mc_cursor mask[MC_MAX_DEPTH];
    mc_cursor color;                     /* colours of the drawn level */
    levelvec v[MC_MAX_DEPTH];            /* level-l node -> child k */
#if FLAT_SQUARES
    leafvec leaves2;                     /* with 2x2 squares, orthographic (see leafvec) */
#endif
    mc_pos radius;                       /* bounding sphere of the model, Q F pixels */
    /* how far the drawn leaves under a level-l node can lie from its centre, per screen axis: the
     * sum of the largest displacement of each level below, so exact for the fixed-point positions
     * (plus POS_REACH_SLACK where sums round, pos.h) */
    mc_pos reach_x[MC_MAX_DEPTH + 1], reach_y[MC_MAX_DEPTH + 1];
    uint8_t *fb;
    uint16_t *zb;
    int32_t w, h;                        /* size in pixels */
    mc_pos wf, hf;                       /* size in Q F */
    unsigned d;                          /* drawn level */
    unsigned zshift;                     /* depth buffer value = z >> zshift (see the top) */
    unsigned poll_level;                 /* level at which the abort callback is polled */
    int perspective;
    int inside;                          /* 0: every node drawn with checks (small targets, splats) */
    int32_t splat;                       /* orthographic footprint side, pixels (1: one pixel) */
    mc_pos_wide leaf_side;               /* perspective zoom splats: leaf side at magnification 1,
                                          * Q F pixels; 0: one pixel per leaf */
    mc_pos cx, cy;                       /* perspective: screen centre plus translation, Q F */
    mc_pos_wide eye, near;               /* perspective: eye distance and near plane, Q F pixels */
    /* perspective: the exact vectors of the last three levels (level l in pv[l + 3 - d]). At d >= 3,
     * v[d-3..d-1] hold each linear frame's instead, with z in depth-buffer units (linear_frame) */
    exactvec pv[3];
    mc_pos ball[2];                      /* how far a level d-3 / d-2 node's leaves lie from its centre */
    mc_pos basis[2][3][3];               /* the step to a child along model axis j at levels d-3 and
                                          * d-2, as the exact vectors are: [level][j][x, y, z], Q F */
    mc_abort_fn abort;
    void *user;
    uint32_t points, polls;
    int aborted;
    /* back-facing subtrees (octree_render.h, mc_cull): the cones of level cone_level, NO_CONES when
     * none are used this frame */
    mc_cursor cone;
    unsigned cone_level;
    int32_t cone_w[3];                   /* unit vector towards the viewer, model axes, Q14 */
    int32_t cone_spread;                 /* perspective: sin of the eye's spread over the sphere, Q14 */
    uint32_t culled;
} ctx;

#define NO_CONES (MC_MAX_DEPTH + 1u)
/* Perspective depths in depth-buffer units are offset by this: a linear frame's leaves sum three
 * rounded depth vectors to a floored centre (linear_frame), and never go below 0. */
#define FRAME_DEPTH_ROOM 3
#define CONE_BYTES 7   /* octree.h */

/* Steps over the subtree of one node at level l without drawing it: reads the masks of levels
 * l..d-1 inside the subtree only to count how far each cursor must move. */
static void skip_subtree(ctx *c, unsigned l)
{
    uint32_t n = 1;
    for (unsigned lev = l; lev < c->d; lev++) {
        if (lev == c->cone_level) mc_cursor_skip(&c->cone, CONE_BYTES * n);
        uint32_t children = 0;
        for (uint32_t i = 0; i < n; i++) {
            if (c->mask[lev].p == c->mask[lev].end) mc_cursor_refill(&c->mask[lev]);
            children += mc_popcount8(*c->mask[lev].p++);
        }
        n = children;
    }
    mc_cursor_skip(&c->color, n);
}

/* An s x s footprint (octree_render.h, MC_SPLAT_ZOOM) centred on (fx, fy), which is on the target, clipped
 * to the target; each pixel depth tested. */
static void draw_square(ctx *c, mc_pos fx, mc_pos fy, int32_t s, uint16_t depth, uint8_t color)
{
    int32_t x0 = pos_floor(fx - POS_HALF_PIXELS(s - 1)), y0 = pos_floor(fy - POS_HALF_PIXELS(s - 1));
    int32_t x1 = x0 + s, y1 = y0 + s;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > c->w) x1 = c->w;
    if (y1 > c->h) y1 = c->h;
    for (int32_t y = y0; y < y1; y++) {
        uint16_t *zr = c->zb + y * c->w;
        uint8_t *fr = c->fb + y * c->w;
        for (int32_t x = x0; x < x1; x++)
            if (depth < zr[x]) { zr[x] = depth; fr[x] = color; }
    }
}

/* The squares' depth test: the branch (the four pixels of a leaf mostly win or lose together, and
 * the select form's two stores a pixel cost more instructions than the branches they replace) */
#define SQUARE_TEST(i, depth, col) if ((depth) < zb[i]) { zb[i] = (depth); fb[i] = *(col); }
/* The 2x2 square whose top-left pixel is i, colour cv read once (a pixel store may alias the colour
 * array); fb1 = fb + w, the colour row below, kept in a register of its own so that the stores
 * fold into addressing. */
#define SQUARE2_TEST(i, depth, cv)                                                                 \
    {                                                                                              \
        uint16_t *const z0_ = zb + (i), *const z1_ = z0_ + w;                                      \
        if ((depth) < z0_[0]) { z0_[0] = (depth); fb[i] = (cv); }                                  \
        if ((depth) < z0_[1]) { z0_[1] = (depth); fb[(i) + 1] = (cv); }                            \
        if ((depth) < z1_[0]) { z1_[0] = (depth); fb1[i] = (cv); }                                 \
        if ((depth) < z1_[1]) { z1_[1] = (depth); fb1[(i) + 1] = (cv); }                           \
    }

/* One leaf as a 2x2 square: its position xy + vxy floors to the square's top-left pixel, its depth
 * is z + vz, its colour *col (read once: a pixel store may alias the colour array); zb, fb, fb1 and
 * w as SQUARE2_TEST has them. */
#define SQUARE2_LEAF(xy, z, vxy, vz, col)                                                          \
    {                                                                                              \
        const mc_pos2 p_ = POS2_ADD(xy, vxy);                                                      \
        const intptr_t i_ = POS2_ROW(p_) * w + POS2_COL(p_);                                       \
        const uint16_t depth_ = (uint16_t)((z) + (vz));                                            \
        const uint8_t cv_ = *(col);                                                                \
        MC_PLOT_HOOK(POS2_X(p_) + POS_HALF_PIXELS(1), POS2_Y(p_) + POS_HALF_PIXELS(1), col);       \
        SQUARE2_TEST(i_, depth_, cv_)                                                              \
    }

/* The leaves (mask m, colours col) of one level d-1 node as 2x2 squares wholly on the target, no
 * checks: xy is the node's centre less half a pixel both ways, so that a leaf's position floors to
 * its square's top-left pixel (as draw_square has it); lv its leaves' vectors; fb1 = fb + w, which
 * the caller's loop keeps. Returns col past the node's colours. */
MC_ALWAYS_INLINE const uint8_t *square2_leaves(uint16_t *restrict zb, uint8_t *restrict fb, uint8_t *fb1, intptr_t w,
                                               const levelvec *lv, unsigned m, mc_pos2 xy, mc_pos z, const uint8_t *col)
{
    for (; m; m &= m - 1, col++) {
        const unsigned k = mc_ctz(m);
        SQUARE2_LEAF(xy, z, lv->xy[k], lv->z[k], col)
    }
    return col;
}

/* Where the leaves under a level-l node centred at (x, y) land: 0 partly on screen (or drawn with
 * checks anyway: c->inside is 0), 1 wholly on screen, -1 wholly off screen (orthographic only). */
static int classify(const ctx *c, mc_pos x, mc_pos y, unsigned l)
{
    const mc_pos rx = c->reach_x[l], ry = c->reach_y[l];
    if (x + rx < 0 || y + ry < 0 || x - rx >= c->wf || y - ry >= c->hf) return -1;   /* by the leaves' centres */
    /* and their squares: a square's top-left pixel is floor(p - (s - 1) / 2) and its bottom-right
     * one s - 1 further, so it is on the target exactly when (s - 1) / 2 <= p and p + (s - 1) / 2 < w */
    const mc_pos margin = POS_HALF_PIXELS(c->splat - 1), sx = rx + margin, sy = ry + margin;
    return c->inside && x - sx >= 0 && y - sy >= 0 && x + sx < c->wf && y + sy < c->hf;
}

/* Leaves of one level d-1 node that may reach off screen, orthographic: each point checked (a leaf
 * is drawn when its centre is on the target), as one pixel or, with footprints above one pixel, as
 * a c->splat square clipped to the target. */
static void leaves_clipped(ctx *c, unsigned m, mc_pos x, mc_pos y, mc_pos z, const uint8_t *col)
{
    const unsigned l = c->d - 1;
    if (c->splat == 2 && classify(c, x, y, l) > 0) {   /* the node's squares are all on the target after all */
        c->points += mc_popcount8(m);
        square2_leaves(c->zb, c->fb, c->fb + c->w, c->w, &c->v[l], m, POS2(x - POS_HALF_PIXELS(1), y - POS_HALF_PIXELS(1)),
                       z, col);
        return;
    }
    const mc_pos2 *v = c->v[l].xy;
    const mc_pos *vz = c->v[l].z;
    for (; m; m &= m - 1, col++) {
        unsigned k = mc_ctz(m);
        const mc_pos2 p = POS2_ADD(POS2(x, y), v[k]);
        mc_pos fx = POS2_X(p), fy = POS2_Y(p);
        int32_t px = pos_floor(fx), py = pos_floor(fy);
        if ((uint32_t)px >= (uint32_t)c->w || (uint32_t)py >= (uint32_t)c->h) continue;
        uint16_t depth = (uint16_t)(z + vz[k]);
        c->points++;
        MC_PLOT_HOOK(fx, fy, col);
        if (c->splat == 2) {
            /* most leaves of a node whose squares may reach off the target still have theirs on it */
            const int32_t x0 = pos_floor(fx - POS_HALF_PIXELS(1)), y0 = pos_floor(fy - POS_HALF_PIXELS(1));
            if ((uint32_t)x0 < (uint32_t)(c->w - 1) && (uint32_t)y0 < (uint32_t)(c->h - 1)) {
                const intptr_t w = c->w, i = (intptr_t)y0 * w + x0;
                uint16_t *zb = c->zb;
                uint8_t *fb = c->fb, *fb1 = fb + w;
                const uint8_t cv = *col;
                SQUARE2_TEST(i, depth, cv)
            } else {
                draw_square(c, fx, fy, 2, depth, *col);
            }
        } else if (c->splat > 1) {
            draw_square(c, fx, fy, c->splat, depth, *col);
        } else {
            int32_t i = py * c->w + px;
            if (depth < c->zb[i]) { c->zb[i] = depth; c->fb[i] = *col; }
        }
    }
}

/* Leaves of one level d-1 node in perspective, lv its exact vectors: each point divides by its own
 * distance (exact, not linearised, so it lands where the reference renderer, runtime/ref, puts it).
 * Points nearer than the near plane (1/64 cube side in front of the eye) are not drawn. */
static void leaves_perspective(ctx *c, const exactvec *lv, unsigned m, mc_pos x, mc_pos y, mc_pos z,
                               const uint8_t *col)
{
    const mc_pos *vx = lv->x, *vy = lv->y, *vz = lv->z;
    for (; m; m &= m - 1, col++) {
        unsigned k = mc_ctz(m);
        mc_pos zk = z + vz[k];
        mc_pos_wide dist = c->eye + zk - c->radius;   /* z carries a +radius offset */
        if (dist < c->near) continue;
        const mc_pos_mag q = pos_magnification(c->eye, dist);
        mc_pos fx, fy;
        if (!pos_place(c->cx, pos_magnify(x + vx[k], q), c->wf, &fx) ||
            !pos_place(c->cy, pos_magnify(y + vy[k], q), c->hf, &fy)) continue;
        int32_t i = pos_floor(fy) * c->w + pos_floor(fx);
        uint16_t depth = (uint16_t)(pos_depth(zk, c->zshift) + FRAME_DEPTH_ROOM);
        c->points++;
        MC_PLOT_HOOK(fx, fy, col);
        if (c->leaf_side) {                               /* zoom splats: the leaf's side here */
            int32_t s = pos_footprint(pos_magnify(c->leaf_side, q));
            if (s > 1) { draw_square(c, fx, fy, s, depth, *col); continue; }
        }
        if (depth < c->zb[i]) { c->zb[i] = depth; c->fb[i] = *col; }
    }
}

/* One node at level d-1 that may reach off screen, or any with footprints, or one projected leaf by
 * leaf. */
static void leaves(ctx *c, unsigned m, mc_pos x, mc_pos y, mc_pos z, const uint8_t *col)
{
    /* perspective at d >= 3 reaches here only inside linear frames, whose leaves are orthographic */
    if (c->perspective && c->d < 3) leaves_perspective(c, &c->pv[2], m, x, y, z, col);
    else leaves_clipped(c, m, x, y, z, col);
}

/* The hot path: the leaves of one node at level d-1 wholly on screen, orthographic. pxy is its
 * packed centre (see levelvec), pz its depth; lv, lz the leaf level's vectors; col its leaves'
 * colours. A present child costs one 64-bit and one 32-bit addition, the pixel index and the depth
 * test. LEAF(n, j) draws child j of a node whose mask is n, when bit j is set; its colour is the
 * rank of j among the set bits of n. */
#define LEAF(n, j)                                                                         \
    if ((n) & (1u << (j))) {                                                               \
        const mc_pos2 p_ = POS2_ADD(pxy, lv[j]);                                           \
        intptr_t i_ = POS2_ROW(p_) * w + POS2_COL(p_);                                     \
        uint16_t depth_ = (uint16_t)(pz + lz[j]);                                          \
        const uint8_t *col_ = col + mc_popcount8((n) & ((1u << (j)) - 1u));                   \
        MC_PLOT_HOOK(POS2_X(p_), POS2_Y(p_), col_);                                        \
        DEPTH_TEST(i_, depth_, col_)                                                       \
    }
#if MC_DEPTH_SELECT
/* No branch: the leaf's depth and colour are written either to its pixel, when it is nearer, or to
 * a spare pixel that no leaf of this draw_inside call lands on and whose values draw_inside puts
 * back at the end (spare_pixel): one conditional move of an index, no reads of the old values. */
#define DEPTH_TEST(i, depth, col)                                                          \
    { intptr_t t_ = (depth) < zb[i] ? (i) : spare;                                         \
      OPAQUE_INDEX(t_);                                                                    \
      zb[t_] = (depth); fb[t_] = *(col); }
#if defined(__GNUC__) && !defined(__clang__)
/* Hides the selected index from GCC's optimiser: otherwise it selects the two buffer addresses
 * instead (tree PRE), with a branch. Clang selects the index without it. */
#define OPAQUE_INDEX(v) __asm__("" : "+r"(v))
#else
#define OPAQUE_INDEX(v) ((void)0)
#endif
#else
#define DEPTH_TEST(i, depth, col) if ((depth) < zb[i]) { zb[i] = (depth); fb[i] = *(col); }
#endif
#define LEAVES(n) LEAF(n, 0) LEAF(n, 1) LEAF(n, 2) LEAF(n, 3) LEAF(n, 4) LEAF(n, 5) LEAF(n, 6) LEAF(n, 7)

#if MC_LEAF_SWITCH
/* One case per mask value: the compiler folds every test of LEAVES(n) and every colour rank, so a
 * node costs one indirect jump and each present leaf only its own work (see config.h). */
#define CASE1(n) case n: LEAVES(n) col += MC_POPCOUNT8(n); break;
#define CASE4(n) CASE1(n) CASE1(n + 1) CASE1(n + 2) CASE1(n + 3)
#define CASE16(n) CASE4(n) CASE4(n + 4) CASE4(n + 8) CASE4(n + 12)
#define CASE64(n) CASE16(n) CASE16(n + 16) CASE16(n + 32) CASE16(n + 48)
/* ... and moves col past the node's colours by a constant */
#define DRAW_LEAVES(cm)                                                                    \
    switch (cm) { CASE64(0) CASE64(64) CASE64(128) CASE64(192) }
#else
/* The paper's unrolled 8-child loop: an absent child costs a test and a branch. */
#define DRAW_LEAVES(cm) LEAVES(cm) col += mc_popcount8(cm);
#endif

#if MC_DEPTH_SELECT
/* A pixel none of the leaves under the level-l node centred at xy can land on: a corner of the
 * target outside the node's reach. There is one: setup_vectors sets c->inside only when a level
 * d-3 node's reach spans less than the target's width or height. */
static intptr_t spare_pixel(const ctx *c, unsigned l, mc_pos2 xy)
{
    const mc_pos x = POS2_X(xy), y = POS2_Y(xy);
    if (pos_floor(x - c->reach_x[l]) > 0 || pos_floor(y - c->reach_y[l]) > 0) return 0;
    if (pos_floor(x + c->reach_x[l]) < c->w - 1) return c->w - 1;
    return (intptr_t)(c->h - 1) * c->w;
}
#endif

/* The walk draw_inside and draw_inside_squares share: the level d-2 children (mask m) of a level d-3
 * node centred at (xy, z), each one's level d-1 children's mask cm with its centre (pxy, pz), LEAF_BODY
 * drawing their leaves and moving col past their colours. Masks of level d-1 come one sibling group
 * per d-2 node and colours one cousin group per d-2 node, each from one chunk (octree.h). Everything
 * the loops touch is in locals, so nothing is reloaded after each pixel store: the two cursors too,
 * written back before a refill and at the end (a colour store may alias any field of *c). */
#define WALK_LEVEL3(LEAF_BODY)                                                                     \
    mc_cursor *const mc = &c->mask[l3 + 2];                                                        \
    const uint8_t *mp = mc->p, *mend = mc->end;                                                    \
    const uint8_t *col = c->color.p, *cend = c->color.end, *first = col;                           \
    uint32_t points = 0;                                                                           \
    for (child_iter s3 = CHILDREN(m); s3; s3 = NEXT_CHILD(s3)) {                                   \
        const intptr_t k3 = CHILD(s3);                                                             \
        const mc_pos2 xy2 = POS2_ADD(xy, L[0].xy[k3]);                                             \
        const mc_pos zz2 = z + L[0].z[k3];                                                         \
        const unsigned m2 = *masks2++;                                                             \
        if (mp >= mend) { mc->p = mp; mc_cursor_refill(mc); mp = mc->p; mend = mc->end; }          \
        const uint8_t *masks1 = mp;                                                                \
        mp += mc_popcount8(m2);                                                                    \
        if (col >= cend) {                                                                         \
            points += (uint32_t)(col - first);                                                     \
            c->color.p = col;                                                                      \
            mc_cursor_refill(&c->color);                                                           \
            col = first = c->color.p;                                                              \
            cend = c->color.end;                                                                   \
        }                                                                                          \
        for (child_iter s2 = CHILDREN(m2); s2; s2 = NEXT_CHILD(s2)) {                              \
            const intptr_t k2 = CHILD(s2);                                                         \
            const mc_pos2 pxy = POS2_ADD(xy2, L[1].xy[k2]);                                        \
            const mc_pos pz = zz2 + L[1].z[k2];                                                    \
            const unsigned cm = *masks1++;                                                         \
            LEAF_BODY                                                                              \
        }                                                                                          \
    }                                                                                              \
    points += (uint32_t)(col - first); /* every leaf here is on screen */                          \
    mc->p = mp;                                                                                    \
    c->color.p = col;                                                                              \
    c->points += points;

/* Nodes at level d-2 wholly on screen, orthographic: the children of one node at level d-3 whose
 * mask is m (or just one of them: m = its child bit), through WALK_LEVEL3. Not inlined: there is
 * one copy of the leaf code however many callers. */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void draw_inside(ctx *c, unsigned l3, unsigned m, const uint8_t *masks2, mc_pos2 xy, mc_pos z)
{
    const levelvec *restrict L = &c->v[l3];       /* levels d-3, d-2 (L + 1) and d-1 (L + 2) */
#define lv (L[2].xy)
#define lz (L[2].z)
    uint8_t *restrict fb = c->fb;
    uint16_t *restrict zb = c->zb;
    const intptr_t w = c->w;
#if MC_DEPTH_SELECT
    const intptr_t spare = spare_pixel(c, l3, xy);
    const uint16_t spare_depth = zb[spare];
    const uint8_t spare_color = fb[spare];
#endif
    WALK_LEVEL3(DRAW_LEAVES(cm))
#if MC_DEPTH_SELECT
    zb[spare] = spare_depth;
    fb[spare] = spare_color;
#endif
#undef lv
#undef lz
}

/* draw_inside for footprints of s > 1 pixels (MC_SPLAT_ZOOM, orthographic; c->splat): each leaf an
 * s x s square with no clipping, since the reach then holds the squares too (setup_vectors). The
 * square's top-left pixel is the leaf's centre less (s - 1) / 2 pixels, as draw_square has it; that
 * offset is folded into the node's centre once. s is a constant where the caller is inlined for 2. */
/* Test hook: 1 draws every footprint above one pixel through the clipped path, so a test can
 * compare the two (tests/stress: the other form of the renderer). */
#ifndef MC_TEST_CLIPPED_SQUARES
#define MC_TEST_CLIPPED_SQUARES 0
#endif
MC_ALWAYS_INLINE void inside_squares(ctx *c, unsigned l3, unsigned m, const uint8_t *masks2, mc_pos2 xy, mc_pos z,
                                     const int32_t s)
{
    const levelvec *restrict L = &c->v[l3];
    uint8_t *restrict fb = c->fb;
    uint16_t *restrict zb = c->zb;
    const intptr_t w = c->w;
    uint8_t *const fb1 = fb + w;   /* the row below, for SQUARE2_TEST; based on fb: the rows overlap */
    const mc_pos half = POS_HALF_PIXELS(s - 1);
    xy = POS2_ADD(xy, POS2(-half, -half));
    /* each leaf a square; for s = 2 written out (the loops are not unrolled at -O2) */
#define SQUARE_LEAVES                                                                              \
    if (s == 2) {                                                                                  \
        col = square2_leaves(zb, fb, fb1, w, &L[2], cm, pxy, pz, col);                             \
    } else {                                                                                       \
        for (unsigned lm = cm; lm; lm &= lm - 1, col++) {                                          \
            const unsigned j = mc_ctz(lm);                                                         \
            const mc_pos2 p = POS2_ADD(pxy, L[2].xy[j]);                                           \
            const intptr_t i = POS2_ROW(p) * w + POS2_COL(p);                                      \
            const uint16_t depth = (uint16_t)(pz + L[2].z[j]);                                     \
            const uint8_t cv = *col;   /* once: a pixel store may alias it */                      \
            MC_PLOT_HOOK(POS2_X(p) + half, POS2_Y(p) + half, col);                                 \
            for (int32_t dy = 0; dy < s; dy++)                                                     \
                for (int32_t dx = 0; dx < s; dx++) SQUARE_TEST(i + dy * w + dx, depth, &cv)        \
        }                                                                                          \
    }
    WALK_LEVEL3(SQUARE_LEAVES)
#undef SQUARE_LEAVES
}

#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void draw_inside_squares(ctx *c, unsigned l3, unsigned m, const uint8_t *masks2, mc_pos2 xy, mc_pos z)
{
    if (c->splat == 2) inside_squares(c, l3, m, masks2, xy, z, 2);   /* 640x480 at depth 8: the common one */
    else inside_squares(c, l3, m, masks2, xy, z, c->splat);
}

#if FLAT_SQUARES
/* Orthographic 2x2 squares, the 640x480 view at depth 8, walked flat (FLAT_SQUARES): a level d-2
 * node's leaves are one 64-bit mask (bit 8 j + k: child k of its child j) over c->leaves2, drawn in
 * one loop. So a leaf costs its square and a bit scan, its node's masks one shift and OR each, and
 * the loop's one hard branch (its end) comes once per level d-2 node, not once per level d-1 node.
 * The same leaves, in the same order, as square2_leaves under WALK_LEVEL3. */
typedef struct square_run {
    mc_pos2 xy;                          /* the level d-2 node's centre, less half a pixel both ways */
    uint64_t leaves;
    mc_pos z;
} square_run;

/* The leaves of runs r..end-1, colours from c->color. A function of its own: none of the walk's
 * state is live across its loop, which then keeps everything in registers. */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void draw_runs2(ctx *c, const square_run *r, const square_run *end)
{
    uint16_t *restrict zb = c->zb;
    uint8_t *restrict fb = c->fb;
    const intptr_t w = c->w;
    uint8_t *const fb1 = fb + w;   /* the row below, for SQUARE2_TEST; based on fb: the rows overlap */
    const leafvec *const lv = &c->leaves2;
    const uint8_t *col = c->color.p, *first = col;
    uint32_t points = 0;
    for (; r < end; r++) {
        if (col >= c->color.end) {   /* one cousin group per level d-2 node, from one chunk */
            points += (uint32_t)(col - first);
            c->color.p = col;
            mc_cursor_refill(&c->color);
            col = first = c->color.p;
        }
        const mc_pos2 xy = r->xy;
        const mc_pos z = r->z;
        for (uint64_t m = r->leaves; m; m &= m - 1, col++) {
            const uint64_t k = mc_ctz64(m);
            SQUARE2_LEAF(xy, z, lv->xy[k], lv->z[k], col)
        }
    }
    c->color.p = col;
    c->points += points + (uint32_t)(col - first);
}

/* draw_inside_squares for s = 2, orthographic: the level d-2 children (mask m) of a level d-3 node
 * centred at (xy, z) as runs, then their leaves (draw_runs2). */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void draw_squares2(ctx *c, unsigned l3, unsigned m, const uint8_t *masks2, mc_pos2 xy, mc_pos z)
{
    const levelvec *restrict L = &c->v[l3];
    mc_cursor *const mc = &c->mask[l3 + 2];
    const uint8_t *mp = mc->p, *mend = mc->end;
    square_run runs[8], *r = runs;
    xy = POS2_ADD(xy, POS2(-POS_HALF_PIXELS(1), -POS_HALF_PIXELS(1)));
    for (child_iter s3 = CHILDREN(m); s3; s3 = NEXT_CHILD(s3), r++) {
        const intptr_t k3 = CHILD(s3);
        const unsigned m2 = *masks2++;
        if (mp >= mend) { mc->p = mp; mc_cursor_refill(mc); mp = mc->p; mend = mc->end; }
        uint64_t leaves = 0;   /* its children's masks, one sibling group, each at its child's byte */
        for (child_iter s2 = CHILDREN(m2); s2; s2 = NEXT_CHILD(s2)) leaves |= (uint64_t)*mp++ << (8 * CHILD(s2));
        r->xy = POS2_ADD(xy, L[0].xy[k3]);
        r->z = z + L[0].z[k3];
        r->leaves = leaves;
    }
    mc->p = mp;
    draw_runs2(c, runs, r);
}
#endif

/* The children of a level d-3 node wholly on screen: one pixel or squares a leaf. */
static inline void draw_level3(ctx *c, unsigned l3, unsigned m, const uint8_t *masks2, mc_pos2 xy, mc_pos z)
{
#if FLAT_SQUARES
    if (c->splat == 2 && !c->perspective) {
        draw_squares2(c, l3, m, masks2, xy, z);
        return;
    }
#endif
    if (c->splat > 1) draw_inside_squares(c, l3, m, masks2, xy, z);
    else draw_inside(c, l3, m, masks2, xy, z);
}

/* A node at level d-2 (or the root when d < 2) whose mask m is already read, drawn point by point
 * with checks: it may reach off screen, or the projection is perspective. */
static void draw_checked(ctx *c, unsigned l, unsigned m, mc_pos x, mc_pos y, mc_pos z)
{
    const mc_pos2 *v = c->v[l].xy;
    const mc_pos *vz = c->v[l].z;
    if (l + 1 == c->d) {                                 /* only when d = 1: the root's leaves */
        leaves(c, m, x, y, z, mc_cursor_take(&c->color, mc_popcount8(m)));
        return;
    }
    const uint8_t *masks = mc_cursor_take(&c->mask[l + 1], mc_popcount8(m));
    if (c->color.p >= c->color.end) mc_cursor_refill(&c->color);
    for (; m; m &= m - 1) {
        unsigned k = mc_ctz(m);
        unsigned cm = *masks++;
        const uint8_t *col = c->color.p;
        c->color.p += mc_popcount8(cm);
        const mc_pos2 p = POS2_ADD(POS2(x, y), v[k]);
        leaves(c, cm, POS2_X(p), POS2_Y(p), z + vz[k], col);
    }
}

/* Whether the node at c->cone_level (= d - 3) being entered is skipped as back-facing (octree.h's
 * test, a . w < -s, with w rounded to Q14: the product is off by at most half the axis's l1 norm,
 * and in perspective the cone widened by the eye's spread: sin(theta + alpha) <= sin theta + sin
 * alpha, and |a| <= its l1 norm). Steps over its subtree when it is (its own mask, its children's,
 * the record's n2 masks and n3 colours); else over its record. */
static inline int culled(ctx *c, unsigned l)
{
    if (c->cone.p >= c->cone.end) mc_cursor_refill(&c->cone);
    const uint8_t *k = c->cone.p;
    /* int8 fields, sign-extended without implementation-defined conversions */
    const int32_t ax = (int32_t)k[0] - ((k[0] & 0x80) << 1), ay = (int32_t)k[1] - ((k[1] & 0x80) << 1);
    const int32_t az = (int32_t)k[2] - ((k[2] & 0x80) << 1);
    const int32_t dot = ax * c->cone_w[0] + ay * c->cone_w[1] + az * c->cone_w[2];   /* |dot| < 2^23 */
    const int32_t l1 = (ax < 0 ? -ax : ax) + (ay < 0 ? -ay : ay) + (az < 0 ? -az : az);
    c->cone.p += CONE_BYTES;
    if (dot >= -((int32_t)k[3] * 16384 + l1 * c->cone_spread + l1)) return 0;
    const unsigned m = *mc_cursor_take(&c->mask[l], 1);
    mc_cursor_skip(&c->mask[l + 1], mc_popcount8(m));
    mc_cursor_skip(&c->mask[l + 2], k[4]);
    mc_cursor_skip(&c->color, (uint32_t)k[5] | (uint32_t)k[6] << 8);
    c->culled++;
    return 1;
}

/* Polls the abort callback; non-zero when the frame is to be given up. */
static int poll_abort(ctx *c)
{
    c->polls++;
    if (c->abort(c->user)) c->aborted = 1;
    return c->aborted;
}

/* On entering a node at level l: polls the abort callback at c->poll_level and tests the cone at
 * c->cone_level. Non-zero when the node is not to be drawn: the frame was given up, or the node
 * was culled (its subtree stepped over). */
MC_ALWAYS_INLINE int passed_over(ctx *c, unsigned l)
{
    if (l == c->poll_level && c->abort && poll_abort(c)) return 1;
    return l == c->cone_level && culled(c, l);
}

/* A node at level l = d-3 of an orthographic subtree wholly on screen: its grandchildren's leaves
 * in one loop (draw_level3). Inlined into visit_inside's loop, so a node there costs no call of
 * its own. */
MC_ALWAYS_INLINE void inside_level3(ctx *c, unsigned l, mc_pos2 xy, mc_pos z)
{
    if (passed_over(c, l)) return;
    const unsigned m = *mc_cursor_take(&c->mask[l], 1);
    draw_level3(c, l, m, mc_cursor_take(&c->mask[l + 1], mc_popcount8(m)), xy, z);
}

/* A node at level l <= d-3 of an orthographic subtree wholly on screen: no checks at all, packed
 * positions. Its level d-3 nodes draw their grandchildren's leaves in one loop (draw_inside). */
static void visit_inside(ctx *c, unsigned l, mc_pos2 xy, mc_pos z)
{
    if (l + 3 == c->d) {
        inside_level3(c, l, xy, z);
        return;
    }
    if (passed_over(c, l)) return;
    unsigned m = *mc_cursor_take(&c->mask[l], 1);
    const mc_pos2 *v = c->v[l].xy;
    const mc_pos *vz = c->v[l].z;
    if (l + 4 == c->d) {
        for (child_iter s = CHILDREN(m); s; s = NEXT_CHILD(s)) {
            const intptr_t k = CHILD(s);
            inside_level3(c, l + 1, POS2_ADD(xy, v[k]), z + vz[k]);
            if (c->aborted) return;
        }
        return;
    }
    for (child_iter s = CHILDREN(m); s; s = NEXT_CHILD(s)) {
        const intptr_t k = CHILD(s);
        visit_inside(c, l + 1, POS2_ADD(xy, v[k]), z + vz[k]);
        if (c->aborted) return;
    }
}

/* Visits one node at level l < d whose centre is at (x, y, z) and which may reach off screen (or,
 * in perspective, any node above level d-3, whose children are not classified: persp_node projects
 * level d-3). Children wholly off screen are stepped over, children wholly on screen
 * go to visit_inside / draw_inside, the rest are visited here. The last levels are drawn without
 * further calls (the paper's Algorithm 2, taken two levels further).
 * The abort callback is polled on entering a node at level MC_ABORT_LEVEL, or at level d-3 when
 * that is shallower (small depths), below which the walk makes no calls. */
static void visit(ctx *c, unsigned l, mc_pos x, mc_pos y, mc_pos z);
static void persp_node(ctx *c, unsigned l, mc_pos x, mc_pos y, mc_pos z);

/* The centre of child k of a level-l node centred at (x, y, z). */
MC_ALWAYS_INLINE void child_centre(const ctx *c, unsigned l, unsigned k, mc_pos x, mc_pos y, mc_pos z, mc_pos *cx,
                                   mc_pos *cy, mc_pos *cz)
{
    const mc_pos2 p = POS2_ADD(POS2(x, y), c->v[l].xy[k]);
    *cx = POS2_X(p);
    *cy = POS2_Y(p);
    *cz = z + c->v[l].z[k];
}

/* The children (mask m, already read) of a node at level l = d-3 centred at (x, y, z), on an
 * orthographic walk or a linear frame: each skipped, drawn unchecked or drawn with checks. It calls
 * no walk function, so the walk recurses only through visit (visit_children is inlined into it) and
 * visit_inside, once a level, as the firmware's static stack bound expects (front/fw/stack_bound.py). */
static void frame_children(ctx *c, unsigned l, unsigned m, mc_pos x, mc_pos y, mc_pos z)
{
    for (; m; m &= m - 1) {
        const unsigned k = mc_ctz(m);
        mc_pos cx, cy, cz;
        child_centre(c, l, k, x, y, z, &cx, &cy, &cz);
        int where = classify(c, cx, cy, l + 1);
        if (where < 0) {
            skip_subtree(c, l + 1);
        } else {
            const uint8_t *cm = mc_cursor_take(&c->mask[l + 1], 1);
            if (where > 0) draw_level3(c, l, 1u << k, cm, POS2(x, y), z);
            else draw_checked(c, l + 1, *cm, cx, cy, cz);
        }
        if (c->aborted) return;
    }
}

/* The children (mask m, already read) of a node at level l <= d-3 centred at (x, y, z); see visit.
 * Inlined into visit, so that the walk's recursion is one function a level. */
MC_ALWAYS_INLINE void visit_children(ctx *c, unsigned l, unsigned m, mc_pos x, mc_pos y, mc_pos z)
{
    if (l + 3 == c->d) {                                  /* the children are at level d-2 */
        frame_children(c, l, m, x, y, z);
        return;
    }
    for (; m; m &= m - 1) {
        const unsigned k = mc_ctz(m);
        mc_pos cx, cy, cz;
        child_centre(c, l, k, x, y, z, &cx, &cy, &cz);
        if (c->perspective) {                            /* above the linear frames: nothing projected */
            if (l + 4 == c->d) persp_node(c, l + 1, cx, cy, cz);
            else visit(c, l + 1, cx, cy, cz);
            if (c->aborted) return;
            continue;
        }
        int where = classify(c, cx, cy, l + 1);
        if (where < 0) skip_subtree(c, l + 1);
        else if (where > 0) visit_inside(c, l + 1, POS2(cx, cy), cz);
        else visit(c, l + 1, cx, cy, cz);
        if (c->aborted) return;
    }
}

static void visit(ctx *c, unsigned l, mc_pos x, mc_pos y, mc_pos z)
{
    if (passed_over(c, l)) return;
    unsigned m = *mc_cursor_take(&c->mask[l], 1);
    if (l + 2 >= c->d) {                                 /* d <= 2: the root draws everything */
        draw_checked(c, l, m, x, y, z);
        return;
    }
    visit_children(c, l, m, x, y, z);
}

/* Perspective (d >= 3): sets up the first-order projection about the centre (x, y, z) of a node at
 * level l0 = d-3 or d-2 (exact coordinates: x, y from the view axis, z with the +radius offset, Q F)
 * when pos_linear_ok bounds its error for every leaf below by MC_LINEAR_ERROR / 256 pixel: the
 * vectors of levels l0..d-1 in c->v (z in depth-buffer units, set once a frame), their reaches,
 * the node's footprint and whether it may go the unchecked way. The node is then drawn as an
 * orthographic one centred at (*sx, *sy, *sz). Returns 0 where the bound fails, the node reaches
 * the near plane, or its numbers would leave the coordinate range. */
static int linear_frame(ctx *c, unsigned l0, mc_pos x, mc_pos y, mc_pos z, mc_pos *sx, mc_pos *sy, mc_pos *sz)
{
    const unsigned b = c->d - 3;
    const mc_pos r = c->ball[l0 - b];
    const mc_pos_wide dist = c->eye + z - c->radius;
    if (MC_LINEAR_ERROR == 0 || dist - r < c->near) return 0;
    const mc_pos_mag q = pos_magnification(c->eye, dist);
    mc_pos_mag gx, gy;
    if (!pos_linear_setup(x, y, q, dist, &gx, &gy)) return 0;
    const mc_pos_wide ox = pos_project(x, q), oy = pos_project(y, q);
    const mc_pos_wide lim = POS_PIXELS(MC_COORD_LIMIT / 4);
    if (ox <= -lim || ox >= lim || oy <= -lim || oy >= lim) return 0;
    const mc_pos_wide aox = ox < 0 ? -ox : ox, aoy = oy < 0 ? -oy : oy;
    if (!pos_linear_ok(r, aox > aoy ? aox : aoy, c->eye, dist, MC_LINEAR_ERROR)) return 0;
    /* level l0's vectors are +-A +-B +-C, the images of the model axes' steps (c->basis), so the
     * largest |x| is |Ax| + |Bx| + |Cx|; each level below halves them exactly (pos_linear_step) */
    mc_pos(*const bs)[3] = c->basis[l0 - b];
    const mc_pos ax = pos_linear_step(bs[0][0], bs[0][2], q, gx), bx = pos_linear_step(bs[1][0], bs[1][2], q, gx);
    const mc_pos cx = pos_linear_step(bs[2][0], bs[2][2], q, gx), ay = pos_linear_step(bs[0][1], bs[0][2], q, gy);
    const mc_pos by = pos_linear_step(bs[1][1], bs[1][2], q, gy), cy = pos_linear_step(bs[2][1], bs[2][2], q, gy);
    const mc_pos2 a2 = POS2(2 * ax, 2 * ay), b2 = POS2(2 * bx, 2 * by), c2 = POS2(2 * cx, 2 * cy);
    mc_pos2 t[8];
    t[0] = POS2(-ax - bx - cx, -ay - by - cy);
    t[1] = POS2_ADD(t[0], a2);
    t[2] = POS2_ADD(t[0], b2);
    t[3] = POS2_ADD(t[1], b2);
    t[4] = POS2_ADD(t[0], c2);
    t[5] = POS2_ADD(t[1], c2);
    t[6] = POS2_ADD(t[2], c2);
    t[7] = POS2_ADD(t[3], c2);
    mc_pos mx = (ax < 0 ? -ax : ax) + (bx < 0 ? -bx : bx) + (cx < 0 ? -cx : cx);
    mc_pos my = (ay < 0 ? -ay : ay) + (by < 0 ? -by : by) + (cy < 0 ? -cy : cy);
    mc_pos rx = c->reach_x[c->d], ry = c->reach_y[c->d];
    for (unsigned l = c->d; l-- > l0;) {                 /* level l0 + h: halved h times */
        const unsigned h = l - l0;
        mc_pos2 *xy = c->v[l].xy;
        if (h == 0) for (int k = 0; k < 8; k++) xy[k] = t[k];
        else if (h == 1) for (int k = 0; k < 8; k++) xy[k] = POS2_HALF(t[k]);
        else for (int k = 0; k < 8; k++) xy[k] = POS2_HALF(POS2_HALF(t[k]));
        c->reach_x[l] = rx = rx + (h == 0 ? mx : h == 1 ? mx / 2 : mx / 4);
        c->reach_y[l] = ry = ry + (h == 0 ? my : h == 1 ? my / 2 : my / 4);
    }
    if (rx >= lim || ry >= lim) return 0;
    c->reach_x[b] = c->reach_x[l0];                      /* a level d-2 frame: spare_pixel's reach */
    c->reach_y[b] = c->reach_y[l0];
    const int32_t s = c->leaf_side ? pos_footprint(pos_project((mc_pos)c->leaf_side, q)) : 1;
    c->splat = s;
    c->inside = s == 1 || !MC_TEST_CLIPPED_SQUARES;
#if MC_DEPTH_SELECT
    if (2 * ((mc_pos_wide)rx + POS_PIXELS(1)) >= (mc_pos_wide)c->wf &&
        2 * ((mc_pos_wide)ry + POS_PIXELS(1)) >= (mc_pos_wide)c->hf) c->inside = 0;   /* see setup_vectors */
#endif
    *sx = c->cx + (mc_pos)ox;
    *sy = c->cy + (mc_pos)oy;
    *sz = pos_depth_units(z, c->zshift) + FRAME_DEPTH_ROOM;
    return 1;
}

/* Perspective: a level d-2 node no linear frame holds, projected leaf by leaf (c->pv). */
static void exact_level2(ctx *c, mc_pos x, mc_pos y, mc_pos z)
{
    const unsigned l = c->d - 2;
    unsigned m = *mc_cursor_take(&c->mask[l], 1);
    const uint8_t *masks = mc_cursor_take(&c->mask[l + 1], mc_popcount8(m));
    if (c->color.p >= c->color.end) mc_cursor_refill(&c->color);
    const exactvec *p = &c->pv[1];
    for (; m; m &= m - 1) {
        unsigned k = mc_ctz(m);
        unsigned cm = *masks++;
        const uint8_t *col = c->color.p;
        c->color.p += mc_popcount8(cm);
        leaves_perspective(c, &c->pv[2], cm, x + p->x[k], y + p->y[k], z + p->z[k], col);
    }
}

/* Perspective: a node at level d-3 (exact coordinates, as linear_frame's). Drawn through one linear
 * frame where the bound holds, else each child through its own frame, else leaf by leaf. */
static void persp_node(ctx *c, unsigned l, mc_pos x, mc_pos y, mc_pos z)
{
    if (passed_over(c, l)) return;                       /* before the frame: no frame for it */
    mc_pos sx, sy, sz;
    if (linear_frame(c, l, x, y, z, &sx, &sy, &sz)) {
        int where = classify(c, sx, sy, l);
        if (where < 0) {                                 /* its cone record is read: only the rest */
            const unsigned cones = c->cone_level;
            c->cone_level = NO_CONES;
            skip_subtree(c, l);
            c->cone_level = cones;
            return;
        }
        unsigned m = *mc_cursor_take(&c->mask[l], 1);
        if (where > 0) draw_level3(c, l, m, mc_cursor_take(&c->mask[l + 1], mc_popcount8(m)), POS2(sx, sy), sz);
        else frame_children(c, l, m, sx, sy, sz);
        return;
    }
    unsigned m = *mc_cursor_take(&c->mask[l], 1);
    const exactvec *p = &c->pv[0];
    for (; m; m &= m - 1) {
        unsigned k = mc_ctz(m);
        mc_pos cx = x + p->x[k], cy = y + p->y[k], cz = z + p->z[k];
        if (linear_frame(c, l + 1, cx, cy, cz, &sx, &sy, &sz)) {
            /* the child as the only child of a node at its own centre: a zero vector k at level l */
            c->v[l].xy[k] = POS2(0, 0);
            frame_children(c, l, 1u << k, sx, sy, sz - c->v[l].z[k]);
        } else {
            exact_level2(c, cx, cy, cz);
        }
        if (c->aborted) return;
    }
}

/* Builds the per-level displacement vectors. Each is rounded once from the exact product of the
 * Q30 rotation and the Q16 scale, so a leaf's position is off by at most (d + 1) / 2 units of Q F
 * per axis: the root's rounding plus one per level. Returns the root's orthographic depth in
 * depth-buffer units. */
static int32_t setup_vectors(ctx *c, const mc_view *v, mc_splat splat)
{
    int32_t r[3][3];
    mc_view_rotation(v, r);
    /* towards the viewer in model axes, for the cones (setup_cones): the third row, Q30 -> Q14 */
    for (int j = 0; j < 3; j++) c->cone_w[j] = (int32_t)mc_round_shift(r[2][j], 16);
    uint32_t side = (uint32_t)(c->w < c->h ? c->w : c->h);
    int64_t scale = (int64_t)v->zoom * side;       /* pixels per cube side, Q16 */
    const int32_t radius = (int32_t)mc_mul_shift64(scale, HALF_SQRT3_Q30, 30 + 16 - F) + 2 * MC_MAX_DEPTH;
    c->zshift = 0;
    while (((uint32_t)(2 * radius) >> c->zshift) >= MC_DEPTH_SPAN) c->zshift++;
    c->radius = (mc_pos)pos_units(radius, 1, F - POS_FRAC);
    /* orthographic depth vectors are in depth-buffer units (the shift folded in, one rounding per
     * level); perspective keeps positions, since it divides by the distance */
    mc_pos mx[MC_MAX_DEPTH], my[MC_MAX_DEPTH];           /* the largest |x|, |y| of each level */
    for (unsigned l = 0; l < c->d; l++) {
        mx[l] = my[l] = 0;
        for (int k = 0; k < 8; k++) {
            int64_t sx = k & 1 ? 1 : -1, sy = k & 2 ? 1 : -1, sz = k & 4 ? 1 : -1;
            /* child k's centre is +-1/4 of the node's side 2^-l from its parent's: 2^-(l+2) */
            int64_t ex = sx * r[0][0] + sy * r[0][1] + sz * r[0][2];
            int64_t ey = sx * r[1][0] + sy * r[1][1] + sz * r[1][2];
            int64_t ez = sx * r[2][0] + sy * r[2][1] + sz * r[2][2];
            levelvec *v = &c->v[l];
            const int sh = 30 + 16 + (int)l + 2;          /* Q30 rotation * Q16 scale * 2^-(l+2) */
            const mc_pos x = (mc_pos)pos_units(ex, scale, sh - POS_FRAC);
            const mc_pos y = (mc_pos)-pos_units(ey, scale, sh - POS_FRAC);
            v->z[k] = (mc_pos)-pos_units(ez, scale, sh - F + (int)c->zshift);
            v->xy[k] = POS2(x, y);
            const mc_pos ax = x < 0 ? -x : x, ay = y < 0 ? -y : y;
            mx[l] = ax > mx[l] ? ax : mx[l];
            my[l] = ay > my[l] ? ay : my[l];
            /* perspective: Q F depths above the linear frames, and the last levels' exact vectors */
            const mc_pos zq = (mc_pos)-pos_units(ez, scale, sh - POS_FRAC);
            if (c->perspective && (l + 3 < c->d || c->d < 3)) v->z[k] = zq;
            if (c->perspective && l + 3 >= c->d) {
                exactvec *p = &c->pv[l + 3 - c->d];
                p->x[k] = x;
                p->y[k] = y;
                p->z[k] = zq;
            }
        }
    }
    c->reach_x[c->d] = c->reach_y[c->d] = 0;
    for (unsigned l = c->d; l-- > 0;) {
        c->reach_x[l] = c->reach_x[l + 1] + mx[l];
        c->reach_y[l] = c->reach_y[l + 1] + my[l];
    }
    for (unsigned l = 0; l <= c->d; l++) {     /* nothing to add unless sums round (pos.h) */
        c->reach_x[l] += POS_REACH_SLACK;
        c->reach_y[l] += POS_REACH_SLACK;
    }
    /* perspective, linear frames: the model axes' steps at levels d-3 and d-2 (a child's vector is
     * their sum with signs, setup_vectors' sx, sy, sz), and a level l node's leaves lie within sqrt(3)/2 (S 2^-l - S 2^-d) of
     * its centre, plus the rounding of the d - l vectors that reach them */
    for (unsigned i = 0; i < 2 && c->d >= 3; i++) {
        const unsigned l = c->d - 3 + i;
        for (int j = 0; j < 3; j++)
            for (int a = 0; a < 3; a++)
                c->basis[i][j][a] = (mc_pos)(a ? -1 : 1) * (mc_pos)pos_units(r[a][j], scale, 30 + 16 + (int)l + 2 - POS_FRAC);
        c->ball[i] = (mc_pos)(pos_units((int64_t)HALF_SQRT3_Q16 * ((1 << (c->d - l)) - 1), scale, 32 + (int)c->d - POS_FRAC) +
                              pos_units(c->d + 2, 1, F - POS_FRAC));
    }
    c->eye = pos_units(v->eye, scale, 32 - POS_FRAC);              /* Q16 sides * Q16 px */
    c->near = pos_units(scale, 1, 16 + 6 - POS_FRAC);               /* 1/64 cube side */
    if (c->near < POS_EPSILON) c->near = POS_EPSILON;                /* tiny views: never divide by 0 */
    /* footprints, chosen once per frame: a leaf's side on screen is scale / 2^d pixels */
    c->splat = 1;
    c->leaf_side = 0;
    if (splat == MC_SPLAT_ZOOM || (splat == MC_SPLAT_DEFAULT && MC_SPLAT_DEFAULT_MODE == MC_SPLAT_ZOOM)) {
        const mc_pos_wide leaf = pos_units(scale, 1, 16 + (int)c->d - POS_FRAC);
        if (c->perspective) c->leaf_side = leaf;
        else c->splat = pos_footprint(leaf);
    }
    /* wholly on screen: a node's leaves, and with footprints their squares (classify) */
    c->inside = !c->perspective && (c->splat == 1 || !MC_TEST_CLIPPED_SQUARES);
#if FLAT_SQUARES
    if (c->splat == 2 && !c->perspective && c->d >= 3) {   /* draw_squares2 draws level d-3 nodes */
        const levelvec *const v2 = &c->v[c->d - 2], *const v1 = &c->v[c->d - 1];
        for (int j = 0; j < 64; j++) {
            c->leaves2.xy[j] = POS2_ADD(v2->xy[j >> 3], v1->xy[j & 7]);
            c->leaves2.z[j] = v2->z[j >> 3] + v1->z[j & 7];
        }
    }
#endif
#if MC_DEPTH_SELECT
    /* draw_inside needs a pixel outside the reach of each level d-3 node (spare_pixel): on targets
     * so small that a node's reach spans both their width and height, every node is checked */
    if (c->d >= 3) {
        const unsigned l = c->d - 3;
        const mc_pos_wide one = POS_PIXELS(1);
        if (2 * ((mc_pos_wide)c->reach_x[l] + one) >= (mc_pos_wide)POS_PIXELS(c->w) &&
            2 * ((mc_pos_wide)c->reach_y[l] + one) >= (mc_pos_wide)POS_PIXELS(c->h)) c->inside = 0;
    }
#endif
    return (radius >> c->zshift) + MC_MAX_DEPTH;   /* one depth unit of room per level's rounding */
}

/* Culling (octree_render.h, mc_cull): the cones of level d-3; the direction towards the viewer,
 * the rotation's third row (screen z points at the viewer), is setup_vectors'. */
static void setup_cones(ctx *c, const mc_octree *o, const mc_view *v, mc_cull cull)
{
    c->cone_level = NO_CONES;
    c->culled = 0;
    if (cull == MC_CULL_OFF || c->d < 4 || !o->levels[c->d - 3].cones) return;
    c->cone_spread = 0;
    if (c->perspective) {
        if (v->eye <= HALF_SQRT3_Q16) return;   /* the eye inside the sphere: any direction */
        c->cone_spread = (int32_t)(((int64_t)HALF_SQRT3_Q16 << 14) / v->eye) + 1;
    }
    mc_cursor_init(&c->cone, o->levels[c->d - 3].cones);
    c->cone_level = c->d - 3;
}

unsigned mc_octree_lod_depth(const mc_view *view, uint32_t w, uint32_t h, unsigned depth, uint16_t max_error)
{
    if (!max_error || depth <= 1) return depth;
    const mc_view v = mc_view_clamp(view, w, h);
    /* node side at level l, pixels: S / 2^l (times eye / dn in perspective); S = zoom * side in Q16.
     * Wanted: S mag / 2^(16 + l) <= max_error / 16, i.e. 16 S eye <= max_error dn 2^(16 + l) */
    const uint64_t side = w < h ? w : h;
    const uint64_t s = (uint64_t)v.zoom * side;                    /* <= 2^30: clamped extent */
    uint64_t lhs = 16 * s, rhs = (uint64_t)max_error << 17;        /* l = 1 */
    if (v.projection == MC_PERSPECTIVE) {
        const int64_t dn = (int64_t)v.eye - HALF_SQRT3_Q16;           /* nearest sphere point, Q16 sides */
        if (dn < MC_ZOOM_ONE / 64) return depth;
        lhs *= (uint64_t)v.eye;                                    /* < 2^58; rhs stays < 2^63 */
        rhs *= (uint64_t)dn;
    }
    unsigned l = 1;
    while (l < depth && lhs > rhs) l++, rhs <<= 1;
    return l;
}

int mc_octree_render(const mc_octree *octree, const mc_view *view, unsigned depth, const mc_octree_options *opt,
                     const mc_target *t, mc_abort_fn abort, void *user, mc_stats *stats)
{
    if (!octree || !view || !t || !t->color || !t->depth) return MC_ERR_ARG;
    if (depth < 1 || depth > octree->depth || depth > MC_MAX_DEPTH) return MC_ERR_DEPTH;
    if (t->width == 0 || t->height == 0 || t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX)
        return MC_ERR_SIZE;

    ctx c;
    mc_view v = mc_view_clamp(view, t->width, t->height);
    if (opt) depth = mc_octree_lod_depth(&v, t->width, t->height, depth, opt->max_error);
    mc_splat splat = opt ? opt->splat : MC_SPLAT_DEFAULT;
    if (splat != MC_SPLAT_PIXEL && splat != MC_SPLAT_ZOOM) splat = MC_SPLAT_DEFAULT;
    c.fb = t->color;
    c.zb = t->depth;
    c.w = t->width;
    c.h = t->height;
    c.wf = POS_PIXELS(c.w);
    c.hf = POS_PIXELS(c.h);
    c.d = depth;
    c.perspective = v.projection == MC_PERSPECTIVE;
    c.abort = abort;
    c.user = user;
    c.points = c.polls = 0;
    c.aborted = 0;
    for (unsigned l = 0; l < depth; l++) mc_cursor_init(&c.mask[l], octree->levels[l].masks);
    /* a monochrome octree stores no colours (octree.h): every leaf reads palette index 0 */
    if (octree->levels[depth].colors) mc_cursor_init(&c.color, octree->levels[depth].colors);
    else mc_cursor_init_zeros(&c.color);
    const int32_t zroot = setup_vectors(&c, &v, splat);
    setup_cones(&c, octree, &v, opt ? opt->cull : MC_CULL_DEFAULT);
    c.poll_level = depth >= MC_ABORT_LEVEL + 3 ? MC_ABORT_LEVEL : depth >= 3 ? depth - 3 : 0;

    /* the root's centre: the screen centre plus translation (orthographic), or the view axis
     * (perspective: projected per point); depth offset by the bounding radius to keep it positive */
    const mc_pos centre_x = pos_centre(c.w, v.tx), centre_y = pos_centre(c.h, v.ty);
    if (c.perspective) {
        c.cx = centre_x;
        c.cy = centre_y;
        if (depth == 3) persp_node(&c, 0, 0, 0, c.radius);
        else visit(&c, 0, 0, 0, c.radius);
    } else {
        int where = classify(&c, centre_x, centre_y, 0);
        mc_pos z = (mc_pos)zroot;
        if (where > 0 && depth >= 3) visit_inside(&c, 0, POS2(centre_x, centre_y), z);
        else if (where >= 0) visit(&c, 0, centre_x, centre_y, z);
    }
    if (stats) {
        stats->points = c.points;
        stats->polls = c.polls;
        stats->aborted = c.aborted;
        stats->depth = depth;
        stats->culled = c.culled;
    }
    return MC_OK;
}
