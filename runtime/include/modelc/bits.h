/* Bit helpers: population count, lowest set bit, leading zeros.
 *
 * Promise: every function gives the same result on every compiler and architecture. Where the
 * compiler has a builtin (GCC, Clang) it is used (for the population count, only where the target
 * has the instruction), else portable C99 does the same work. The
 * functions are forced inline (MC_ALWAYS_INLINE), so a hot loop that calls them compiles as if it
 * had written the operation itself. Header only, freestanding.
 *
 *   mc_popcount8(m)   set bits of a byte, from a 256-entry table (one load: cheaper than the
 *                     builtin on cores without a popcount instruction, and the same everywhere)
 *   MC_POPCOUNT8(n)   the same as a constant expression, for case labels and constant folding
 *   mc_popcount32(v)  set bits of a 32-bit word
 *   mc_ctz(m)         index of the lowest set bit of m; m must not be 0
 *   mc_ctz64(m)       the same for a 64-bit m, as a 64-bit value (ready to index with)
 *   mc_clz32(v)       leading zero bits of a 32-bit word; 32 for 0
 *   mc_fit_shift(m, b) the least s with m >> s < 2^b, for m < 2^(b + 32): the right shift that keeps
 *                     a quantity's b leading bits (a normal scaled to fit 32-bit products)
 */
#ifndef MODELC_BITS_H
#define MODELC_BITS_H

#include <stdint.h>

#if defined(__GNUC__) || defined(__clang__)
#define MC_ALWAYS_INLINE static inline __attribute__((always_inline))
#define MC_NOINLINE __attribute__((noinline))   /* a rare path kept out of a hot loop's registers, or code kept once */
#else
#define MC_ALWAYS_INLINE static inline
#define MC_NOINLINE
#endif

/* MC_BITS_BUILTINS: 1 (default with GCC and Clang) takes the compiler's builtins, 0 the portable
 * C99 below; the unit tests build both. MC_BITS_ASM: 1 (default with the builtins on x86-64) takes
 * mc_ctz64 as one instruction of inline assembly, 0 the builtin. */
#ifndef MC_BITS_BUILTINS
#if defined(__GNUC__) || defined(__clang__)
#define MC_BITS_BUILTINS 1
#else
#define MC_BITS_BUILTINS 0
#endif
#endif
#if MC_BITS_BUILTINS != 0 && MC_BITS_BUILTINS != 1
#error "MC_BITS_BUILTINS must be 0 (portable C99) or 1 (GCC or Clang builtins)"
#endif
#if MC_BITS_BUILTINS && !(defined(__GNUC__) || defined(__clang__))
#error "MC_BITS_BUILTINS=1 needs GCC's or Clang's builtins"
#endif
#ifndef MC_BITS_ASM
#if MC_BITS_BUILTINS && defined(__x86_64__)
#define MC_BITS_ASM 1
#else
#define MC_BITS_ASM 0
#endif
#endif
#if MC_BITS_ASM && !(MC_BITS_BUILTINS && defined(__x86_64__))
#error "MC_BITS_ASM=1 needs MC_BITS_BUILTINS=1 on x86-64"
#endif

#define MC_POPCOUNT8(n) (((n) & 1) + ((n) >> 1 & 1) + ((n) >> 2 & 1) + ((n) >> 3 & 1) + \
                         ((n) >> 4 & 1) + ((n) >> 5 & 1) + ((n) >> 6 & 1) + ((n) >> 7 & 1))

/* static: each translation unit that counts bits has its own copy, which a compiler places next to
 * its code; one that does not emits nothing */
static const uint8_t mc_popcount8_table[256] = {
#define MC_B2(n) n, n + 1, n + 1, n + 2
#define MC_B4(n) MC_B2(n), MC_B2(n + 1), MC_B2(n + 1), MC_B2(n + 2)
#define MC_B6(n) MC_B4(n), MC_B4(n + 1), MC_B4(n + 1), MC_B4(n + 2)
    MC_B6(0), MC_B6(1), MC_B6(1), MC_B6(2)
#undef MC_B2
#undef MC_B4
#undef MC_B6
};

/* m in 0..255. A macro, not a function: nested in another inline call's argument, a function call
 * changes GCC's instruction scheduling around it. */
#define mc_popcount8(m) ((unsigned)mc_popcount8_table[(m)])

MC_ALWAYS_INLINE unsigned mc_popcount32(uint32_t v)
{
    /* the builtin only where it is one instruction: elsewhere (x86-64 without -mpopcnt, every
     * Cortex-M) it is a call into the compiler's library, slower than the arithmetic below */
#if MC_BITS_BUILTINS && defined(__POPCNT__)
    return (unsigned)__builtin_popcountl((unsigned long)v);
#else
    v = v - ((v >> 1) & 0x55555555u);
    v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
    v = (v + (v >> 4)) & 0x0F0F0F0Fu;
    return (unsigned)((v * 0x01010101u) >> 24);
#endif
}

/* unsigned: used as an index without sign extension */
MC_ALWAYS_INLINE unsigned mc_ctz(unsigned m)
{
#if MC_BITS_BUILTINS
    return (unsigned)__builtin_ctz(m);
#else
    unsigned k = 0;
    while (!(m & 1u)) { m >>= 1; k++; }
    return k;
#endif
}

MC_ALWAYS_INLINE uint64_t mc_ctz64(uint64_t m)
{
#if MC_BITS_ASM
    /* the instruction alone: GCC pads __builtin_ctzll with a register clear and a sign extension of
     * its int result, two instructions a leaf in the renderer's squares loop. rep bsf is tzcnt where
     * the CPU has it and bsf elsewhere, the same for m != 0 */
    uint64_t k;
    __asm__("rep; bsfq %1, %0" : "=r"(k) : "r"(m) : "cc");
    return k;
#elif MC_BITS_BUILTINS
    return (uint64_t)__builtin_ctzll(m);
#else
    const uint32_t lo = (uint32_t)m;
    return lo ? mc_ctz(lo) : 32u + mc_ctz((unsigned)(m >> 32));
#endif
}

MC_ALWAYS_INLINE unsigned mc_clz32(uint32_t v)
{
    if (v == 0) return 32;   /* the builtin leaves 0 undefined */
#if MC_BITS_BUILTINS
    return (unsigned)__builtin_clzl((unsigned long)v) - (unsigned)(8 * sizeof(unsigned long) - 32);
#else
    unsigned n = 0;
    while (!(v & 0x80000000u)) { v <<= 1; n++; }
    return n;
#endif
}

MC_ALWAYS_INLINE unsigned mc_fit_shift(uint64_t m, unsigned b)
{
    const uint32_t top = (uint32_t)(m >> b);
    return top ? 32u - mc_clz32(top) : 0u;
}

#endif
