/* The sparse depth buffer: see modelc/sdepth.h. */
#include "modelc/sdepth.h"
#include "modelc/bytes.h"

/* d[0 .. n) = v, a machine word at a time where bytes.h can (a loop of 16-bit stores is neither
 * merged nor vectorised at -O2, and the init passes over every pixel of every frame) */
static void fill16(uint16_t *d, uint16_t v, uint32_t n)
{
    uint32_t i = 0;
#if MC_WORDS
    mc_word w = v;
    w |= w << 16;
    w |= (w << 16) << 16;   /* a 64-bit word's upper half; 0 for a 32-bit word */
    uint8_t *b = (uint8_t *)(void *)d;
    for (; i + MC_WORD_BYTES / 2u <= n; i += MC_WORD_BYTES / 2u) mc_words_store(b + 2u * i, w);
#endif
    for (; i < n; i++) d[i] = v;
}

int mc_sdepth_init(mc_sdepth *s, uint16_t width, uint16_t height, uint32_t *bits, uint16_t *depth, uint8_t *color,
                   uint16_t empty_depth, uint8_t empty_color)
{
    if (!s || !bits || !depth) return MC_ERR_ARG;
    if (!width || !height || width > MC_TARGET_MAX || height > MC_TARGET_MAX) return MC_ERR_SIZE;
    s->depth = depth, s->color = color;
    s->width = width, s->height = height;
    s->blocks = (uint16_t)MC_SDEPTH_BLOCKS(width), s->row_words = (uint16_t)MC_SDEPTH_ROW_WORDS(width);
    s->used = bits, s->rows = bits + (uint32_t)height * s->blocks;
    s->matched = 0;
    s->in_use = s->in_use_matched = 0;
    s->row_lo = height, s->row_hi = 0;
    s->empty_depth = empty_depth, s->empty_color = empty_color;
    const uint32_t n = (uint32_t)width * height, words = MC_SDEPTH_WORDS(width, height);
    for (uint32_t i = 0; i < words; i++) bits[i] = 0;
    fill16(depth, empty_depth, n);
    if (color)
        for (uint32_t i = 0; i < n; i++) color[i] = empty_color;
    return MC_OK;
}

void mc_sdepth_keep_matched(mc_sdepth *s, uint32_t *matched)
{
    s->matched = matched;
    s->in_use_matched = 0;
    if (matched)
        for (uint32_t w = 0; w < (uint32_t)s->height * s->blocks; w++) matched[w] = 0;
}

void mc_sdepth_clear(mc_sdepth *s)
{
    for (uint32_t y = s->row_lo; y <= s->row_hi; y++) {
        uint32_t *rw = s->rows + y * s->row_words;
        for (uint32_t k = 0; k < s->row_words; k++) {
            for (uint32_t m = rw[k]; m; m &= ~(0x80000000u >> mc_clz32(m))) {
                const uint32_t b = 32u * k + mc_clz32(m), w = y * s->blocks + b;
                for (uint32_t u = s->used[w]; u; u &= ~(0x80000000u >> mc_clz32(u))) {
                    const uint32_t i = y * s->width + 32u * b + mc_clz32(u);
                    s->depth[i] = s->empty_depth;
                    if (s->color) s->color[i] = s->empty_color;
                }
                s->used[w] = 0;
                if (s->matched) s->matched[w] = 0;
            }
            rw[k] = 0;
        }
    }
    s->in_use = s->in_use_matched = 0;
    s->row_lo = s->height, s->row_hi = 0;
}

void mc_sdepth_forget(mc_sdepth *s)
{
    for (uint32_t y = s->row_lo; y <= s->row_hi; y++) {
        uint32_t *rw = s->rows + y * s->row_words;
        for (uint32_t k = 0; k < s->row_words; k++) {
            for (uint32_t m = rw[k]; m; m &= ~(0x80000000u >> mc_clz32(m))) {
                const uint32_t w = y * s->blocks + 32u * k + mc_clz32(m);
                s->used[w] = 0;
                if (s->matched) s->matched[w] = 0;
            }
            rw[k] = 0;
        }
    }
    s->in_use = s->in_use_matched = 0;
    s->row_lo = s->height, s->row_hi = 0;
}

void mc_sdepth_remove(mc_sdepth *s, uint32_t x, uint32_t y)
{
    const uint32_t w = y * s->blocks + (x >> 5), i = y * s->width + x, bit = 0x80000000u >> (x & 31u);
    if (s->used[w] & bit) {
        s->in_use--;
        if (s->matched && (s->matched[w] & bit)) s->in_use_matched--;
    }
    s->used[w] &= ~bit;
    if (s->matched) s->matched[w] &= ~bit;
    if (!s->used[w]) s->rows[y * s->row_words + (x >> 10)] &= ~(0x80000000u >> ((x >> 5) & 31u));
    s->depth[i] = s->empty_depth;
    if (s->color) s->color[i] = s->empty_color;
}
