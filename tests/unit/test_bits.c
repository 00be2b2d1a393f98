/* Number helpers against independent references: bits.h (popcount, lowest set bit, leading zeros)
 * and the renderer's child lists (runtime/src/child_bits.h, every mask) against bit-by-bit loops,
 * rng.h (PCG32) against the reference implementation's published demo output, chunk.h's cursor
 * against the bytes of its chunks read one by one, and bytes.h's word-wide copy, OR and clear
 * against byte loops at every alignment and length up to a few words, the bytes around each run
 * untouched.
 *
 * PCG32 reference: pcg-c-basic's pcg32-demo seeds with pcg32_srandom_r(&rng, 42u, 54u) and prints
 * 0xa15c02b7 0x7b47f409 0xba1d3330 0x83d2f293 0xbfa4784b 0xcbed606e as its first six numbers
 * (M. E. O'Neill, pcg-random.org; the same six numbers are the expected values of other ports'
 * test suites).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <cmocka.h>

#include <modelc/bits.h>
#include <modelc/bytes.h>
#include <modelc/chunk.h>
#include <modelc/rng.h>

#undef MC_LEAF_SWITCH
#define MC_LEAF_SWITCH 1   /* the table exists in the switch form only */
#include "../../runtime/src/child_bits.h"

static unsigned naive_popcount(uint32_t v)
{
    unsigned n = 0;
    for (int i = 0; i < 32; i++) n += (v >> i) & 1u;
    return n;
}

static unsigned naive_ctz(uint32_t v)
{
    unsigned i = 0;
    while (i < 32 && !((v >> i) & 1u)) i++;
    return i;
}

static unsigned naive_clz(uint32_t v)
{
    unsigned n = 0;
    for (int i = 31; i >= 0 && !((v >> i) & 1u); i--) n++;
    return n;
}

/* a fixed sequence of test words, independent of rng.h */
static uint32_t words_state = 0x12345678u;
static uint32_t next_word(void)
{
    words_state ^= words_state << 13;
    words_state ^= words_state >> 17;
    words_state ^= words_state << 5;
    return words_state;
}

static void test_bits(void **state)
{
    (void)state;
    for (unsigned m = 0; m < 256; m++) {
        assert_int_equal(mc_popcount8(m), naive_popcount(m));
        assert_int_equal(MC_POPCOUNT8(m), naive_popcount(m));
        if (m) assert_int_equal(mc_ctz(m), naive_ctz(m));
    }
    assert_int_equal(mc_clz32(0), 32);
    assert_int_equal(mc_popcount32(0), 0);
    assert_int_equal(mc_popcount32(0xFFFFFFFFu), 32);
    for (int i = 0; i < 32; i++) {
        const uint32_t b = (uint32_t)1 << i;
        assert_int_equal(mc_ctz(b), (unsigned)i);
        assert_int_equal(mc_ctz64((uint64_t)b << 32 | (uint64_t)1 << 63), 32u + (unsigned)i);
        assert_int_equal(mc_clz32(b), 31u - (unsigned)i);
        assert_int_equal(mc_clz32(b | (b - 1u)), 31u - (unsigned)i);
    }
    for (int i = 0; i < 100000; i++) {
        const uint32_t v = next_word() >> (i % 32);
        assert_int_equal(mc_popcount32(v), naive_popcount(v));
        assert_int_equal(mc_clz32(v), naive_clz(v));
        if (v) assert_int_equal(mc_ctz(v), naive_ctz(v));
        /* 64 bits: the word in either half, or both */
        const uint64_t hi = (uint64_t)v << 32, both = hi | (next_word() >> (i % 32));
        if (v) assert_int_equal(mc_ctz64(v), naive_ctz(v));
        if (v) assert_int_equal(mc_ctz64(hi), 32u + naive_ctz(v));
        if (both) assert_int_equal(mc_ctz64(both), (uint32_t)both ? naive_ctz((uint32_t)both) : 32u + naive_ctz(v));
    }
}

/* child_seq and the walk over it (child_bits.h) for every mask, against the mask's bits read one
 * by one */
static void test_child_lists(void **state)
{
    (void)state;
    for (unsigned m = 0; m < 256; m++) {
        unsigned bits[8], n = 0;
        for (unsigned k = 0; k < 8; k++)
            if (m >> k & 1u) bits[n++] = k;
        for (unsigned j = 0; j < 8; j++) {
            const unsigned want = j < n ? bits[j] + 1 : 0;
            const unsigned got = (unsigned)(child_seq[m] >> (MC_CHILD_BITS * j) & ((1u << MC_CHILD_BITS) - 1));
            if (got != want) fail_msg("child_seq[%u] slot %u of %d bits: %u, not %u", m, j, MC_CHILD_BITS, got, want);
        }
        unsigned seen = 0;
        for (child_iter s = CHILDREN(m); s; s = NEXT_CHILD(s)) {
            assert_true(seen < n);
            assert_int_equal(CHILD(s), bits[seen]);
            seen++;
        }
        assert_int_equal(seen, n);
    }
}

static void test_rng_reference(void **state)
{
    (void)state;
    static const uint32_t want[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    mc_rng r;
    mc_rng_seed(&r, 42u, 54u);
    for (int i = 0; i < 6; i++) assert_int_equal(mc_rng_next(&r), want[i]);
}

static void test_rng_streams_and_bounds(void **state)
{
    (void)state;
    mc_rng a, b, c;
    mc_rng_seed(&a, 7, 1);
    mc_rng_seed(&b, 7, 1);
    mc_rng_seed(&c, 7, 2);
    int differ = 0;
    for (int i = 0; i < 1000; i++) {
        const uint32_t x = mc_rng_next(&a);
        assert_int_equal(x, mc_rng_next(&b));   /* same seed and stream: the same numbers */
        differ += x != mc_rng_next(&c);
    }
    assert_true(differ > 990);                  /* another stream: another sequence */
    assert_int_equal(mc_rng_below(&a, 0), 0);
    assert_int_equal(mc_rng_below(&a, 1), 0);
    /* uniform over 0..5: each value within 5 % of 1/6 of 60000 draws (about 6 standard deviations) */
    unsigned count[6] = {0};
    for (int i = 0; i < 60000; i++) {
        const uint32_t v = mc_rng_below(&a, 6);
        assert_true(v < 6);
        count[v]++;
    }
    for (int k = 0; k < 6; k++) assert_true(count[k] > 9500 && count[k] < 10500);
    /* a bound just above 2^31 rejects almost half the draws and still returns values below it */
    for (int i = 0; i < 1000; i++) assert_true(mc_rng_below(&a, 0x80000001u) < 0x80000001u);
}

static void test_cursor(void **state)
{
    (void)state;
    static const uint8_t c0[] = {1, 2, 3}, c2[] = {4, 5, 6, 7, 8};
    const mc_chunk list[] = {{c0, 3}, {c0, 0}, {c2, 5}, {0, 0}};
    mc_cursor c;
    mc_cursor_init(&c, list);
    const uint8_t *p = mc_cursor_take(&c, 3);   /* a group of 3 in the first chunk */
    assert_int_equal(p[0], 1);
    assert_int_equal(p[2], 3);
    p = mc_cursor_take(&c, 2);                  /* the empty chunk is stepped over */
    assert_int_equal(p[0], 4);
    assert_int_equal(p[1], 5);
    mc_cursor_skip(&c, 2);
    assert_int_equal(*mc_cursor_take(&c, 1), 8);
    mc_cursor_init(&c, list);
    mc_cursor_skip(&c, 100);                    /* past the end: stops at the sentinel */
    assert_ptr_equal(c.p, c.end);

    mc_cursor_init_zeros(&c);                   /* the zero run: groups of up to 64 zeros, forever */
    for (int i = 0; i < 1000; i++) {
        const uint32_t n = 1u + (uint32_t)(i * 7) % MC_CHUNK_ZERO_RUN;
        p = mc_cursor_take(&c, n);
        for (uint32_t k = 0; k < n; k++) assert_int_equal(p[k], 0);
        mc_cursor_skip(&c, n);
    }
}

/* mc_bytes_copy, mc_bytes_or, mc_bytes_zero, mc_bytes_any and mc_words_load_part against byte loops: every
 * offset of both runs within a word, every length up to four words and a bit, in buffers whose bytes
 * outside the run must keep their values */
static void test_bytes(void **state)
{
    (void)state;
    enum { SIZE = 96 };
    uint8_t d[SIZE], s[SIZE], want[SIZE];
    mc_rng r;
    mc_rng_seed(&r, 0xb17e5, 3);
    for (unsigned op = 0; op < 3; op++)
        for (unsigned od = 0; od < 8; od++)
            for (unsigned os = 0; os < 8; os++)
                for (unsigned n = 0; n <= 4 * MC_WORD_BYTES + 3; n++) {
                    for (unsigned i = 0; i < SIZE; i++) d[i] = (uint8_t)mc_rng_next(&r), s[i] = (uint8_t)mc_rng_next(&r);
                    for (unsigned i = 0; i < SIZE; i++) want[i] = d[i];
                    for (unsigned i = 0; i < n; i++)
                        want[od + i] = op == 0 ? s[os + 32 + i] : op == 1 ? (uint8_t)(d[od + i] | s[os + 32 + i]) : 0;
                    if (op == 0) mc_bytes_copy(d + od, s + os + 32, n);
                    else if (op == 1) mc_bytes_or(d + od, s + os + 32, n);
                    else mc_bytes_zero(d + od, n);
                    for (unsigned i = 0; i < SIZE; i++)
                        if (d[i] != want[i]) fail_msg("op %u, offsets %u %u, length %u: byte %u is %02x, want %02x", op, od, os, n, i, d[i], want[i]);
                }
    /* mc_bytes_any: a run of zeros, then one byte set anywhere in it, or just outside either end */
    for (unsigned o = 0; o < 8; o++)
        for (unsigned n = 0; n <= 4 * MC_WORD_BYTES + 3; n++)
            for (int at = -1; at <= (int)n; at++) {
                for (unsigned i = 0; i < SIZE; i++) s[i] = 0xFF;
                for (unsigned i = 0; i < n; i++) s[o + 16 + i] = 0;
                const int inside = at >= 0 && at < (int)n;
                if (inside) s[o + 16 + (unsigned)at] = (uint8_t)(1u << (mc_rng_next(&r) & 7u));
                if (mc_bytes_any(s + o + 16, n) != inside)
                    fail_msg("mc_bytes_any: offset %u, length %u, byte %d set: %d", o, n, at, mc_bytes_any(s + o + 16, n));
            }
    for (unsigned o = 0; o < 8; o++)
        for (unsigned k = 0; k < MC_WORD_BYTES; k++) {
            for (unsigned i = 0; i < SIZE; i++) s[i] = (uint8_t)mc_rng_next(&r);
            uint64_t want_v = 0;
            for (unsigned i = 0; i < k; i++) want_v |= (uint64_t)s[o + i] << (8 * i);
            assert_true((uint64_t)mc_words_load_part(s + o, k) == want_v);
        }
}

int main(void)
{
    setvbuf(stdout, NULL, _IONBF, 0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bits),
        cmocka_unit_test(test_child_lists),
        cmocka_unit_test(test_rng_reference),
        cmocka_unit_test(test_rng_streams_and_bounds),
        cmocka_unit_test(test_cursor),
        cmocka_unit_test(test_bytes),
    };
    return cmocka_run_group_tests_name("bits", tests, NULL, NULL);
}
