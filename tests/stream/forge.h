/* What a forger of modelc streams does (tests only): rewrites the header's and every record's CRC-32
 * so that they match whatever bytes are there, so that a test reaches the reader's checks behind the
 * CRCs (runtime/include/modelc/stream.h). Walks the records by their own lengths and stops at the
 * first that does not fit. */
#ifndef MODELC_TESTS_FORGE_H
#define MODELC_TESTS_FORGE_H

#include <stdint.h>
#include <modelc/stream.h>

static void forge_put32(uint8_t *q, uint32_t v)
{
    q[0] = (uint8_t)v;
    q[1] = (uint8_t)(v >> 8);
    q[2] = (uint8_t)(v >> 16);
    q[3] = (uint8_t)(v >> 24);
}

static void forge_crcs(uint8_t *p, uint32_t len)
{
    if (len < MC_STREAM_HEADER_BYTES) return;
    forge_put32(p + 16, mc_stream_crc32(0, p, 16));
    for (uint32_t at = MC_STREAM_HEADER_BYTES; len - at >= 8;) {
        const uint32_t n = p[at + 4] | p[at + 5] << 8 | p[at + 6] << 16 | (uint32_t)p[at + 7] << 24;
        if (n > len - at - 8 || len - at - 8 - n < 4) break;
        forge_put32(p + at + 8 + n, mc_stream_crc32(0, p + at, 8 + n));
        at += 12 + n;
    }
}

#endif
