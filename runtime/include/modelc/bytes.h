/* Runs of bytes a machine word at a time: for the passes over whole image rows (imgedge.c, the
 * tracker's frame buffers) that would otherwise touch every byte on its own.
 *
 * Promise: mc_bytes_copy, mc_bytes_or, mc_bytes_zero and mc_bytes_any do what their byte loops
 * would, on any alignment and any length, reading and writing only the n bytes given (copy and or:
 * the two runs must not overlap); mc_words_load_part reads only the bytes it is given. With GCC or Clang on a little-endian target they move MC_WORD_BYTES bytes per step
 * (8 where pointers are 64-bit, else 4) through a may_alias, byte-aligned word type, which is
 * neither an aliasing violation nor an unaligned-access fault (the compiler splits the access where
 * the target cannot do it unaligned); elsewhere (MC_WORDS 0) through the plain byte loops. No
 * library call at any optimisation level. Header only, freestanding.
 */
#ifndef MODELC_BYTES_H
#define MODELC_BYTES_H

#include <stdint.h>
#include "bits.h"

#if (defined(__GNUC__) || defined(__clang__)) && defined(__BYTE_ORDER__) && \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define MC_WORDS 1
#else
#define MC_WORDS 0
#endif

#if UINTPTR_MAX > 0xFFFFFFFFu
typedef uint64_t mc_word;
#define MC_WORD_BYTES 8u
#else
typedef uint32_t mc_word;
#define MC_WORD_BYTES 4u
#endif

#if MC_WORDS
typedef mc_word __attribute__((may_alias, aligned(1))) mc_word_any;
MC_ALWAYS_INLINE mc_word mc_words_load(const uint8_t *p) { return *(const mc_word_any *)(const void *)p; }
MC_ALWAYS_INLINE void mc_words_store(uint8_t *p, mc_word v) { *(mc_word_any *)(void *)p = v; }
#endif

/* The k < MC_WORD_BYTES bytes at p as a word, little-endian (byte i in bits 8i..8i+7), zero above. */
MC_ALWAYS_INLINE mc_word mc_words_load_part(const uint8_t *p, uint32_t k)
{
    mc_word v = 0;
    for (uint32_t i = 0; i < k; i++) v |= (mc_word)p[i] << (8u * i);
    return v;
}

MC_ALWAYS_INLINE void mc_bytes_copy(uint8_t *restrict d, const uint8_t *restrict s, uint32_t n)
{
    uint32_t i = 0;
#if MC_WORDS
    for (; i + MC_WORD_BYTES <= n; i += MC_WORD_BYTES) mc_words_store(d + i, mc_words_load(s + i));
#endif
    for (; i < n; i++) d[i] = s[i];
}

MC_ALWAYS_INLINE void mc_bytes_or(uint8_t *restrict d, const uint8_t *restrict s, uint32_t n)
{
    uint32_t i = 0;
#if MC_WORDS
    for (; i + MC_WORD_BYTES <= n; i += MC_WORD_BYTES) mc_words_store(d + i, mc_words_load(d + i) | mc_words_load(s + i));
#endif
    for (; i < n; i++) d[i] |= s[i];
}

MC_ALWAYS_INLINE void mc_bytes_zero(uint8_t *d, uint32_t n)
{
    uint32_t i = 0;
#if MC_WORDS
    for (; i + MC_WORD_BYTES <= n; i += MC_WORD_BYTES) mc_words_store(d + i, 0);
#endif
    for (; i < n; i++) d[i] = 0;
}

/* 1 when any of the n bytes at p is not zero, else 0 */
MC_ALWAYS_INLINE int mc_bytes_any(const uint8_t *p, uint32_t n)
{
    mc_word any = 0;
    uint32_t i = 0;
#if MC_WORDS
    for (; i + MC_WORD_BYTES <= n; i += MC_WORD_BYTES) any |= mc_words_load(p + i);
#endif
    for (; i < n; i++) any |= p[i];
    return any != 0;
}

#endif
