/* libFuzzer target: the stream reader (runtime/src/stream.c, stream_mesh.c) on any bytes, then the point
 * renderer on whatever octree the reader takes and the mesh renderers on whatever mesh (shaded at its
 * level, and lines once it has its adjacency). The first byte chooses how: bit 0 set rewrites every CRC to match
 * (tests/stream/forge.h), so that the checks behind the CRCs are reached; bits 1..3 the size of the
 * pieces fed (1 byte up to the whole). Every depth the reader offers is then drawn at three views
 * into a small target. A crash or a sanitizer report is a finding; so is a reader that offers a depth
 * deeper than its header's, or a stream taken whole whose octree is not as deep as its header says or
 * whose mesh is not whole.
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
#include "../../runtime/front/common/mesh_frame.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define CAP (1u << 20)
static uint8_t work[CAP], buf[CAP];
static uint8_t fb[64 * 48];
static uint16_t zb[64 * 48];
/* a mesh's level of detail and line memory: the most vertices and faces a CAP-byte stream can hold */
static uint32_t anc[CAP / 6];
static uint8_t facing[MC_MESH_LINES_BYTES(CAP / 6)];
static uint8_t nbr[MC_PMESH_NEIGHBOUR_BYTES(CAP / 6, 4)];

static mc_view view_of(int view)
{
    mc_view v = mc_view_default();
    v.yaw = view * 1365;
    v.pitch = view * 500;
    v.zoom = 65536 << view;
    v.projection = view == 2 ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    return v;
}

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
            const mc_view v = view_of(view);
            mc_clear(&t);
            if (mc_octree_render(o, &v, d, NULL, &t, NULL, NULL, NULL) != MC_OK) abort();
        }
    const mc_pmesh *pm = mc_stream_pmesh(&s);
    const uint32_t level = mc_stream_mesh_level(&s);
    if (!pm != !level || (pm && (level < pm->base_vertices || level > pm->vertices))) abort();
    if (end == MC_STREAM_OK && s.has_mesh && (!pm || level != pm->vertices || !pm->opposite)) abort();
    if (pm) {
        mc_pmesh_lod lod;
        mc_pmesh_lod_init(&lod, pm, anc);
        /* with the adjacency, the level's neighbour table kept through the splits and collapses too */
        if (pm->opposite && pm->faces <= CAP / 6) mc_pmesh_lod_neighbours(&lod, nbr);
        if (mc_pmesh_lod_set(&lod, level) != level) abort();
        memset(facing, 0, MC_MESH_LINES_BYTES(pm->faces));
        for (int view = 0; view < 3; view++) {
            const mc_view v = view_of(view);
            for (int style = 1; style <= (pm->opposite ? 3 : 1); style++)
                if (mc_front_mesh_frame(&lod, facing, NULL, NULL, &v, (mc_front_style)style, &t, NULL) != MC_OK) abort();
        }
        mc_pmesh_lod_set(&lod, pm->base_vertices);   /* and back: every collapse the splits allow */
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
