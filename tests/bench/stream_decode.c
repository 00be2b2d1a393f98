/* The stream side of the progressive-mesh benchmark (tests/bench/pmesh.sh): a whole stream
 * (modelc --emit stream --as both, plain or --stream-splits packed) read by mc_stream_feed in one
 * piece, then the levels of the mesh it decoded swept as pmesh_lod.c sweeps a bake's.
 *
 *   stream_decode FILE.mcs CAP ROUNDS   CAP: the receive buffer (budget.json stream.buffer); per
 *       round "ns per split read X" (the whole feed, every record checked, over the mesh's splits)
 *       and "ns per level change X" (mc_pmesh_lod_set from the base to the full level and back on
 *       the arrays the stream filled); first "version V splits S mesh bytes B" (B: the base and
 *       split records, framing included)
 *   stream_decode FILE.mcs CAP --feeds N   N feeds and nothing else, for callgrind
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/stream.h"

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e9 + t.tv_nsec;
}

static uint32_t le32(const uint8_t *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }

static int feed(mc_stream *s, uint8_t *buf, uint32_t cap, const uint8_t *file, uint32_t n)
{
    mc_stream_init(s, buf, cap);
    if (mc_stream_feed(s, file, n) != MC_STREAM_OK || mc_stream_end(s) != MC_STREAM_OK || !mc_stream_pmesh(s)) {
        fprintf(stderr, "stream_decode: %s at byte %u\n", mc_stream_error_name(s->error), s->error_at);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 4 && argc != 5) {
        fprintf(stderr, "usage: stream_decode FILE.mcs CAP ROUNDS | FILE.mcs CAP --feeds N\n");
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) { perror(argv[1]); return 2; }
    fseek(f, 0, SEEK_END);
    const uint32_t n = (uint32_t)ftell(f), cap = (uint32_t)strtoul(argv[2], NULL, 10);
    fseek(f, 0, SEEK_SET);
    uint8_t *file = malloc(n), *buf = malloc(cap);
    if (!file || !buf || fread(file, 1, n, f) != n) { fprintf(stderr, "stream_decode: cannot read %s\n", argv[1]); return 2; }
    fclose(f);
    static mc_stream s;
    if (argc == 5 && !strcmp(argv[3], "--feeds")) {
        for (int r = atoi(argv[4]); r > 0; r--)
            if (feed(&s, buf, cap, file, n)) return 1;
        printf("splits %u\n", mc_stream_pmesh(&s)->vertices - mc_stream_pmesh(&s)->base_vertices);
        return 0;
    }
    uint64_t mesh_bytes = 0, adjacency_bytes = 0;   /* the base's and the splits' records; the adjacency's */
    for (uint32_t at = MC_STREAM_HEADER_BYTES; at + 8 <= n; at += MC_STREAM_RECORD_BYTES + le32(file + at + 4)) {
        if (file[at] == 5 || file[at] == 6 || file[at] == 8) mesh_bytes += MC_STREAM_RECORD_BYTES + le32(file + at + 4);
        if (file[at] == 7 || file[at] == 9) adjacency_bytes += MC_STREAM_RECORD_BYTES + le32(file + at + 4);
    }
    if (feed(&s, buf, cap, file, n)) return 1;
    const mc_pmesh *pm = mc_stream_pmesh(&s);
    const uint32_t splits = pm->vertices - pm->base_vertices;
    printf("version %u splits %u mesh bytes %llu adjacency bytes %llu\n", file[4], splits, (unsigned long long)mesh_bytes,
           (unsigned long long)adjacency_bytes);
    uint32_t *anc = malloc(MC_PMESH_LOD_BYTES(pm->vertices, 4));
    if (!anc) return 2;
    for (int r = atoi(argv[3]); r > 0; r--) {
        double t0 = now_ns();
        if (feed(&s, buf, cap, file, n)) return 1;
        printf("ns per split read %.2f\n", (now_ns() - t0) / splits);
        mc_pmesh_lod lod;
        mc_pmesh_lod_init(&lod, mc_stream_pmesh(&s), anc);
        t0 = now_ns();
        mc_pmesh_lod_set(&lod, pm->vertices);
        mc_pmesh_lod_set(&lod, pm->base_vertices);
        printf("ns per level change %.2f\n", (now_ns() - t0) / (2.0 * splits));
    }
    return 0;
}
