/* libFuzzer target: the stream reader (runtime/src/stream.c) on any bytes, then the point renderer on
 * whatever the reader takes. The first byte chooses how: bit 0 set rewrites every CRC to match
 * (tests/stream/forge.h), so that the checks behind the CRCs are reached; bits 1..3 the size of the
 * pieces fed (1 byte up to the whole). Every depth the reader offers is then drawn at three views
 * into a small target. A crash or a sanitizer report is a finding; so is a reader that offers a depth
 * deeper than its header's, or a stream taken whole whose octree is not as deep as its header says.
 *
 * Built with -DMC_FUZZ_STREAM_MAIN instead of libFuzzer, main replays the files it is given
 * (tests/stream/suite.sh: tests/fuzz/regress/stream/). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/modelc.h>
#include <modelc/stream.h>
#include "../stream/forge.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CAP (1u << 20)
static uint8_t work[CAP], buf[CAP];
static uint8_t fb[64 * 48];
static uint16_t zb[64 * 48];

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size - 1 > CAP) return 0;
    const unsigned how = data[0];
    const uint32_t n = (uint32_t)(size - 1);
    memcpy(work, data + 1, n);
    if (how & 1) forge_crcs(work, n);
    const uint32_t piece = 1u << (3 * ((how >> 1) & 7));   /* 1, 8, 64, ... 2^21 bytes */
    mc_stream s;
    mc_stream_init(&s, buf, CAP);
    for (uint32_t at = 0; at < n;) {
        const uint32_t k = n - at < piece ? n - at : piece;
        if (mc_stream_feed(&s, work + at, k) != MC_STREAM_OK) break;
        at += k;
    }
    const int end = mc_stream_end(&s);
    const mc_octree *o = mc_stream_octree(&s);
    if (o && (o->depth != mc_stream_depth(&s) || o->depth > s.depth)) abort();
    if (end == MC_STREAM_OK && (!o || o->depth != s.depth)) abort();
    const mc_target t = {fb, zb, 64, 48};
    for (unsigned d = 1; o && d <= o->depth; d++)
        for (int view = 0; view < 3; view++) {
            mc_view v = mc_view_default();
            v.yaw = view * 1365;
            v.pitch = view * 500;
            v.zoom = 65536 << view;
            v.projection = view == 2 ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
            mc_clear(&t);
            if (mc_octree_render(o, &v, d, NULL, &t, NULL, NULL, NULL) != MC_OK) abort();
        }
    return 0;
}

#ifdef MC_FUZZ_STREAM_MAIN
int main(int argc, char **argv)
{
    static uint8_t in[CAP + 1];
    for (int i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        if (!f) { perror(argv[i]); return 2; }
        const size_t n = fread(in, 1, sizeof in, f);
        fclose(f);
        LLVMFuzzerTestOneInput(in, n);
    }
    printf("replayed %d inputs\n", argc - 1);
    return 0;
}
#endif
