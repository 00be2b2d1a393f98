/* The sparse depth buffer (modelc/sdepth.h) and the two passes that use it, against plain models:
 *   - random inserts, removals and clears on frames 1x1 to 1100x3 (rows of one block, of a partial
 *     block, and of more than 32 blocks: two words of block bits a row) against a dense array of
 *     (in use, depth, colour): the same state after every operation, pixels not in use holding the
 *     empty values, the bit vectors consistent (a block's bit set exactly when its word is not 0),
 *     mc_sdepth_any and mc_sdepth_any_from over random boxes equal to a scan, mc_sdepth_clear
 *     touching only pixels in use;
 *   - mc_line_sdepth: random lines, on and off the frame, against mc_line drawn with no depth test
 *     into a target: the same pixels and count, each entry the line's depth there less the offset
 *     (saturating at 0), nearest kept where lines cross;
 *   - mc_raster_triangle_hide, _offset and _box: random triangles (the rasterizer's own generator ranges:
 *     specks to triangles far beyond the frame, both orientations, culled or not, a third pushed back
 *     by a random offset) over random entries against mc_raster_triangle drawn into an empty target:
 *     an entry is emptied exactly where the triangle covers its pixel at a depth not greater than the
 *     entry's less the offset, and the count returned is those; and entries at the triangle's own
 *     depth there plus the offset, one less or one more (flat triangles among them), where emptied
 *     and kept lie a unit apart.
 * Each of these runs its second half with matched bits kept (mc_sdepth_keep_matched): entries
 * inserted matched or not (mc_sdepth_insert_matched, mc_sdepth_insert), lines matched against random
 * edge masks (mc_track_line: an entry matched where the mask there shares a bin with the
 * line's), every pixel's matched bit that of its kept entry, cleared with it,
 * and mc_sdepth_count_matched equal to the model's count.
 * Random numbers: PCG32 (modelc/rng.h) with fixed seeds.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <modelc/line.h>
#include <modelc/raster.h>
#include <modelc/rng.h>
#include <modelc/sdepth.h>
#include <modelc/track.h>

#define EMPTY_D 0xFFFEu
#define EMPTY_C 200u

typedef struct frame {
    mc_sdepth s;
    uint32_t *bits;
    uint16_t *depth;
    uint8_t *color;
    /* the model */
    uint8_t *in;
    uint16_t *md;
    uint8_t *mcol;
    uint32_t *mbits;   /* the matched words, when kept */
    uint8_t *mm;       /* the model's matched bits */
    /* a plain target of the same size, for mc_line and mc_raster_triangle to draw the expected */
    mc_target t;
} frame;

static void frame_new(frame *f, unsigned w, unsigned h)
{
    f->bits = malloc(4u * MC_SDEPTH_WORDS(w, h));
    f->depth = malloc(2u * w * h);
    f->color = malloc(w * h);
    f->in = calloc(w * h, 1);
    f->md = malloc(2u * w * h);
    f->mcol = malloc(w * h);
    f->t.color = malloc(w * h), f->t.depth = malloc(2u * w * h);
    f->t.width = (uint16_t)w, f->t.height = (uint16_t)h;
    assert_non_null(f->bits);
    /* garbage first: init must set everything */
    memset(f->bits, 0xA5, 4u * MC_SDEPTH_WORDS(w, h));
    memset(f->depth, 0x5A, 2u * w * h);
    memset(f->color, 0x33, w * h);
    assert_int_equal(mc_sdepth_init(&f->s, (uint16_t)w, (uint16_t)h, f->bits, f->depth, f->color, EMPTY_D, EMPTY_C),
                     MC_OK);
    for (unsigned i = 0; i < w * h; i++) f->md[i] = EMPTY_D, f->mcol[i] = EMPTY_C;
    f->mm = calloc(w * h, 1);
    f->mbits = malloc(4u * MC_SDEPTH_MATCHED_WORDS(w, h));
    memset(f->mbits, 0xA5, 4u * MC_SDEPTH_MATCHED_WORDS(w, h));
}

/* keeps matched bits from now on (the entries in use unmatched) */
static void frame_keep_matched(frame *f)
{
    mc_sdepth_keep_matched(&f->s, f->mbits);
    memset(f->mm, 0, (size_t)f->s.width * f->s.height);
}

static void frame_free(frame *f)
{
    free(f->bits), free(f->depth), free(f->color), free(f->in), free(f->md), free(f->mcol), free(f->mm), free(f->mbits);
    free(f->t.color), free(f->t.depth);
}

/* the buffer against the model, and the bit vectors against each other */
static void frame_check(const frame *f)
{
    const mc_sdepth *s = &f->s;
    uint32_t n = 0, nm = 0;
    for (unsigned y = 0; y < s->height; y++) {
        for (unsigned x = 0; x < s->width; x++) {
            const unsigned i = y * s->width + x;
            if (mc_sdepth_in_use(s, x, y) != f->in[i] || s->depth[i] != f->md[i] || s->color[i] != f->mcol[i])
                fail_msg("pixel (%u, %u): in use %d depth %u colour %u, model %d %u %u", x, y, mc_sdepth_in_use(s, x, y),
                         s->depth[i], s->color[i], f->in[i], f->md[i], f->mcol[i]);
            n += f->in[i];
            if (s->matched) {
                const int m = (s->matched[y * s->blocks + x / 32u] >> (31u - x % 32u)) & 1u;
                if (m != f->mm[i]) fail_msg("pixel (%u, %u): matched %d, model %d", x, y, m, f->mm[i]);
                nm += f->mm[i];
            }
        }
        for (unsigned b = 0; b < s->blocks; b++) {
            const uint32_t word = s->used[y * s->blocks + b];
            if (32u * b + 32u > s->width && s->width % 32u)   /* bits beyond the row stay clear */
                assert_int_equal(word & (0xFFFFFFFFu >> (s->width % 32u)), 0);
            const int bit = (s->rows[y * s->row_words + b / 32u] >> (31u - b % 32u)) & 1u;
            if (bit != (word != 0)) fail_msg("row %u block %u: block bit %d, word %08x", y, b, bit, word);
        }
        for (unsigned b = s->blocks; b < 32u * s->row_words; b++)
            assert_int_equal((s->rows[y * s->row_words + b / 32u] >> (31u - b % 32u)) & 1u, 0);
    }
    assert_int_equal(mc_sdepth_count(s), n);
    assert_int_equal(mc_sdepth_count_matched(s), nm);
}

static void model_insert_matched(frame *f, unsigned x, unsigned y, uint16_t z, uint8_t c, int m)
{
    const unsigned i = y * f->s.width + x;
    if (f->in[i] && z >= f->md[i]) return;
    f->in[i] = 1, f->md[i] = z, f->mcol[i] = c, f->mm[i] = (uint8_t)(m != 0);
}

static void model_insert(frame *f, unsigned x, unsigned y, uint16_t z, uint8_t c) { model_insert_matched(f, x, y, z, c, 0); }

static void model_remove(frame *f, unsigned x, unsigned y)
{
    const unsigned i = y * f->s.width + x;
    f->in[i] = 0, f->md[i] = EMPTY_D, f->mcol[i] = EMPTY_C, f->mm[i] = 0;
}

/* mc_sdepth_clear, and the model emptied likewise */
static void frame_clear(frame *f)
{
    mc_sdepth_clear(&f->s);
    for (unsigned i = 0; i < (unsigned)f->s.width * f->s.height; i++) model_remove(f, i % f->s.width, i / f->s.width);
}

static void ops_on(unsigned w, unsigned h, int rounds, uint64_t seed)
{
    mc_rng r;
    mc_rng_seed(&r, seed, 5);
    frame f;
    frame_new(&f, w, h);
    frame_check(&f);
    for (int round = 0; round < rounds; round++) {
        if (round == rounds / 2) frame_keep_matched(&f);   /* the second half keeps matched bits */
        const unsigned ops = mc_rng_below(&r, 4u * w * h / 3u + 2u);
        for (unsigned k = 0; k < ops; k++) {
            const unsigned x = mc_rng_below(&r, w), y = mc_rng_below(&r, h);
            if (mc_rng_below(&r, 4) == 0) {
                mc_sdepth_remove(&f.s, x, y);
                model_remove(&f, x, y);
            } else {
                /* few distinct depths, so that ties happen */
                const uint16_t z = (uint16_t)(mc_rng_below(&r, 2) ? mc_rng_below(&r, 8) : mc_rng_below(&r, EMPTY_D));
                const uint8_t c = (uint8_t)mc_rng_below(&r, 256);
                const unsigned i = y * w + x;
                const int want = !f.in[i] || z < f.md[i];
                if (f.s.matched && mc_rng_below(&r, 4)) {
                    const uint32_t m = mc_rng_below(&r, 2) ? mc_rng_next(&r) : 0;
                    assert_int_equal(mc_sdepth_insert_matched(&f.s, x, y, z, c, m), want);
                    model_insert_matched(&f, x, y, z, c, m != 0);
                } else {
                    assert_int_equal(mc_sdepth_insert(&f.s, x, y, z, c), want);
                    model_insert(&f, x, y, z, c);
                }
            }
        }
        frame_check(&f);
        for (int q = 0; q < 50; q++) {
            unsigned i0 = mc_rng_below(&r, w), i1 = mc_rng_below(&r, w), j0 = mc_rng_below(&r, h), j1 = mc_rng_below(&r, h);
            if (i0 > i1) { unsigned t = i0; i0 = i1; i1 = t; }
            if (j0 > j1) { unsigned t = j0; j0 = j1; j1 = t; }
            int any = 0;
            uint32_t far = 0;
            for (unsigned y = j0; y <= j1; y++)
                for (unsigned x = i0; x <= i1; x++)
                    if (f.in[y * w + x]) any = 1, far = f.md[y * w + x] > far ? f.md[y * w + x] : far;
            if (mc_sdepth_any(&f.s, i0, i1, j0, j1) != any)
                fail_msg("%ux%u: any(%u..%u, %u..%u) = %d, scan %d", w, h, i0, i1, j0, j1, !any, any);
            /* from the farthest entry's depth, one more, and a random depth */
            const uint32_t zs[3] = {far, far + 1u, mc_rng_below(&r, EMPTY_D + 1u)};
            for (int k = 0; k < 3; k++) {
                const int want = any && far >= zs[k];
                if (mc_sdepth_any_from(&f.s, i0, i1, j0, j1, zs[k]) != want)
                    fail_msg("%ux%u: any_from(%u..%u, %u..%u, %u) = %d, scan %d", w, h, i0, i1, j0, j1, (unsigned)zs[k], !want, want);
            }
        }
        if (mc_rng_below(&r, 3) == 0) {
            /* clear touches the pixels in use only: mark the others, they must keep the mark */
            for (unsigned i = 0; i < w * h; i++)
                if (!f.in[i]) f.depth[i] = 7, f.color[i] = 9;
            mc_sdepth_clear(&f.s);
            for (unsigned i = 0; i < w * h; i++) {
                if (!f.in[i]) {
                    assert_int_equal(f.depth[i], 7);
                    assert_int_equal(f.color[i], 9);
                    f.depth[i] = EMPTY_D, f.color[i] = EMPTY_C;
                }
                model_remove(&f, i % w, i / w);
            }
            frame_check(&f);
        }
    }
    frame_free(&f);
}

static void test_ops_1x1(void **state) { (void)state; ops_on(1, 1, 400, 1); }
static void test_ops_31x7(void **state) { (void)state; ops_on(31, 7, 200, 2); }
static void test_ops_64x5(void **state) { (void)state; ops_on(64, 5, 200, 3); }
static void test_ops_97x13(void **state) { (void)state; ops_on(97, 13, 100, 4); }
static void test_ops_1100x3(void **state) { (void)state; ops_on(1100, 3, 60, 5); }

static void test_init_errors(void **state)
{
    (void)state;
    mc_sdepth s;
    uint32_t bits[64];
    uint16_t d[64];
    assert_int_equal(mc_sdepth_init(&s, 8, 8, 0, d, 0, 1, 0), MC_ERR_ARG);
    assert_int_equal(mc_sdepth_init(&s, 8, 8, bits, 0, 0, 1, 0), MC_ERR_ARG);
    assert_int_equal(mc_sdepth_init(0, 8, 8, bits, d, 0, 1, 0), MC_ERR_ARG);
    assert_int_equal(mc_sdepth_init(&s, 0, 8, bits, d, 0, 1, 0), MC_ERR_SIZE);
    assert_int_equal(mc_sdepth_init(&s, 8, 0, bits, d, 0, 1, 0), MC_ERR_SIZE);
    /* no colours: entries keep depths only */
    assert_int_equal(mc_sdepth_init(&s, 8, 8, bits, d, 0, 1000, 0), MC_OK);
    assert_int_equal(mc_sdepth_insert(&s, 3, 4, 10, 5), 1);
    assert_int_equal(d[4 * 8 + 3], 10);
    mc_sdepth_remove(&s, 3, 4);
    assert_int_equal(d[4 * 8 + 3], 1000);
    assert_int_equal(mc_sdepth_count(&s), 0);
}

/* ---- lines ------------------------------------------------------------------------------------ */

static int32_t rnd_coord(mc_rng *r, unsigned side)
{
    switch (mc_rng_below(r, 6)) {
    case 0: return (int32_t)mc_rng_below(r, 2 * side + 40) - (int32_t)side / 2 - 20;
    case 1: return (int32_t)mc_rng_below(r, 4000) - 2000;
    case 2: return mc_rng_below(r, 2) ? MC_LINE_COORD_MAX - (int32_t)mc_rng_below(r, 3) : -MC_LINE_COORD_MAX + (int32_t)mc_rng_below(r, 3);
    default: return (int32_t)mc_rng_below(r, side);
    }
}

static void lines_on(unsigned w, unsigned h, int count, uint64_t seed)
{
    mc_rng r;
    mc_rng_seed(&r, seed, 7);
    frame f;
    frame_new(&f, w, h);
    uint8_t *tc = f.t.color, *edges = malloc(w * h);
    uint16_t *td = f.t.depth;
    assert_non_null(edges);
    /* without matched bits kept, the matching walk draws nothing */
    mc_line_vertex a0 = {0, 0, 0}, b0 = {(int32_t)w - 1, (int32_t)h - 1, 0};
    assert_int_equal(mc_track_line(&f.s, a0, b0, 1, 0, edges, 0xFF), 0);
    for (int n = 0; n < count; n++) {
        mc_line_vertex a, b;
        a.x = rnd_coord(&r, w), a.y = rnd_coord(&r, h), b.x = rnd_coord(&r, w), b.y = rnd_coord(&r, h);
        if (mc_rng_below(&r, 8) == 0) b.x = a.x + (int32_t)mc_rng_below(&r, 3) - 1, b.y = a.y;
        a.z = mc_rng_below(&r, 2) ? mc_rng_below(&r, 0x10000) : mc_rng_below(&r, 300);
        b.z = mc_rng_below(&r, 2) ? mc_rng_below(&r, 0x10000) : mc_rng_below(&r, 300);
        const uint16_t off = (uint16_t)(mc_rng_below(&r, 2) ? mc_rng_below(&r, 40) : mc_rng_below(&r, 0x10000));
        const uint8_t c = (uint8_t)mc_rng_below(&r, 200);
        /* mc_line, no depth test, depths written, into a target marked empty */
        for (unsigned i = 0; i < w * h; i++) tc[i] = 255, td[i] = MC_DEPTH_EMPTY;
        mc_line_style st = {0, MC_LINE_NO_DEPTH_TEST | MC_LINE_WRITE_DEPTH};
        const uint32_t want = mc_line(&f.t, a, b, c, &st);
        /* the second half keeps matched bits; most of its lines are matched against an edge image
         * of random codes (0: none, else 1 + bin) at a random bin and tolerance */
        if (n == count / 2) frame_keep_matched(&f);
        const int matching = f.s.matched && mc_rng_below(&r, 4);
        const uint8_t want_bins = (uint8_t)mc_rng_below(&r, 256);
        if (matching)
            for (unsigned i = 0; i < w * h; i++) edges[i] = (uint8_t)(mc_rng_below(&r, 2) ? 0 : mc_rng_below(&r, 256));
        const uint32_t got = matching ? mc_track_line(&f.s, a, b, c, off, edges, want_bins)
                                      : mc_line_sdepth(&f.s, a, b, c, off);
        if (got != want) fail_msg("line (%d,%d)-(%d,%d) on %ux%u: %u pixels, mc_line %u", a.x, a.y, b.x, b.y, w, h, got, want);
        uint32_t drawn = 0;
        for (unsigned i = 0; i < w * h; i++)
            if (tc[i] != 255) {
                drawn++;
                const uint16_t zt = (uint16_t)(td[i] > off ? td[i] - off : 0);
                const int m = matching && (edges[i] & want_bins);
                model_insert_matched(&f, i % w, i / w, zt, c, m);
            }
        assert_int_equal(drawn, want);
        if (n % 16 == 15 || n == count - 1) frame_check(&f);
        if (mc_rng_below(&r, 10) == 0) frame_clear(&f);
    }
    free(edges);
    frame_free(&f);
}

static void test_lines_33x17(void **state) { (void)state; lines_on(33, 17, 20000, 21); }
static void test_lines_320x240(void **state) { (void)state; lines_on(320, 240, 1000, 22); }
static void test_lines_1100x9(void **state) { (void)state; lines_on(1100, 9, 300, 23); }

/* ---- the face pass ------------------------------------------------------------------------------ */

static void random_triangle(mc_rng *r, unsigned w, unsigned h, mc_raster_vertex v[3])
{
    const unsigned kind = mc_rng_below(r, 5);
    const int32_t cx = (int32_t)mc_rng_below(r, 16 * w), cy = (int32_t)mc_rng_below(r, 16 * h);
    const int32_t spread = kind == 0 ? 24 : kind == 1 ? 80 : kind == 2 ? 400 : kind == 3 ? 16 * (int32_t)(w + h) : 1 << 21;
    for (int k = 0; k < 3; k++) {
        v[k].x = cx + (int32_t)mc_rng_below(r, 2u * (uint32_t)spread + 1u) - spread;
        v[k].y = cy + (int32_t)mc_rng_below(r, 2u * (uint32_t)spread + 1u) - spread;
        v[k].z = mc_rng_below(r, 2) ? 100 + mc_rng_below(r, 400) : mc_rng_below(r, MC_DEPTH_EMPTY - 1u);
    }
}

/* One face pass over f's entries by triangle v (drawn into f's target first, with flags), pushed
 * back by off: f's model loses the entries the triangle covers at a depth not greater than theirs
 * less off, and the pass, one of mc_raster_triangle_hide, _offset and _box (a third each with no
 * offset; _box given the box mc_raster_centres takes, a triangle without one hiding nothing), must
 * empty as many (frame_check compares the rest). Returns how many it emptied. */
static uint32_t hide_checked(mc_rng *r, frame *f, const mc_raster_vertex v[3], unsigned flags, uint32_t off,
                             const char *what)
{
    const unsigned w = f->s.width, h = f->s.height;
    uint32_t want = 0;
    for (unsigned i = 0; i < w * h; i++)
        if (f->t.color[i] && f->in[i] && f->md[i] >= off && f->t.depth[i] <= f->md[i] - off) {
            model_remove(f, i % w, i / w);
            want++;
        }
    const uint32_t way = off ? 1u : mc_rng_below(r, 3);
    mc_raster_box box;
    const uint32_t got = way == 1u   ? mc_raster_triangle_hide_offset(&f->s, v, flags, off)
                         : way == 0u ? mc_raster_triangle_hide(&f->s, v, flags)
                         : mc_raster_centres(v, w, h, &box) ? mc_raster_triangle_hide_box(&f->s, v, flags, &box)
                                                            : 0u;
    if (got != want)
        fail_msg("triangle (%d,%d,%u) (%d,%d,%u) (%d,%d,%u) offset %u on %ux%u%s: %u emptied, want %u", v[0].x, v[0].y,
                 v[0].z, v[1].x, v[1].y, v[1].z, v[2].x, v[2].y, v[2].z, (unsigned)off, w, h, what, got, want);
    return got;
}

static void hide_on(unsigned w, unsigned h, int count, uint64_t seed)
{
    mc_rng r;
    mc_rng_seed(&r, seed, 9);
    frame f;
    frame_new(&f, w, h);
    uint8_t *tc = f.t.color;
    uint16_t *td = f.t.depth;
    uint32_t emptied_total = 0;
    for (int n = 0; n < count; n++) {
        /* now and then a fresh start (entries nearer than any face pile up), then a sprinkle of
         * entries, sometimes dense, sometimes none in most blocks */
        if (n % 8 == 0) frame_clear(&f);
        if (n == count / 2) frame_keep_matched(&f);   /* the second half keeps matched bits */
        const unsigned fill = mc_rng_below(&r, 3) == 0 ? w * h / 2u : mc_rng_below(&r, w * h / 16u + 2u);
        for (unsigned k = 0; k < fill; k++) {
            const unsigned x = mc_rng_below(&r, w), y = mc_rng_below(&r, h);
            const uint16_t z = (uint16_t)(mc_rng_below(&r, 2) ? 100 + mc_rng_below(&r, 400) : mc_rng_below(&r, EMPTY_D));
            if (f.s.matched) {
                const uint32_t m = mc_rng_below(&r, 2);
                mc_sdepth_insert_matched(&f.s, x, y, z, 1, m);
                model_insert_matched(&f, x, y, z, 1, (int)m);
            } else {
                mc_sdepth_insert(&f.s, x, y, z, 1);
                model_insert(&f, x, y, z, 1);
            }
        }
        mc_raster_vertex v[3];
        random_triangle(&r, w, h, v);
        const unsigned flags = mc_rng_below(&r, 2) ? MC_RASTER_CULL_BACK : 0;
        for (unsigned i = 0; i < w * h; i++) tc[i] = 0, td[i] = MC_DEPTH_EMPTY;
        mc_raster_triangle(&f.t, v, 1, flags);
        /* a third of the faces pushed back by an offset (polygon offset) */
        const uint32_t off = mc_rng_below(&r, 3) ? 0 : mc_rng_below(&r, 2) ? mc_rng_below(&r, 40) : mc_rng_below(&r, 70000);
        emptied_total += hide_checked(&r, &f, v, flags, off, "");
        frame_check(&f);
    }
    /* the test is worth its time only if triangles did hide entries */
    assert_true(4u * emptied_total > (uint32_t)count);
    print_message("# info: %ux%u: %d triangles emptied %u entries\n", w, h, count, emptied_total);
    frame_free(&f);
}

/* Entries at the face's own depth: the triangle drawn into an empty target first, then entries at
 * pixels it covers, each at its depth there plus the offset plus -1, 0 or 1 (a third of the
 * triangles flat, every corner at one depth), so that every entry lies on the boundary between
 * emptied (0, 1) and kept (-1). Now and then also every pixel it does not cover, at depth 0 (nearer
 * than any face), which stays. */
static void hide_at_face_on(unsigned w, unsigned h, int count, uint64_t seed)
{
    mc_rng r;
    mc_rng_seed(&r, seed, 11);
    frame f;
    frame_new(&f, w, h);
    uint8_t *tc = f.t.color;
    uint16_t *td = f.t.depth;
    uint32_t emptied_total = 0, kept_total = 0;
    for (int n = 0; n < count; n++) {
        mc_raster_vertex v[3];
        random_triangle(&r, w, h, v);
        if (mc_rng_below(&r, 3) == 0) v[1].z = v[2].z = v[0].z;
        const unsigned flags = mc_rng_below(&r, 2) ? MC_RASTER_CULL_BACK : 0;
        const uint32_t off = mc_rng_below(&r, 2) ? 0 : mc_rng_below(&r, 40);
        for (unsigned i = 0; i < w * h; i++) tc[i] = 0, td[i] = MC_DEPTH_EMPTY;
        mc_raster_triangle(&f.t, v, 1, flags);
        frame_clear(&f);
        const int nearer = mc_rng_below(&r, 4) == 0;
        for (unsigned i = 0; i < w * h; i++) {
            const unsigned x = i % w, y = i / w;
            if (tc[i]) {
                const uint32_t z = td[i] + off + mc_rng_below(&r, 3);
                if (z >= 1u && z - 1u < EMPTY_D) mc_sdepth_insert(&f.s, x, y, (uint16_t)(z - 1u), 1), model_insert(&f, x, y, (uint16_t)(z - 1u), 1);
            } else if (nearer && v[0].z > 0 && v[1].z > 0 && v[2].z > 0) {
                mc_sdepth_insert(&f.s, x, y, 0, 1), model_insert(&f, x, y, 0, 1);
            }
        }
        const uint32_t entries = f.s.in_use, got = hide_checked(&r, &f, v, flags, off, ", entries at its depth");
        emptied_total += got, kept_total += entries - got;
        frame_check(&f);
    }
    /* both sides of the boundary were met often */
    assert_true(emptied_total > (uint32_t)count && kept_total > (uint32_t)count / 2u);
    print_message("# info: %ux%u: %d triangles over entries at their depth: %u emptied, %u kept\n", w, h, count,
                  emptied_total, kept_total);
    frame_free(&f);
}

static void test_hide_9x7(void **state) { (void)state; hide_on(9, 7, 30000, 31); }
static void test_hide_67x45(void **state) { (void)state; hide_on(67, 45, 8000, 32); }
static void test_hide_320x240(void **state) { (void)state; hide_on(320, 240, 500, 33); }
static void test_hide_1100x7(void **state) { (void)state; hide_on(1100, 7, 2000, 34); }
static void test_hide_at_face_17x13(void **state) { (void)state; hide_at_face_on(17, 13, 20000, 35); }
static void test_hide_at_face_320x240(void **state) { (void)state; hide_at_face_on(320, 240, 400, 36); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_errors), cmocka_unit_test(test_ops_1x1),      cmocka_unit_test(test_ops_31x7),
        cmocka_unit_test(test_ops_64x5),    cmocka_unit_test(test_ops_97x13),    cmocka_unit_test(test_ops_1100x3),
        cmocka_unit_test(test_lines_33x17), cmocka_unit_test(test_lines_320x240), cmocka_unit_test(test_lines_1100x9),
        cmocka_unit_test(test_hide_9x7),    cmocka_unit_test(test_hide_67x45),   cmocka_unit_test(test_hide_320x240),
        cmocka_unit_test(test_hide_1100x7), cmocka_unit_test(test_hide_at_face_17x13), cmocka_unit_test(test_hide_at_face_320x240),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
