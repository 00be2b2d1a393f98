/* The two fixed-point operations too long to inline. */
#include "modelc/fixed.h"

mc_fix mc_fix_div(mc_fix a, mc_fix b)
{
    if (b == 0) return a > 0 ? MC_FIX_MAX : a < 0 ? MC_FIX_MIN : 0;
    int64_t n = (int64_t)a * MC_FIX_ONE;            /* |n| < 2^55: no overflow */
    int64_t mag_n = n < 0 ? -n : n, mag_b = b < 0 ? -(int64_t)b : b;
    int64_t q = (mag_n + mag_b / 2) / mag_b;        /* round half away from zero */
    return mc_fix_sat((n < 0) != (b < 0) ? -q : q);
}

/* Unsigned 64x64 -> 128 multiply from 32-bit halves (portable C99, no __int128 on 32-bit targets). */
static void mul_u128(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
    uint64_t al = a & 0xFFFFFFFFu, ah = a >> 32, bl = b & 0xFFFFFFFFu, bh = b >> 32;
    uint64_t ll = al * bl, lh = al * bh, hl = ah * bl, hh = ah * bh;
    uint64_t mid = (ll >> 32) + (lh & 0xFFFFFFFFu) + (hl & 0xFFFFFFFFu);
    *lo = (ll & 0xFFFFFFFFu) | (mid << 32);
    *hi = hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
}

int64_t mc_mul_shift64(int64_t a, int64_t b, int s)
{
    int neg = (a < 0) != (b < 0);
    uint64_t ua = a < 0 ? 0u - (uint64_t)a : (uint64_t)a;
    uint64_t ub = b < 0 ? 0u - (uint64_t)b : (uint64_t)b;
    uint64_t hi, lo;
    mul_u128(ua, ub, &hi, &lo);
    if (s > 0) {                                    /* add half an output unit: round half away */
        uint64_t half_hi = s > 64 ? (uint64_t)1 << (s - 65) : 0;
        uint64_t half_lo = s <= 64 ? (uint64_t)1 << (s - 1) : 0;
        uint64_t old = lo;
        lo += half_lo;
        hi += half_hi + (lo < old);
        if (s >= 64) { lo = hi >> (s - 64); hi = 0; }
        else { lo = (lo >> s) | (hi << (64 - s)); hi >>= s; }
    }
    if (hi != 0 || lo > (uint64_t)INT64_MAX) return neg ? INT64_MIN : INT64_MAX;
    return neg ? -(int64_t)lo : (int64_t)lo;
}
