/* Two streams of one mesh read whole: the mesh arrays the reader fills from each are the same bytes.
 * For a plain (version 2) and a packed (version 3) stream of one bake's mesh, without compiling the
 * bake: tests/gen/pmesh.sh runs it on a mesh too large to compile cheaply.
 *
 *   stream_same A.mcs B.mcs CAP    CAP: a receive buffer large enough for either (budget.json
 *       stream.buffer); prints one "ok ..." or "FAIL ..." line, exits non-zero on a failure
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/stream.h>
#include "mesh_arrays.h"

static const mc_pmesh *read_whole(const char *path, mc_stream *s, uint32_t cap, unsigned *version)
{
    FILE *f = fopen(path, "rb");
    if (!f) return perror(path), NULL;
    fseek(f, 0, SEEK_END);
    const uint32_t n = (uint32_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *file = malloc(n), *buf = malloc(cap);
    if (!file || !buf || fread(file, 1, n, f) != n) return fclose(f), fprintf(stderr, "cannot read %s\n", path), NULL;
    fclose(f);
    *version = n > 4 ? file[4] : 0;
    mc_stream_init(s, buf, cap);
    if (mc_stream_feed(s, file, n) != MC_STREAM_OK || mc_stream_end(s) != MC_STREAM_OK || !mc_stream_pmesh(s) ||
        !mc_stream_pmesh(s)->opposite) {
        printf("FAIL %s: %s at byte %u, or no whole mesh part\n", path, mc_stream_error_name(s->error), s->error_at);
        return NULL;
    }
    free(file);
    return mc_stream_pmesh(s);
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: stream_same A.mcs B.mcs CAP\n");
        return 2;
    }
    const uint32_t cap = (uint32_t)strtoul(argv[3], NULL, 10);
    static mc_stream sa, sb;
    unsigned va, vb;
    const mc_pmesh *a = read_whole(argv[1], &sa, cap, &va), *b = read_whole(argv[2], &sb, cap, &vb);
    if (!a || !b) return 1;
    if (a->vertices != b->vertices || a->base_vertices != b->base_vertices || a->faces != b->faces ||
        a->edges != b->edges || a->index_bytes != b->index_bytes || a->half_bytes != b->half_bytes) {
        printf("FAIL the two meshes' counts or widths differ\n");
        return 1;
    }
    uint32_t record;
    uint64_t bytes;
    const char *differs = mesh_arrays_differ(a, b, &record, &bytes);
    if (differs) {
        printf("FAIL %s record %u differs\n", differs, record);
        return 1;
    }
    printf("ok same: versions %u and %u, %u vertices (%u-byte indices), %u faces: %llu bytes of mesh arrays equal\n", va,
           vb, a->vertices, a->index_bytes, a->faces, (unsigned long long)bytes);
    return 0;
}
