/* Hole filling on synthetic images (modelc/finish.h): the scanline neighbourhood criterion closes
 * hole types 1 to 4 and leaves border holes (type 5) open; it agrees with a brute-force evaluation
 * of the criterion on random images; and zoom footprints (octree_render.h, MC_SPLAT_ZOOM) cover s x s
 * pixels. Prints "ok - NAME" / "not ok - NAME: why" per check; exits non-zero if any failed.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/modelc.h>

#define W 48
#define H 40
#define K MC_FILL_REACH

static uint8_t fb[W * H], fb0[W * H];
static uint16_t zb[W * H], zb0[W * H];
static const mc_target T = {fb, zb, W, H};
static int failed;

static void check(int ok, const char *name, const char *why)
{
    if (ok) printf("ok - finish: %s\n", name);
    else printf("not ok - finish: %s: %s\n", name, why);
    failed += !ok;
}

static void clear(void) { mc_clear(&T); }
static void put(int x, int y, uint16_t z, uint8_t c) { zb[y * W + x] = z; fb[y * W + x] = c; }
static void hole(int x, int y) { zb[y * W + x] = MC_DEPTH_EMPTY; fb[y * W + x] = 0; }
static void rect(int x0, int y0, int x1, int y1, uint16_t z, uint8_t c)   /* [x0, x1) x [y0, y1) */
{
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) put(x, y, z, c);
}
static void save(void) { memcpy(fb0, fb, sizeof fb); memcpy(zb0, zb, sizeof zb); }

/* the block every interior hole is cut into */
static void block(void) { clear(); rect(4, 4, 44, 36, 100, 7); }

/* Cuts the holes (x, y) listed, fills, and checks every one closed with the block's colour and
 * nothing else changed. */
static void closes(const char *name, const int (*xy)[2], int n)
{
    block();
    for (int i = 0; i < n; i++) hole(xy[i][0], xy[i][1]);
    save();
    uint32_t f = mc_finish_scanline_holes(&T);
    char why[200] = "";
    for (int i = 0; i < n && !why[0]; i++) {
        int j = xy[i][1] * W + xy[i][0];
        if (zb[j] != MC_DEPTH_FILLED || fb[j] != 7)
            snprintf(why, sizeof why, "hole (%d, %d) not closed (depth %u colour %u)", xy[i][0], xy[i][1], zb[j], fb[j]);
    }
    if (!why[0] && f != (uint32_t)n) snprintf(why, sizeof why, "filled %u pixels, want %d", f, n);
    check(!why[0], name, why);
}

/* Fills and checks nothing changed (the image is set up by the caller). */
static void stays_open(const char *name)
{
    save();
    uint32_t f = mc_finish_scanline_holes(&T);
    char why[200] = "";
    if (f || memcmp(zb, zb0, sizeof zb) || memcmp(fb, fb0, sizeof fb)) {
        int at = -1;
        for (int i = 0; i < W * H && at < 0; i++)
            if (zb[i] != zb0[i]) at = i;
        snprintf(why, sizeof why, "filled %u pixels, first at (%d, %d)", f, at % W, at / W);
    }
    check(!why[0], name, why);
}

/* ---- brute force: the criterion as finish.h states it, on a copy of the input ----------------- */
static void brute(const uint16_t *z, const uint8_t *c, uint16_t *oz, uint8_t *oc, uint32_t *count)
{
    static const int dir[8][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, 1}, {1, -1}, {-1, 1}};
    memcpy(oz, z, sizeof zb);
    memcpy(oc, c, sizeof fb);
    *count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (z[y * W + x] != MC_DEPTH_EMPTY) continue;
            int bounded = 0, best = -1;
            for (int l = 0; l < 4; l++) {
                int hit[2] = {-1, -1};
                for (int s = 0; s < 2; s++) {
                    const int *d = dir[2 * l + s];
                    for (int r = 1; r <= K; r++) {
                        int xx = x + d[0] * r, yy = y + d[1] * r;
                        if (xx < 0 || yy < 0 || xx >= W || yy >= H) break;
                        if (z[yy * W + xx] < MC_DEPTH_FILLED) { hit[s] = yy * W + xx; break; }
                    }
                }
                if (hit[0] < 0 || hit[1] < 0) continue;
                bounded++;
                for (int s = 0; s < 2; s++)
                    if (best < 0 || z[hit[s]] < z[best]) best = hit[s];
            }
            if (bounded < 3) continue;
            oz[y * W + x] = MC_DEPTH_FILLED;
            oc[y * W + x] = c[best];
            (*count)++;
        }
}

static uint64_t rng = 88172645463325252ull;
static uint32_t rnd(uint32_t n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng % n);
}

/* ---- footprints: a one-leaf scene -------------------------------------------------------------- */
static const uint8_t one_mask[1] = {0x01}, one_color[1] = {5};
static const mc_chunk mask_chunks[2] = {{one_mask, 1}, {0, 0}};
static const mc_chunk color_chunks[2] = {{one_color, 1}, {0, 0}};
static const uint8_t palette[3 * 8] = {0};
static const mc_octree_level one_levels[2] = {{1, mask_chunks, NULL, NULL}, {1, NULL, color_chunks, NULL}};
static const mc_octree one_leaf = {1, 8, palette, one_levels};

static int drawn_pixels(void)
{
    int n = 0;
    for (int i = 0; i < W * H; i++) n += zb[i] != MC_DEPTH_EMPTY;
    return n;
}

int main(void)
{
    char name[200], why[200];

    /* type 1: single pixels */
    static const int t1[][2] = {{10, 10}, {20, 12}, {30, 30}, {5, 34}};
    closes("type 1: single empty pixels inside the model are closed", t1, 4);
    block();
    for (int i = 0; i < 4; i++) hole(t1[i][0], t1[i][1]);
    uint32_t f1 = mc_finish_pixel_holes(&T);
    snprintf(why, sizeof why, "mc_finish_pixel_holes filled %u of 4", f1);
    check(f1 == 4, "type 1: the one-pixel fill closes them too", why);

    /* type 2: horizontal gaps up to the reach, and a long crack along a row */
    int t2[64][2], n = 0;
    for (int x = 8; x < 8 + 2; x++) t2[n][0] = x, t2[n++][1] = 8;
    for (int x = 14; x < 14 + K; x++) t2[n][0] = x, t2[n++][1] = 12;
    for (int x = 10; x < 34; x++) t2[n][0] = x, t2[n++][1] = 20;
    closes("type 2: horizontal gaps (2 and MC_FILL_REACH long) and a 24-pixel crack along a row", (const int (*)[2])t2, n);

    /* type 3: vertical */
    n = 0;
    for (int y = 8; y < 8 + 2; y++) t2[n][0] = 8, t2[n++][1] = y;
    for (int y = 14; y < 14 + K; y++) t2[n][0] = 12, t2[n++][1] = y;
    for (int y = 6; y < 34; y++) t2[n][0] = 30, t2[n++][1] = y;
    closes("type 3: vertical gaps (2 and MC_FILL_REACH long) and a 28-pixel crack along a column", (const int (*)[2])t2, n);

    /* type 4: clusters and diagonal cracks */
    static const int sq[][2] = {{10, 10}, {11, 10}, {10, 11}, {11, 11}};
    closes("type 4: a 2x2 block", sq, 4);
    static const int ell[][2] = {{20, 10}, {21, 10}, {20, 11}};
    closes("type 4: an L of three pixels", ell, 3);
    static const int corner[][2] = {{30, 10}, {31, 11}};
    closes("type 4: two pixels touching at a corner", corner, 2);
    n = 0;
    for (int i = 0; i < 20; i++) t2[n][0] = 10 + i, t2[n++][1] = 8 + i;
    closes("type 4: a 20-pixel diagonal crack (down-right)", (const int (*)[2])t2, n);
    n = 0;
    for (int i = 0; i < 20; i++) t2[n][0] = 35 - i, t2[n++][1] = 8 + i;
    closes("type 4: a 20-pixel diagonal crack (down-left)", (const int (*)[2])t2, n);
    if (K >= 3) {
        n = 0;
        for (int y = 20; y < 23; y++)
            for (int x = 20; x < 23; x++) t2[n][0] = x, t2[n++][1] = y;
        closes("type 4: a 3x3 block (MC_FILL_REACH 3)", (const int (*)[2])t2, n);
    }

    /* type 5: the outline, open to the background */
    block();
    stays_open("type 5: the outside of a rectangle's straight edges and corners");
    block();
    hole(10, 4);                                  /* notches one pixel deep in the top edge */
    hole(15, 4), hole(16, 4);
    hole(22, 4), hole(23, 4), hole(24, 4);
    hole(4, 20);                                  /* and in the left, right and bottom edges */
    hole(43, 12), hole(43, 13);
    hole(30, 35), hole(31, 35), hole(32, 35), hole(33, 35);
    stays_open("type 5: notches one pixel deep, 1 to 4 pixels wide, in every edge");
    clear();
    rect(4, 4, 44, 20, 100, 7);                  /* an L: concave corner at (24, 20) */
    rect(4, 20, 24, 36, 100, 7);
    stays_open("type 5: a concave corner");
    for (int slope = 1; slope <= 4; slope++) {   /* staircase edges: triangles of slopes 1/s and s */
        clear();
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                if (x * slope >= y + 4 && y * slope >= x - 30) put(x, y, 100, 7);
        snprintf(name, sizeof name, "type 5: staircase outlines of slope %d and 1/%d", slope, slope);
        stays_open(name);
    }
    clear();
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if ((x - 24) * (x - 24) + (y - 20) * (y - 20) <= 15 * 15) put(x, y, 100, 7);
    stays_open("type 5: a disc's outline");

    /* the colour of the nearest bound; filled pixels are never bounds, so a second call fills nothing */
    block();
    hole(20, 20);
    put(21, 20, 50, 3);
    put(20, 21, 60, 4);
    mc_finish_scanline_holes(&T);
    snprintf(why, sizeof why, "colour %u depth %u, want colour 3 (the nearest bound) depth %u", fb[20 * W + 20],
             zb[20 * W + 20], (unsigned)MC_DEPTH_FILLED);
    check(fb[20 * W + 20] == 3 && zb[20 * W + 20] == MC_DEPTH_FILLED, "a hole takes the colour of its nearest bound", why);
    save();
    uint32_t again = mc_finish_scanline_holes(&T);
    check(again == 0 && !memcmp(zb, zb0, sizeof zb) && !memcmp(fb, fb0, sizeof fb),
          "a second call fills nothing more", "it changed the image");

    /* random images against the brute-force criterion */
    static uint16_t bz[W * H];
    static uint8_t bc[W * H];
    int bad = 0;
    uint32_t total = 0;
    for (int r = 0; r < 3000 && !bad; r++) {
        clear();
        uint32_t density = 1 + rnd(99);
        for (int i = 0; i < W * H; i++)
            if (rnd(100) < density) { zb[i] = (uint16_t)rnd(60000); fb[i] = (uint8_t)rnd(256); }
        if (rnd(4) == 0)   /* some blank rows and columns */
            for (int k = 0; k < 3; k++) {
                int a = (int)rnd(W), b = (int)rnd(H);
                for (int y = 0; y < H; y++) hole(a, y);
                for (int x = 0; x < W; x++) hole(x, b);
            }
        uint32_t want;
        brute(zb, fb, bz, bc, &want);
        uint32_t got = mc_finish_scanline_holes(&T);
        total += got;
        if (got != want || memcmp(zb, bz, sizeof zb) || memcmp(fb, bc, sizeof fb)) {
            snprintf(why, sizeof why, "image %d (density %u%%): filled %u, brute force %u", r, density, got, want);
            bad = 1;
        }
    }
    snprintf(name, sizeof name, "3000 random images: the same pixels and colours as a brute-force evaluation of the criterion (%u fills)", total);
    check(!bad, name, why);

    /* mc_finish dispatches */
    block();
    hole(10, 10), hole(11, 10);
    check(mc_finish(&T, MC_FILL_NONE) == 0 && mc_finish(&T, MC_FILL_PIXEL) == 0 && mc_finish(&T, MC_FILL_SCANLINE) == 2,
          "mc_finish: none and pixel leave a 2-pixel gap, scanline closes it", "wrong counts");
    block();
    hole(10, 10), hole(11, 10);
    check(mc_finish(&T, (mc_fill)99) == (MC_FILL_DEFAULT_MODE == 2 ? 2u : 0u), "mc_finish: other values mean MC_FILL_DEFAULT_MODE",
          "wrong count");

    /* footprints of a one-leaf scene: s x s pixels, s = ceil(leaf side), 1..MC_SPLAT_MAX */
    static const struct { int32_t zoom; int want_side; } fp[] = {
        {MC_ZOOM_ONE / 64, 1}, {MC_ZOOM_ONE / 40, 1}, {MC_ZOOM_ONE / 32, 1}, {MC_ZOOM_ONE / 20, 1},
        {MC_ZOOM_ONE / 16, 2}, {MC_ZOOM_ONE / 8, 3}, {MC_ZOOM_ONE / 5, 4}, {MC_ZOOM_ONE, 20}};
    mc_target ft = {fb, zb, W, H};   /* shorter side H = 40: a depth-1 leaf is zoom * 20 pixels wide */
    for (size_t i = 0; i < sizeof fp / sizeof fp[0]; i++) {
        int side = fp[i].want_side > MC_SPLAT_MAX ? MC_SPLAT_MAX : fp[i].want_side;
        mc_view v = mc_view_default();
        v.zoom = fp[i].zoom;
        const mc_octree_options zoom = {MC_SPLAT_ZOOM, 0, MC_CULL_DEFAULT}, pixel = {MC_SPLAT_PIXEL, 0, MC_CULL_DEFAULT};
        mc_clear(&ft);
        mc_stats st;
        mc_octree_render(&one_leaf, &v, 1, &zoom, &ft, NULL, NULL, &st);
        int got = drawn_pixels();
        mc_clear(&ft);
        mc_octree_render(&one_leaf, &v, 1, &pixel, &ft, NULL, NULL, NULL);
        int one = drawn_pixels();
        snprintf(name, sizeof name, "zoom splat: a leaf %.3g pixels wide covers %dx%d pixels, one-pixel splat 1",
                 fp[i].zoom / 65536.0 * H / 2, side, side);
        snprintf(why, sizeof why, "covers %d pixels (one-pixel splat: %d), points %u", got, one, st.points);
        check(got == side * side && one == 1 && st.points == 1, name, why);
    }
    return failed != 0;
}
