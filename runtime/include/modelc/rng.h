/* A seeded, deterministic random number generator: PCG32 (O'Neill, "PCG: A Family of Simple Fast
 * Space-Efficient Statistically Good Algorithms for Random Number Generation", 2014), the XSH RR
 * output of a 64-bit linear congruential state, exactly as the reference pcg_basic.c.
 *
 * Promise: the same seed and stream give the same numbers on every compiler and architecture
 * (integer arithmetic modulo 2^64 only, no floating point); mc_rng_seed(r, 42, 54) then mc_rng_next
 * gives the reference implementation's published demo sequence 0xa15c02b7, 0x7b47f409, ...
 * (tests/unit/test_rng.c). Different streams give independent sequences from the same seed.
 * mc_rng_below(r, n) is uniform over 0..n-1 with no modulo bias. No heap, no global state: the
 * caller owns the mc_rng. Header only, freestanding.
 */
#ifndef MODELC_RNG_H
#define MODELC_RNG_H

#include <stdint.h>

typedef struct mc_rng {
    uint64_t state;
    uint64_t inc;   /* odd: selects the stream */
} mc_rng;

static inline uint32_t mc_rng_next(mc_rng *r)
{
    const uint64_t old = r->state;
    r->state = old * 6364136223846793005u + r->inc;
    const uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    const uint32_t rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

static inline void mc_rng_seed(mc_rng *r, uint64_t seed, uint64_t stream)
{
    r->state = 0;
    r->inc = (stream << 1) | 1u;
    (void)mc_rng_next(r);
    r->state += seed;
    (void)mc_rng_next(r);
}

/* Uniform in 0..n-1 for n >= 1 (0 for n = 0): draws below 2^32 mod n are rejected, so every value
 * has the same count of accepted draws. */
static inline uint32_t mc_rng_below(mc_rng *r, uint32_t n)
{
    if (n == 0) return 0;
    const uint32_t threshold = (0u - n) % n;
    for (;;) {
        const uint32_t v = mc_rng_next(r);
        if (v >= threshold) return v % n;
    }
}

#endif
