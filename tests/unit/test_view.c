/* View clamping, mc_octree_render's argument checks and contract on hand-made and random scenes, and the
 * one-pixel hole filler (modelc/xform.h, octree_render.h, finish.h).
 *
 * Long because the scene builder, the guard-cell targets and the plot hook are shared by every check
 * of the renderer's contract; split up, each part would carry its own copy of them.
 *
 * The runtime is compiled into this test with MC_PLOT_HOOK pointing at mc_test_plot_hook (see
 * tests/unit/suite.sh), so every point the renderer reports as on screen is checked to really lie on
 * the target before it is written. Targets are surrounded by guard cells that must survive every
 * render and every hole-filling pass. Scenes are built here, every chunk in its own exactly sized
 * heap block, so the sanitizer run catches a read past a chunk.
 */
#define _GNU_SOURCE
#include <inttypes.h>
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <modelc/modelc.h>

#define F MC_FRAC_BITS
/* side of the hand-made targets: 64 pixels, or less where MC_FRAC_BITS makes MC_TARGET_MAX smaller */
#define S (MC_TARGET_MAX < 64 ? MC_TARGET_MAX : 64)

static uint64_t rng_state = 0x5eed;
static uint64_t rng64(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15u);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    return z ^ (z >> 31);
}
static uint32_t rnd(uint32_t n) { return (uint32_t)(rng64() % n); }

/* ---- the plot hook ------------------------------------------------------------------------- */

void mc_test_plot_hook(int32_t fx, int32_t fy, const uint8_t *color);
static struct {
    int32_t w, h;
    uint32_t calls, off;
    int32_t off_fx, off_fy;
} hook;

void mc_test_plot_hook(int32_t fx, int32_t fy, const uint8_t *color)
{
    (void)color;
    hook.calls++;
    int32_t px = fx >> F, py = fy >> F;
    if (px < 0 || py < 0 || px >= hook.w || py >= hook.h) {
        if (!hook.off) { hook.off_fx = fx; hook.off_fy = fy; }
        hook.off++;
    }
}

/* ---- targets with guard cells -------------------------------------------------------------- */

#define GUARD 512
#define GUARD_COLOR 0xA5
#define GUARD_DEPTH 0x5A5A

typedef struct gtarget {
    mc_target t;
    uint8_t *color_block;
    uint16_t *depth_block;
    size_t n;
} gtarget;

static void gt_init(gtarget *g, unsigned w, unsigned h)
{
    g->n = (size_t)w * h;
    g->color_block = malloc(g->n + 2 * GUARD);
    g->depth_block = malloc((g->n + 2 * GUARD) * sizeof(uint16_t));
    assert_non_null(g->color_block);
    assert_non_null(g->depth_block);
    memset(g->color_block, GUARD_COLOR, g->n + 2 * GUARD);
    for (size_t i = 0; i < g->n + 2 * GUARD; i++) g->depth_block[i] = GUARD_DEPTH;
    g->t.color = g->color_block + GUARD;
    g->t.depth = g->depth_block + GUARD;
    g->t.width = (uint16_t)w;
    g->t.height = (uint16_t)h;
    hook.w = (int32_t)w;
    hook.h = (int32_t)h;
}

static int gt_guards_ok(const gtarget *g)
{
    for (size_t i = 0; i < GUARD; i++) {
        if (g->color_block[i] != GUARD_COLOR || g->color_block[GUARD + g->n + i] != GUARD_COLOR) return 0;
        if (g->depth_block[i] != GUARD_DEPTH || g->depth_block[GUARD + g->n + i] != GUARD_DEPTH) return 0;
    }
    return 1;
}

static void gt_free(gtarget *g)
{
    free(g->color_block);
    free(g->depth_block);
}

/* ---- scenes -------------------------------------------------------------------------------- */

#define MAXD 12

typedef struct tree {
    unsigned depth;
    uint32_t nodes[MAXD + 1];
    uint8_t *mask[MAXD + 1], *color[MAXD + 1];
    uint32_t *parent[MAXD + 1];              /* index of each node's parent in the level above */
    mc_chunk *mchunks[MAXD + 1], *cchunks[MAXD + 1];
    mc_octree_level levels[MAXD + 1];
    uint8_t palette[256 * 3];
    mc_octree scene;
    uint8_t colors_at[MAXD + 1][32];         /* bit set of the palette indices used at each level */
} tree;

/* Splits a level's array into chunks, each in its own heap block of exactly its size. A chunk may end
 * only where the grandparent changes (between cousin groups), which is also a sibling-group boundary,
 * so the chunks are valid under octree.h's rules for masks and for colours. */
static mc_chunk *make_chunks(const uint8_t *data, uint32_t n, const tree *t, unsigned level, int split)
{
    mc_chunk *ch = calloc(n + 2, sizeof *ch);
    assert_non_null(ch);
    uint32_t nch = 0, start = 0;
    for (uint32_t i = 1; i <= n; i++) {
        int end = i == n;
        if (!end && split && level >= 2) {
            uint32_t g0 = t->parent[level - 1][t->parent[level][i - 1]];
            uint32_t g1 = t->parent[level - 1][t->parent[level][i]];
            end = g0 != g1 && rnd(3) == 0;
        }
        if (!end) continue;
        uint8_t *block = malloc(i - start);
        assert_non_null(block);
        memcpy(block, data + start, i - start);
        ch[nch].data = block;
        ch[nch].size = i - start;
        nch++;
        start = i;
    }
    ch[nch].data = NULL;
    ch[nch].size = 0;
    return ch;
}

static void free_chunks(mc_chunk *ch)
{
    if (!ch) return;
    for (mc_chunk *c = ch; c->data; c++) free((void *)c->data);
    free(ch);
}

/* Builds the scene from t->depth, t->mask (levels 0..depth-1) and t->color (levels 1..depth). */
static void tree_finish(tree *t, int split)
{
    t->parent[0] = calloc(1, sizeof(uint32_t));
    for (unsigned l = 0; l < t->depth; l++) {
        t->parent[l + 1] = calloc(t->nodes[l + 1] + 1, sizeof(uint32_t));
        uint32_t k = 0;
        for (uint32_t i = 0; i < t->nodes[l]; i++)
            for (int b = 0; b < 8; b++)
                if (t->mask[l][i] & (1u << b)) t->parent[l + 1][k++] = i;
        assert_int_equal(k, t->nodes[l + 1]);
    }
    memset(t->colors_at, 0, sizeof t->colors_at);
    for (unsigned l = 0; l <= t->depth; l++) {
        t->levels[l].nodes = t->nodes[l];
        t->mchunks[l] = l < t->depth ? make_chunks(t->mask[l], t->nodes[l], t, l, split) : NULL;
        t->cchunks[l] = l > 0 ? make_chunks(t->color[l], t->nodes[l], t, l, split) : NULL;
        t->levels[l].masks = t->mchunks[l];
        t->levels[l].colors = t->cchunks[l];
        t->levels[l].cones = NULL;   /* no normal cones: every leaf drawn */
        if (l > 0)
            for (uint32_t i = 0; i < t->nodes[l]; i++) t->colors_at[l][t->color[l][i] >> 3] |= 1u << (t->color[l][i] & 7);
    }
    for (int i = 0; i < 256 * 3; i++) t->palette[i] = (uint8_t)i;
    t->scene.depth = (uint8_t)t->depth;
    t->scene.palette_size = 256;
    t->scene.palette = t->palette;
    t->scene.levels = t->levels;
}

static void tree_free(tree *t)
{
    for (unsigned l = 0; l <= t->depth; l++) {
        free_chunks(t->mchunks[l]);
        free_chunks(t->cchunks[l]);
        free(t->mask[l]);
        free(t->color[l]);
        free(t->parent[l]);
    }
    memset(t, 0, sizeof *t);
}

/* A random octree of the given depth; density 0..2 from sparse (mostly one child) to dense, with the
 * width of each level capped so deep trees stay small. */
static void tree_random(tree *t, unsigned depth, int density, int split)
{
    memset(t, 0, sizeof *t);
    t->depth = depth;
    t->nodes[0] = 1;
    for (unsigned l = 0; l <= depth; l++) {
        t->mask[l] = l < depth ? malloc(t->nodes[l]) : NULL;
        t->color[l] = malloc(t->nodes[l]);
        uint32_t next = 0;
        for (uint32_t i = 0; i < t->nodes[l]; i++) {
            t->color[l][i] = (uint8_t)rnd(256);
            if (l == depth) continue;
            unsigned m;
            if (t->nodes[l] > 3000 || density == 0) m = 1u << rnd(8);
            else if (density == 1) m = (1u << rnd(8)) | (1u << rnd(8)) | (rnd(4) ? 0 : 1u << rnd(8));
            else m = (unsigned)rnd(255) + 1;
            t->mask[l][i] = (uint8_t)m;
            next += (uint32_t)__builtin_popcount(m);
        }
        if (l < depth) t->nodes[l + 1] = next;
    }
    tree_finish(t, split);
}

/* The hand-made depth-2 scene: the root has children 0 (-x -y -z) and 7 (+x +y +z); child 0 has its
 * own child 0, child 7 its child 7. Colours 1 and 2 at level 1, 3 and 4 at level 2, each leaf colour
 * in a chunk of its own. */
static void tree_tiny(tree *t)
{
    memset(t, 0, sizeof *t);
    t->depth = 2;
    t->nodes[0] = 1;
    t->nodes[1] = 2;
    t->nodes[2] = 2;
    static const uint8_t m0[] = {0x81}, m1[] = {0x01, 0x80}, c1[] = {1, 2}, c2[] = {3, 4};
    t->mask[0] = malloc(1);
    memcpy(t->mask[0], m0, 1);
    t->mask[1] = malloc(2);
    memcpy(t->mask[1], m1, 2);
    t->color[0] = calloc(1, 1);
    t->color[1] = malloc(2);
    memcpy(t->color[1], c1, 2);
    t->color[2] = malloc(2);
    memcpy(t->color[2], c2, 2);
    tree_finish(t, 0);
}

/* ---- mc_view_clamp ------------------------------------------------------------------------- */

static const int32_t extremes[] = {INT32_MIN, INT32_MIN + 1, -65536 * 64, -1, 0, 1, 1023, 1024, 1025,
                                   MC_ZOOM_MIN - 1, MC_ZOOM_MIN, MC_EYE_MIN, MC_ZOOM_ONE, 2 * MC_ZOOM_ONE,
                                   MC_COORD_LIMIT / 4 - 1, MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4 + 1,
                                   MC_ZOOM_MAX, MC_ZOOM_MAX + 1, MC_EYE_MAX, MC_EYE_MAX + 1,
                                   INT32_MAX - 1, INT32_MAX};
#define N_EXTREMES (sizeof extremes / sizeof extremes[0])

static int32_t clamp_ref(int64_t v, int64_t lo, int64_t hi) { return (int32_t)(v < lo ? lo : v > hi ? hi : v); }

static void check_clamp(const mc_view *in, uint32_t w, uint32_t h)
{
    mc_view out = mc_view_clamp(in, w, h);
    uint64_t side = w < h ? w : h;
    if (side == 0) side = 1;
    /* documented: zoom in [1/64, 64] and screen extent zoom * side <= MC_COORD_LIMIT / 2 pixels, and
     * never above 2^16 pixels (xform.h: a mesh vertex's projection below 2^62) */
    const int64_t ext = MC_COORD_LIMIT / 2 < 65536 ? MC_COORD_LIMIT / 2 : 65536;
    int64_t zhi = (int64_t)((uint64_t)ext * MC_ZOOM_ONE / side);
    if (zhi > MC_ZOOM_MAX) zhi = MC_ZOOM_MAX;
    int64_t zlo = MC_ZOOM_MIN < zhi ? MC_ZOOM_MIN : zhi;   /* a huge target leaves no room for 1/64 */
    if (zhi < 1) zhi = zlo = 1;
    if (out.zoom != clamp_ref(in->zoom, zlo, zhi))
        fail_msg("mc_view_clamp(zoom %" PRId32 ", %" PRIu32 "x%" PRIu32 "): zoom %" PRId32 ", want %" PRId32
                 " (the nearest zoom in [1/64, 64] with extent <= %d px)",
                 in->zoom, w, h, out.zoom, clamp_ref(in->zoom, zlo, zhi), (int)ext);
    /* (for sides above that extent * 65536 no positive Q16 zoom keeps the extent in bounds;
     * mc_octree_render refuses such targets anyway) */
    if (out.zoom < 1 ||
        (side <= (uint64_t)ext * MC_ZOOM_ONE && (uint64_t)out.zoom * side > (uint64_t)ext * MC_ZOOM_ONE))
        fail_msg("mc_view_clamp(zoom %" PRId32 ", %" PRIu32 "x%" PRIu32 "): extent %.3f px is not in"
                 " (0, %d]", in->zoom, w, h, (double)out.zoom * (double)side / 65536, (int)ext);
    if (out.tx != clamp_ref(in->tx, -MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4) ||
        out.ty != clamp_ref(in->ty, -MC_COORD_LIMIT / 4, MC_COORD_LIMIT / 4))
        fail_msg("mc_view_clamp(tx %" PRId32 ", ty %" PRId32 ") = (%" PRId32 ", %" PRId32 "), want each clamped"
                 " to +-MC_COORD_LIMIT/4 = %d", in->tx, in->ty, out.tx, out.ty, MC_COORD_LIMIT / 4);
    if (out.eye != clamp_ref(in->eye, MC_EYE_MIN, MC_EYE_MAX))
        fail_msg("mc_view_clamp(eye %" PRId32 ") = %" PRId32 ", want it clamped to [1/16, 256] sides", in->eye,
                 out.eye);
    if (out.yaw != in->yaw || out.pitch != in->pitch || out.roll != in->roll)
        fail_msg("mc_view_clamp changed the angles (%" PRId32 ",%" PRId32 ",%" PRId32 ") -> (%" PRId32
                 ",%" PRId32 ",%" PRId32 "): any angle is representable", in->yaw, in->pitch, in->roll, out.yaw,
                 out.pitch, out.roll);
    mc_projection want = in->projection == MC_PERSPECTIVE ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    if (out.projection != want)
        fail_msg("mc_view_clamp(projection %d) = %d: a valid projection must be kept, any other value mapped"
                 " to one the renderer knows", (int)in->projection, (int)out.projection);
    mc_view again = mc_view_clamp(&out, w, h);
    if (memcmp(&again, &out, sizeof out) != 0) fail_msg("mc_view_clamp is not idempotent for %" PRIu32 "x%" PRIu32, w, h);
}

static void test_clamp(void **state)
{
    (void)state;
    static const uint32_t sizes[] = {0, 1, 2, 3, 63, 64, 200, 255, 256, 257, 480, 640, 1000,
                                     MC_TARGET_MAX, MC_TARGET_MAX + 1, 8192, 65535, 65536, 1u << 20,
                                     (1u << 20) + 1, 1u << 30, UINT32_MAX};
    const size_t ns = sizeof sizes / sizeof sizes[0];
    for (size_t a = 0; a < ns; a++)
        for (size_t b = 0; b < ns; b++)
            for (size_t i = 0; i < N_EXTREMES; i++) {
                mc_view v = mc_view_default();
                v.zoom = extremes[i];
                v.tx = extremes[(i + 3) % N_EXTREMES];
                v.ty = extremes[(i + 7) % N_EXTREMES];
                v.eye = extremes[(i + 11) % N_EXTREMES];
                v.yaw = extremes[(i + 1) % N_EXTREMES];
                v.pitch = extremes[(i + 5) % N_EXTREMES];
                v.roll = extremes[(i + 9) % N_EXTREMES];
                v.projection = (mc_projection)(i % 4 == 3 ? 7 : (int)(i % 2));
                check_clamp(&v, sizes[a], sizes[b]);
            }
    /* every field through every extreme at the common screen sizes */
    for (size_t i = 0; i < N_EXTREMES; i++)
        for (size_t j = 0; j < N_EXTREMES; j++) {
            mc_view v = mc_view_default();
            v.zoom = extremes[i];
            v.tx = extremes[j];
            v.ty = extremes[N_EXTREMES - 1 - j];
            v.eye = extremes[j];
            check_clamp(&v, 320, 240);
            check_clamp(&v, S, S);
        }
    for (int n = 0; n < 1000000; n++) {
        mc_view v;
        v.yaw = (int32_t)(uint32_t)rng64();
        v.pitch = (int32_t)(uint32_t)rng64();
        v.roll = (int32_t)(uint32_t)rng64();
        v.zoom = (int32_t)(uint32_t)rng64() >> rnd(32);
        v.tx = (int32_t)(uint32_t)rng64() >> rnd(32);
        v.ty = (int32_t)(uint32_t)rng64() >> rnd(32);
        v.eye = (int32_t)(uint32_t)rng64() >> rnd(32);
        v.projection = (mc_projection)(int)rnd(3);
        check_clamp(&v, (uint32_t)rng64() >> rnd(32), (uint32_t)rng64() >> rnd(32));
    }
    /* representable values come back unchanged */
    mc_view d = mc_view_default();
    mc_view c = mc_view_clamp(&d, S, S);
    assert_memory_equal(&c, &d, sizeof d);
    if (MC_COORD_LIMIT / 2 >= 320) {   /* the viewer's default frame at the default MC_FRAC_BITS */
            c = mc_view_clamp(&d, 320, 240);
            assert_memory_equal(&c, &d, sizeof d);
    }
    d.zoom = MC_ZOOM_MIN;
    d.tx = -MC_COORD_LIMIT / 4;
    d.ty = MC_COORD_LIMIT / 4;
    d.eye = MC_EYE_MAX;
    d.projection = MC_PERSPECTIVE;
    c = mc_view_clamp(&d, S, S);
    assert_memory_equal(&c, &d, sizeof d);
}

/* ---- mc_octree_render: arguments ------------------------------------------------------------------ */

static void test_render_args(void **state)
{
    (void)state;
    tree t;
    tree_tiny(&t);
    gtarget g;
    gt_init(&g, S, S);
    mc_view v = mc_view_default();
    mc_stats st;
    mc_target bad;

    assert_int_equal(mc_octree_render(NULL, &v, 1, NULL, &g.t, NULL, NULL, &st), MC_ERR_ARG);
    assert_int_equal(mc_octree_render(&t.scene, NULL, 1, NULL, &g.t, NULL, NULL, &st), MC_ERR_ARG);
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, NULL, NULL, NULL, &st), MC_ERR_ARG);
    bad = g.t;
    bad.color = NULL;
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &bad, NULL, NULL, &st), MC_ERR_ARG);
    bad = g.t;
    bad.depth = NULL;
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &bad, NULL, NULL, &st), MC_ERR_ARG);
    /* NULL pointers are reported before a bad depth or size */
    bad.width = 0;
    assert_int_equal(mc_octree_render(&t.scene, &v, 0, NULL, &bad, NULL, NULL, &st), MC_ERR_ARG);

    assert_int_equal(mc_octree_render(&t.scene, &v, 0, NULL, &g.t, NULL, NULL, &st), MC_ERR_DEPTH);
    assert_int_equal(mc_octree_render(&t.scene, &v, 3, NULL, &g.t, NULL, NULL, &st), MC_ERR_DEPTH);
    assert_int_equal(mc_octree_render(&t.scene, &v, 1000, NULL, &g.t, NULL, NULL, &st), MC_ERR_DEPTH);
    assert_int_equal(mc_octree_render(&t.scene, &v, (unsigned)-1, NULL, &g.t, NULL, NULL, &st), MC_ERR_DEPTH);
    /* a scene deeper than the runtime can decode is refused at any depth beyond MC_MAX_DEPTH,
     * before its levels are read (this one has none) */
    mc_octree deep = t.scene;
    deep.depth = MC_MAX_DEPTH + 1;
    deep.levels = NULL;
    assert_int_equal(mc_octree_render(&deep, &v, MC_MAX_DEPTH + 1, NULL, &g.t, NULL, NULL, &st), MC_ERR_DEPTH);

    static uint8_t cbuf[MC_TARGET_MAX + 1];
    static uint16_t dbuf[MC_TARGET_MAX + 1];
    mc_target big = {cbuf, dbuf, 0, 1};
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &big, NULL, NULL, &st), MC_ERR_SIZE);
    big.width = 1;
    big.height = 0;
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &big, NULL, NULL, &st), MC_ERR_SIZE);
    big.width = MC_TARGET_MAX + 1;
    big.height = 1;
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &big, NULL, NULL, &st), MC_ERR_SIZE);
    big.width = 1;
    big.height = MC_TARGET_MAX + 1;
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &big, NULL, NULL, &st), MC_ERR_SIZE);
    big.width = 65535;
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &big, NULL, NULL, &st), MC_ERR_SIZE);
    /* a bad depth is reported before a bad size */
    assert_int_equal(mc_octree_render(&t.scene, &v, 0, NULL, &big, NULL, NULL, &st), MC_ERR_DEPTH);
    assert_true(gt_guards_ok(&g));
    /* the largest sides are fine */
    big.width = MC_TARGET_MAX;
    big.height = 1;
    hook.w = MC_TARGET_MAX;
    hook.h = 1;
    mc_clear(&big);
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &big, NULL, NULL, NULL), MC_OK);
    big.width = 1;
    big.height = MC_TARGET_MAX;
    hook.w = 1;
    hook.h = MC_TARGET_MAX;
    mc_clear(&big);
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &big, NULL, NULL, NULL), MC_OK);
    gt_free(&g);
    tree_free(&t);
}

/* ---- mc_octree_render: the hand-made scene -------------------------------------------------------- */

/* Lists the drawn pixels of g: returns how many, storing up to 8 as (x, y, colour, depth). */
static int drawn(const gtarget *g, int32_t out[][4])
{
    int n = 0;
    for (int32_t y = 0; y < g->t.height; y++)
        for (int32_t x = 0; x < g->t.width; x++) {
            size_t i = (size_t)y * g->t.width + x;
            if (g->t.depth[i] == MC_DEPTH_EMPTY) {
                if (g->t.color[i] != 0) fail_msg("pixel (%d,%d) is empty with colour %d", x, y, g->t.color[i]);
                continue;
            }
            if (n < 8) {
                out[n][0] = x;
                out[n][1] = y;
                out[n][2] = g->t.color[i];
                out[n][3] = g->t.depth[i];
            }
            n++;
        }
    return n;
}

static void test_render_tiny(void **state)
{
    (void)state;
    tree t;
    tree_tiny(&t);
    gtarget g;
    gt_init(&g, S, S);
    mc_view v = mc_view_default();
    mc_stats st;
    int32_t px[8][4];

    /* depth 2, frontal, zoom 1: the cube spans the S x S target; leaves at +-(1/4 + 1/8) of a side
     * from the centre, screen y pointing down: child 0 of child 0 at (S/8, 7S/8), child 7 of
     * child 7 at (7S/8, S/8), both exactly on pixel corners */
    mc_clear(&g.t);
    hook.calls = hook.off = 0;
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, &st), MC_OK);
    assert_int_equal(st.points, 2);
    assert_int_equal(hook.calls, 2);
    assert_int_equal(hook.off, 0);
    assert_int_equal(st.aborted, 0);
    assert_int_equal(drawn(&g, px), 2);
    assert_int_equal(px[0][0], 7 * S / 8);   /* row-major: the upper point first */
    assert_int_equal(px[0][1], S / 8);
    assert_int_equal(px[0][2], 4);
    assert_int_equal(px[1][0], S / 8);
    assert_int_equal(px[1][1], 7 * S / 8);
    assert_int_equal(px[1][2], 3);
    assert_true(px[0][3] < px[1][3]);        /* +z faces the viewer: the +++ leaf is nearer */
    assert_true(px[1][3] < (int32_t)MC_DEPTH_EMPTY - 1);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 0);

    /* depth 1 reads only level 1's colours: the two children at (S/4, 3S/4) and (3S/4, S/4) */
    mc_clear(&g.t);
    assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &g.t, NULL, NULL, &st), MC_OK);
    assert_int_equal(st.points, 2);
    assert_int_equal(drawn(&g, px), 2);
    assert_int_equal(px[0][0], 3 * S / 4);
    assert_int_equal(px[0][1], S / 4);
    assert_int_equal(px[0][2], 2);
    assert_int_equal(px[1][0], S / 4);
    assert_int_equal(px[1][1], 3 * S / 4);
    assert_int_equal(px[1][2], 1);

    /* half a turn of yaw: x and z flip; the +++ leaf is now at the back, on the left */
    v.yaw = 2048;
    mc_clear(&g.t);
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, &st), MC_OK);
    assert_int_equal(drawn(&g, px), 2);
    assert_int_equal(px[0][0], S / 8);
    assert_int_equal(px[0][1], S / 8);
    assert_int_equal(px[0][2], 4);
    assert_int_equal(px[1][0], 7 * S / 8);
    assert_int_equal(px[1][1], 7 * S / 8);
    assert_int_equal(px[1][2], 3);
    assert_true(px[1][3] < px[0][3]);

    /* rendering adds to what the target holds: a second render leaves the image the same */
    v = mc_view_default();
    mc_clear(&g.t);
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, NULL), MC_OK);
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, NULL), MC_OK);
    assert_int_equal(drawn(&g, px), 2);

    /* translated wholly off screen: MC_OK, nothing drawn, nothing counted */
    v.tx = S * 4;
    mc_clear(&g.t);
    hook.calls = 0;
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, &st), MC_OK);
    assert_int_equal(st.points, 0);
    assert_int_equal(hook.calls, 0);
    assert_int_equal(drawn(&g, px), 0);
    /* half off: only the left point stays */
    v.tx = S / 2;
    mc_clear(&g.t);
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, &st), MC_OK);
    assert_int_equal(st.points, 1);
    assert_int_equal(drawn(&g, px), 1);
    assert_int_equal(px[0][0], S / 8 + S / 2);
    assert_int_equal(px[0][2], 3);

    /* perspective, eye 2 sides away: still both points, the nearer one pushed outwards more */
    v = mc_view_default();
    v.projection = MC_PERSPECTIVE;
    mc_clear(&g.t);
    hook.calls = hook.off = 0;
    assert_int_equal(mc_octree_render(&t.scene, &v, 2, NULL, &g.t, NULL, NULL, &st), MC_OK);
    assert_int_equal(st.points, 2);
    assert_int_equal(hook.off, 0);
    assert_int_equal(drawn(&g, px), 2);
    assert_int_equal(px[0][2], 4);
    assert_int_equal(px[1][2], 3);
    assert_true(px[0][0] >= 7 * S / 8);      /* the near +++ leaf: magnified */
    assert_true(px[1][0] >= S / 8);          /* the far --- leaf: shrunk towards the centre */
    assert_true(px[0][3] < px[1][3]);
    assert_true(gt_guards_ok(&g));
    gt_free(&g);
    tree_free(&t);
}

/* Two leaves on the same pixel: the nearer one wins whichever is drawn first. */
static void test_render_depth_test(void **state)
{
    (void)state;
    tree t;
    memset(&t, 0, sizeof t);
    t.depth = 1;
    t.nodes[0] = 1;
    t.nodes[1] = 2;
    t.mask[0] = malloc(1);
    t.mask[0][0] = 0x88;                     /* children 3 (+x +y -z) and 7 (+x +y +z) */
    t.color[0] = calloc(1, 1);
    t.color[1] = malloc(2);
    t.color[1][0] = 30;
    t.color[1][1] = 70;
    tree_finish(&t, 0);
    gtarget g;
    gt_init(&g, S, S);
    int32_t px[8][4];
    mc_view v = mc_view_default();
    mc_stats st;
    for (int yaw = 0; yaw <= 2048; yaw += 2048) {   /* frontal: 7 is nearer and drawn last; turned: 3 */
        v.yaw = yaw;
        mc_clear(&g.t);
        assert_int_equal(mc_octree_render(&t.scene, &v, 1, NULL, &g.t, NULL, NULL, &st), MC_OK);
        assert_int_equal(st.points, 2);
        assert_int_equal(drawn(&g, px), 1);
        assert_int_equal(px[0][2], yaw == 0 ? 70 : 30);
    }
    gt_free(&g);
    tree_free(&t);
}

/* ---- mc_octree_render: abort polling -------------------------------------------------------------- */

static int abort_after;
static int poll_count;
static int abort_cb(void *user)
{
    (void)user;
    return ++poll_count >= abort_after;
}

static void test_render_abort(void **state)
{
    (void)state;
    tree t;
    rng_state = 77;
    tree_random(&t, MC_ABORT_LEVEL + 3 <= MAXD ? MC_ABORT_LEVEL + 3 : MAXD, 2, 1);
    gtarget g, ref;
    gt_init(&ref, S, S);
    gt_init(&g, S, S);
    mc_view v = mc_view_default();
    v.zoom = MC_ZOOM_ONE / 2;                 /* the whole bounding sphere on screen */
    mc_stats st;
    for (unsigned d = 1; d <= t.depth; d++) {
        /* without a callback nothing is polled */
        mc_clear(&ref.t);
        assert_int_equal(mc_octree_render(&t.scene, &v, d, NULL, &ref.t, NULL, NULL, &st), MC_OK);
        assert_int_equal(st.polls, 0);
        assert_int_equal(st.aborted, 0);
        /* a callback that never aborts: the same image; the polls are one per node at one level of
         * the walk (octree_render.h: MC_ABORT_LEVEL, where the walk goes that deep) */
        abort_after = 1 << 30;
        poll_count = 0;
        mc_clear(&g.t);
        assert_int_equal(mc_octree_render(&t.scene, &v, d, NULL, &g.t, abort_cb, NULL, &st), MC_OK);
        assert_int_equal(st.aborted, 0);
        assert_int_equal(st.polls, (uint32_t)poll_count);
        assert_memory_equal(g.t.depth, ref.t.depth, g.n * sizeof(uint16_t));
        assert_memory_equal(g.t.color, ref.t.color, g.n);
        int one_level = st.polls == 0;
        for (unsigned l = 0; l < d; l++) one_level |= st.polls == t.nodes[l];
        if (!one_level)
            fail_msg("depth %u: %" PRIu32 " polls is not the number of nodes at any one level above the drawn"
                     " one", d, st.polls);
        if (d >= MC_ABORT_LEVEL + 3 && st.polls != t.nodes[MC_ABORT_LEVEL])
            fail_msg("depth %u: %" PRIu32 " polls, want one per node at level MC_ABORT_LEVEL = %d: %" PRIu32, d,
                     st.polls, MC_ABORT_LEVEL, t.nodes[MC_ABORT_LEVEL]);
        print_message("# info: abort: depth %u polls %" PRIu32 "\n", d, st.polls);
        if (st.polls < 3) continue;
        /* giving up at the third poll */
        abort_after = 3;
        poll_count = 0;
        mc_clear(&g.t);
        assert_int_equal(mc_octree_render(&t.scene, &v, d, NULL, &g.t, abort_cb, NULL, &st), MC_OK);
        assert_int_equal(st.polls, 3);
        assert_int_equal(poll_count, 3);
        assert_int_equal(st.aborted, 1);
        assert_true(st.points < t.nodes[d]);
    }
    assert_true(gt_guards_ok(&g));
    assert_true(gt_guards_ok(&ref));
    gt_free(&g);
    gt_free(&ref);
    tree_free(&t);
}

/* ---- mc_octree_render: random scenes and views ---------------------------------------------------- */

static int32_t rand_zoom_like(int32_t one, int lo_bits, int hi_bits)
{
    switch (rnd(8)) {
    case 0: return extremes[rnd(N_EXTREMES)];
    case 1: return (int32_t)(uint32_t)rng64();
    default: {
        int b = lo_bits + (int)rnd((uint32_t)(hi_bits - lo_bits + 1));
        int64_t v = b >= 0 ? (int64_t)one << b : (int64_t)one >> -b;
        v += (int64_t)(rng64() % (uint64_t)(v + 1));
        return v > INT32_MAX ? INT32_MAX : (int32_t)v;
    }
    }
}

/* A crash inside mc_octree_render names the render before cmocka reports the signal. */
static const char *volatile crash_context;
static void (*prev_handler[NSIG])(int);
static void on_crash(int sig)
{
    if (crash_context) fprintf(stderr, "ERROR: signal %d (%s) in mc_octree_render: %s\n", sig, strsignal(sig), crash_context);
    crash_context = NULL;
    signal(sig, prev_handler[sig]);
    if (prev_handler[sig] != SIG_DFL && prev_handler[sig] != SIG_IGN) prev_handler[sig](sig);
    else raise(sig);
}

/* The level of detail's rule (mc_octree_lod_depth) against the same rule in double precision: the
 * least level whose node side, S / 2^l pixels (S = zoom times the shorter side, in perspective times
 * eye / (eye - sqrt(3)/2)), is at most max_error / 16. The runtime rounds sqrt(3)/2 up to Q16, which
 * can only make it one level finer, at near ties: both radii bracket what it may pick. Exact ties
 * (the side equal to the bound) take the level, as the promise says "at most". */
static unsigned lod_rule(const mc_view *v, unsigned w, unsigned h, unsigned d, unsigned err, double radius)
{
    const mc_view cv = mc_view_clamp(v, w, h);
    if (!err || d <= 1) return d;
    double mag = 1;
    if (cv.projection == MC_PERSPECTIVE) {
        const double eye = cv.eye / 65536.0;
        if (eye - radius < 1.0 / 64) return d;
        mag = eye / (eye - radius);
    }
    const double side = cv.zoom / 65536.0 * (w < h ? w : h) * mag;
    for (unsigned l = 1; l < d; l++)
        if (ldexp(side, -(int)l) <= err / 16.0) return l;
    return d;
}

static void test_lod_depth(void **state)
{
    (void)state;
    mc_view v = mc_view_default();
    /* exact ties and the ends: 256 pixels, zoom 1: a level-8 node is one pixel (where the format
     * holds such extents unclamped: not at MC_FRAC_BITS 24) */
    if (MC_COORD_LIMIT / 2 >= 320) {
    assert_int_equal(mc_octree_lod_depth(&v, 256, 256, 10, MC_LOD_PIXEL), 8);
    assert_int_equal(mc_octree_lod_depth(&v, 256, 300, 10, 2 * MC_LOD_PIXEL), 7);
    assert_int_equal(mc_octree_lod_depth(&v, 257, 300, 10, MC_LOD_PIXEL), 9);
    assert_int_equal(mc_octree_lod_depth(&v, 256, 256, 6, MC_LOD_PIXEL), 6); /* not deeper */
    assert_int_equal(mc_octree_lod_depth(&v, 256, 256, 10, 0), 10);              /* off */
    assert_int_equal(mc_octree_lod_depth(&v, 256, 256, 10, 0xFFFF), 1); /* level 1 at most */
    v.zoom = MC_ZOOM_ONE / 4;
    assert_int_equal(mc_octree_lod_depth(&v, 320, 240, 8, MC_LOD_PIXEL), 6); /* 60 px: 0.94 at 6 */
    /* the sphere within 1/64 of a side of the eye */
        v.zoom = MC_ZOOM_ONE, v.projection = MC_PERSPECTIVE, v.eye = 56756 + 1023;
    assert_int_equal(mc_octree_lod_depth(&v, 320, 240, 8, 0xFFFF), 8);
    v.eye = 2 * MC_ZOOM_ONE;                       /* 240 * 2 / (2 - 0.866) = 423.3 px: 0.83 at 9 */
    assert_int_equal(mc_octree_lod_depth(&v, 320, 240, 12, MC_LOD_PIXEL), 9);
    }
    /* random views */
    unsigned fails = 0, finer = 0;
    for (int i = 0; i < 200000; i++) {
        v = mc_view_default();
        v.zoom = (int32_t)lround(MC_ZOOM_ONE * exp2((double)rnd(1 << 20) / (1 << 20) * 14 - 7));
        v.projection = rnd(2) ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
        v.eye = rnd(8) ? (int32_t)lround(MC_ZOOM_ONE * exp2((double)rnd(1 << 20) / (1 << 20) * 12 - 4))
                       : (int32_t)(56756 + 1024 - 8 + rnd(16));   /* near the eye's threshold */
        const unsigned w = 1 + rnd(MC_TARGET_MAX), h = 1 + rnd(MC_TARGET_MAX), d = 1 + rnd(MC_MAX_DEPTH);
        const unsigned err = rnd(4) ? 1 + rnd(1024) : 16u << rnd(6);   /* powers of two: exact ties */
        const unsigned got = mc_octree_lod_depth(&v, w, h, d, (uint16_t)err);
        const unsigned a = lod_rule(&v, w, h, d, err, sqrt(3) / 2), b = lod_rule(&v, w, h, d, err, 56756 / 65536.0);
        if (got != a && got != b) {
            if (!fails++)
                print_message("zoom %d %ux%u depth %u err %u proj %d eye %d: %u, the rule %u..%u\n", (int)v.zoom, w, h,
                              d, err, (int)v.projection, (int)v.eye, got, a, b);
        }
        finer += got != a;
    }
    assert_int_equal(fails, 0);
    assert_true(finer < 200);   /* the rounded radius decides only near ties */
}

static void test_render_random(void **state)
{
    (void)state;
    static const int sigs[] = {SIGFPE, SIGSEGV, SIGBUS, SIGILL};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) prev_handler[sigs[i]] = signal(sigs[i], on_crash);
    rng_state = 2024;
    uint64_t renders = 0, points = 0, filled = 0;
    for (int n = 0; n < 600; n++) {
        tree t;
        unsigned depth = 1 + rnd(MAXD < MC_MAX_DEPTH ? MAXD : MC_MAX_DEPTH);
        tree_random(&t, depth, (int)rnd(3), 1);
        for (int k = 0; k < 20; k++) {
            unsigned w = 1 + rnd(S), h = 1 + rnd(S);
            if (rnd(10) == 0) { w = MC_TARGET_MAX - rnd(2); h = 1 + rnd(3); }
            if (rnd(10) == 0) { h = MC_TARGET_MAX - rnd(2); w = 1 + rnd(3); }
            gtarget g;
            gt_init(&g, w, h);
            mc_view v;
            v.yaw = (int32_t)(rnd(2) ? (uint32_t)rng64() : rnd(4096));
            v.pitch = (int32_t)(rnd(2) ? (uint32_t)rng64() : rnd(4096));
            v.roll = (int32_t)(rnd(2) ? (uint32_t)rng64() : rnd(4096));
            v.zoom = rand_zoom_like(MC_ZOOM_ONE, -9, 7);
            int32_t span = (int32_t)(w > h ? w : h);
            v.tx = rnd(8) ? (int32_t)rnd((uint32_t)(2 * span + 1)) - span : extremes[rnd(N_EXTREMES)];
            v.ty = rnd(8) ? (int32_t)rnd((uint32_t)(2 * span + 1)) - span : extremes[rnd(N_EXTREMES)];
            v.projection = (mc_projection)(int)(rnd(5) == 0 ? 9 : rnd(2));
            v.eye = rand_zoom_like(MC_ZOOM_ONE, -5, 9);
            unsigned d = 1 + rnd(depth);
            mc_stats st;
            mc_clear(&g.t);
            hook.calls = hook.off = 0;
            mc_view cv = mc_view_clamp(&v, w, h);
            char what[256];
            snprintf(what, sizeof what,
                     "tree depth %u drawn at %u, %ux%u, yaw %" PRId32 " pitch %" PRId32 " roll %" PRId32
                     " zoom %" PRId32 " tx %" PRId32 " ty %" PRId32 " %s eye %" PRId32 " (clamped)",
                     depth, d, w, h, cv.yaw, cv.pitch, cv.roll, cv.zoom, cv.tx, cv.ty,
                     cv.projection == MC_PERSPECTIVE ? "perspective" : "orthographic", cv.eye);
            crash_context = what;
            int rc = mc_octree_render(&t.scene, &v, d, NULL, &g.t, NULL, NULL, &st);
            crash_context = NULL;
            renders++;
            if (rc != MC_OK) fail_msg("mc_octree_render returned %d for %s", rc, what);
            if (hook.off)
                fail_msg("%" PRIu32 " point(s) reported on screen lie off the target, first at (%.4f, %.4f)"
                         " pixels: %s", hook.off, hook.off_fx / (double)(1 << F), hook.off_fy / (double)(1 << F),
                         what);
            if (!gt_guards_ok(&g)) fail_msg("mc_octree_render wrote outside the target: %s", what);
            if (st.points != hook.calls)
                fail_msg("stats.points %" PRIu32 " but %" PRIu32 " points reported on screen: %s", st.points,
                         hook.calls, what);
            if (st.points > t.nodes[d])
                fail_msg("stats.points %" PRIu32 " > %" PRIu32 " leaves: %s", st.points, t.nodes[d], what);
            if (st.polls != 0 || st.aborted) fail_msg("polls without a callback: %s", what);
            uint32_t ndrawn = 0, holes = 0;
            for (size_t i = 0; i < g.n; i++) {
                if (g.t.depth[i] == MC_DEPTH_EMPTY) {
                    if (g.t.color[i] != 0) fail_msg("empty pixel %zu has colour %d: %s", i, g.t.color[i], what);
                    continue;
                }
                ndrawn++;
                if (g.t.depth[i] >= MC_DEPTH_EMPTY - 1)
                    fail_msg("pixel (%zu, %zu) drawn with depth %u, want < MC_DEPTH_EMPTY - 1 = %u: %s", i % w,
                             i / w, g.t.depth[i], MC_DEPTH_EMPTY - 1, what);
                uint8_t c = g.t.color[i];
                if (!(t.colors_at[d][c >> 3] & (1u << (c & 7))))
                    fail_msg("pixel %zu has colour %d, not a level-%u colour: %s", i, c, d, what);
            }
            if (ndrawn > st.points)
                fail_msg("%" PRIu32 " pixels drawn from %" PRIu32 " points: %s", ndrawn, st.points, what);
            /* every one-pixel hole of this image, counted before filling */
            for (int32_t y = 1; y + 1 < (int32_t)h; y++)
                for (int32_t x = 1; x + 1 < (int32_t)w; x++) {
                    size_t i = (size_t)y * w + (size_t)x;
                    holes += g.t.depth[i] == MC_DEPTH_EMPTY && g.t.depth[i - 1] != MC_DEPTH_EMPTY &&
                             g.t.depth[i + 1] != MC_DEPTH_EMPTY && g.t.depth[i - w] != MC_DEPTH_EMPTY &&
                             g.t.depth[i + w] != MC_DEPTH_EMPTY;
                }
            uint32_t f = mc_finish_pixel_holes(&g.t);
            if (f != holes) fail_msg("mc_finish_pixel_holes filled %" PRIu32 " of %" PRIu32 " holes: %s", f, holes, what);
            if (!gt_guards_ok(&g)) fail_msg("mc_finish_pixel_holes wrote outside the target: %s", what);
            points += st.points;
            filled += f;
            gt_free(&g);
        }
        tree_free(&t);
    }
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) signal(sigs[i], prev_handler[sigs[i]]);
    print_message("# info: %" PRIu64 " random renders, %" PRIu64 " points on screen, %" PRIu64 " holes filled\n",
                  renders, points, filled);
}

/* ---- mc_finish_pixel_holes ----------------------------------------------------------------- */

static void fill_all(gtarget *g, uint16_t depth, uint8_t color)
{
    for (size_t i = 0; i < g->n; i++) {
        g->t.depth[i] = depth;
        g->t.color[i] = color;
    }
}
#define AT(g, x, y) ((size_t)(y) * (g).t.width + (size_t)(x))
static void set_px(gtarget *g, int x, int y, uint16_t depth, uint8_t color)
{
    g->t.depth[AT(*g, x, y)] = depth;
    g->t.color[AT(*g, x, y)] = color;
}
static void hole(gtarget *g, int x, int y) { set_px(g, x, y, MC_DEPTH_EMPTY, 0); }

static void test_finish_hand(void **state)
{
    (void)state;
    gtarget g;
    gt_init(&g, 8, 6);
    /* one hole, four drawn neighbours: each in turn the nearest gives colour and depth */
    static const int nb[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (int k = 0; k < 4; k++) {
        fill_all(&g, 1000, 9);
        for (int j = 0; j < 4; j++) set_px(&g, 3 + nb[j][0], 2 + nb[j][1], (uint16_t)(500 + 10 * j), (uint8_t)(20 + j));
        set_px(&g, 3 + nb[k][0], 2 + nb[k][1], 100, 77);
        hole(&g, 3, 2);
        assert_int_equal(mc_finish_pixel_holes(&g.t), 1);
        assert_int_equal(g.t.depth[AT(g, 3, 2)], 100);
        assert_int_equal(g.t.color[AT(g, 3, 2)], 77);
        for (int j = 0; j < 4; j++)   /* the neighbours are untouched */
            if (j != k) assert_int_equal(g.t.depth[AT(g, 3 + nb[j][0], 2 + nb[j][1])], 500 + 10 * j);
    }
    /* two-pixel holes, horizontal and vertical, are left open */
    fill_all(&g, 1000, 9);
    hole(&g, 2, 2);
    hole(&g, 3, 2);
    hole(&g, 5, 2);
    hole(&g, 5, 3);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 0);
    assert_int_equal(g.t.depth[AT(g, 2, 2)], MC_DEPTH_EMPTY);
    assert_int_equal(g.t.depth[AT(g, 3, 2)], MC_DEPTH_EMPTY);
    assert_int_equal(g.t.depth[AT(g, 5, 2)], MC_DEPTH_EMPTY);
    assert_int_equal(g.t.depth[AT(g, 5, 3)], MC_DEPTH_EMPTY);
    assert_int_equal(g.t.color[AT(g, 2, 2)], 0);
    /* three drawn neighbours are not enough */
    fill_all(&g, 1000, 9);
    hole(&g, 3, 3);
    hole(&g, 3, 4);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 0);
    /* diagonal neighbours holes: each still has four drawn neighbours, both are filled */
    fill_all(&g, 1000, 9);
    hole(&g, 2, 2);
    hole(&g, 3, 3);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 2);
    assert_int_equal(g.t.depth[AT(g, 2, 2)], 1000);
    assert_int_equal(g.t.depth[AT(g, 3, 3)], 1000);
    /* border pixels: never, even with every neighbour inside the image drawn */
    int border[][2] = {{0, 0}, {7, 0}, {0, 5}, {7, 5}, {3, 0}, {0, 3}, {7, 2}, {4, 5}};
    fill_all(&g, 1000, 9);
    for (size_t b = 0; b < sizeof border / sizeof border[0]; b++) hole(&g, border[b][0], border[b][1]);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 0);
    for (size_t b = 0; b < sizeof border / sizeof border[0]; b++)
        assert_int_equal(g.t.depth[AT(g, border[b][0], border[b][1])], MC_DEPTH_EMPTY);
    /* a checkerboard: every interior empty pixel is a one-pixel hole of the input */
    uint32_t want = 0;
    for (int y = 0; y < 6; y++)
        for (int x = 0; x < 8; x++) {
            if ((x + y) & 1) {
                hole(&g, x, y);
                want += x > 0 && y > 0 && x < 7 && y < 5;
            } else {
                set_px(&g, x, y, (uint16_t)(x * 10 + y), (uint8_t)(x * 10 + y));
            }
        }
    assert_int_equal(mc_finish_pixel_holes(&g.t), want);
    for (int y = 1; y < 5; y++)
        for (int x = 1; x < 7; x++)
            if ((x + y) & 1) {   /* the nearest of the four is the smallest x * 10 + y: the left one */
                assert_int_equal(g.t.depth[AT(g, x, y)], (x - 1) * 10 + y < x * 10 + y - 1 ? (x - 1) * 10 + y : x * 10 + y - 1);
            }
    /* an empty image and an all-drawn image are left alone */
    fill_all(&g, MC_DEPTH_EMPTY, 0);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 0);
    fill_all(&g, 5, 5);
    assert_int_equal(mc_finish_pixel_holes(&g.t), 0);
    assert_true(gt_guards_ok(&g));
    gt_free(&g);
    /* degenerate sizes: nothing is interior */
    static const unsigned dims[][2] = {{1, 1}, {1, 5}, {5, 1}, {2, 2}, {2, 7}, {7, 2}};
    for (size_t k = 0; k < sizeof dims / sizeof dims[0]; k++) {
        gt_init(&g, dims[k][0], dims[k][1]);
        fill_all(&g, 3, 3);
        for (size_t i = 0; i < g.n; i += 2) { g.t.depth[i] = MC_DEPTH_EMPTY; g.t.color[i] = 0; }
        assert_int_equal(mc_finish_pixel_holes(&g.t), 0);
        assert_true(gt_guards_ok(&g));
        gt_free(&g);
    }
}

/* Random images against a reference computed from a copy of the input: exactly the one-pixel holes
 * of the input are filled, each with its nearest neighbour (ties: any of the nearest), and nothing
 * else changes. */
static void test_finish_random(void **state)
{
    (void)state;
    rng_state = 99;
    for (int n = 0; n < 20000; n++) {
        unsigned w = 1 + rnd(24), h = 1 + rnd(24);
        gtarget g;
        gt_init(&g, w, h);
        uint32_t density = 1 + rnd(10);       /* 1 in `density` pixels empty */
        for (size_t i = 0; i < g.n; i++) {
            if (rnd(density) == 0) { g.t.depth[i] = MC_DEPTH_EMPTY; g.t.color[i] = 0; }
            else { g.t.depth[i] = (uint16_t)rnd(8); g.t.color[i] = (uint8_t)rnd(256); }
        }
        uint16_t *d0 = malloc(g.n * sizeof *d0);
        uint8_t *c0 = malloc(g.n);
        memcpy(d0, g.t.depth, g.n * sizeof *d0);
        memcpy(c0, g.t.color, g.n);
        uint32_t want = 0;
        uint32_t got = mc_finish_pixel_holes(&g.t);
        for (size_t i = 0; i < g.n; i++) {
            size_t x = i % w, y = i / w;
            int is_hole = d0[i] == MC_DEPTH_EMPTY && x > 0 && y > 0 && x + 1 < w && y + 1 < h &&
                          d0[i - 1] != MC_DEPTH_EMPTY && d0[i + 1] != MC_DEPTH_EMPTY &&
                          d0[i - w] != MC_DEPTH_EMPTY && d0[i + w] != MC_DEPTH_EMPTY;
            if (!is_hole) {
                if (g.t.depth[i] != d0[i] || g.t.color[i] != c0[i])
                    fail_msg("%ux%u: pixel (%zu,%zu) changed but is not a one-pixel hole of the input", w, h, x, y);
                continue;
            }
            want++;
            const size_t nb[4] = {i - 1, i + 1, i - w, i + w};
            uint16_t best = MC_DEPTH_EMPTY;
            for (int k = 0; k < 4; k++) if (d0[nb[k]] < best) best = d0[nb[k]];
            int ok = 0;
            for (int k = 0; k < 4; k++) ok |= d0[nb[k]] == best && g.t.depth[i] == best && g.t.color[i] == c0[nb[k]];
            if (!ok)
                fail_msg("%ux%u: hole (%zu,%zu) got depth %u colour %u, not a nearest neighbour's (depth %u)", w, h,
                         x, y, g.t.depth[i], g.t.color[i], best);
        }
        if (got != want) fail_msg("%ux%u: returned %" PRIu32 ", filled %" PRIu32, w, h, got, want);
        if (!gt_guards_ok(&g)) fail_msg("%ux%u: wrote outside the image", w, h);
        free(d0);
        free(c0);
        gt_free(&g);
    }
}

int main(void)
{
    setvbuf(stdout, NULL, _IONBF, 0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clamp),
        cmocka_unit_test(test_render_args),
        cmocka_unit_test(test_render_tiny),
        cmocka_unit_test(test_render_depth_test),
        cmocka_unit_test(test_render_abort),
        cmocka_unit_test(test_finish_hand),
        cmocka_unit_test(test_finish_random),
        cmocka_unit_test(test_render_random),
        cmocka_unit_test(test_lod_depth),
    };
    return cmocka_run_group_tests_name("view", tests, NULL, NULL);
}
