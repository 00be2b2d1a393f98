/* Checks a baked progressive mesh through the runtime's level of detail (runtime/src/pmesh.c).
 * Built by tests/gen/pmesh.sh with -DPM=mc_pmesh_NAME -include build/.../NAME.h and the bake's files.
 *
 *   pmesh_check levels        every level of a mesh up to 4000 vertices, else the first and last 200
 *                             and 400 spread between, visited in a shuffled order: every face present
 *                             has three distinct corners, each a vertex present at that level, and
 *                             the face count is F(n); the arrays' own invariants (subtree sizes, the
 *                             splits' parents present before them); one line "ok ..." or "not ok ..."
 *   pmesh_check faces N       the faces of level N, one line each: the corners' quantized positions
 *                             (x y z three times), in the format of modelc --dump-pmesh-level
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modelc/pmesh.h"

extern const mc_pmesh PM;

static uint32_t field(const mc_chunk *list, unsigned size, uint32_t i, unsigned at, unsigned bytes)
{
    return mc_le_index(mc_chunk_record(list, PM.record_shift, size, i) + at, bytes);
}

int main(int argc, char **argv)
{
    const mc_pmesh *pm = &PM;
    const uint32_t V = pm->vertices, V0 = pm->base_vertices, ib = pm->index_bytes;
    void *anc = malloc((size_t)V * ib + 8);
    uint32_t *rank = malloc(sizeof(uint32_t) * V), *fcount = malloc(sizeof(uint32_t) * (V + 1));
    if (!anc || !rank || !fcount) return 2;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, pm, anc);
    if (argc == 3 && !strcmp(argv[1], "faces")) {
        mc_pmesh_lod_set(&lod, (uint32_t)strtoul(argv[2], 0, 10));
        for (uint32_t f = 0; f < lod.faces; f++) {
            uint32_t c[3];
            mc_pmesh_lod_face(&lod, f, c);
            for (int k = 0; k < 3; k++) {
                const uint8_t *p = mc_chunk_record(pm->positions, pm->record_shift, 6, c[k]);
                printf("%u %u %u ", (unsigned)mc_le16(p), (unsigned)mc_le16(p + 2), (unsigned)mc_le16(p + 4));
            }
            printf("\n");
        }
        return 0;
    }
    if (argc != 2 || strcmp(argv[1], "levels")) {
        fprintf(stderr, "usage: pmesh_check levels | faces N\n");
        return 2;
    }
    /* ranks and F(n) from the arrays; the tree's invariants */
    unsigned long problems = 0;
    char first[200] = "";
#define PROBLEM(...) do { if (!problems++) snprintf(first, sizeof first, __VA_ARGS__); } while (0)
    for (uint32_t v = 0; v < V; v++) rank[v] = UINT32_MAX;
    fcount[V0] = pm->base_faces;
    for (uint32_t s = 0; s < V - V0; s++) {
        uint32_t v = field(pm->splits, ib + 1, s, 0, ib);
        uint32_t nf = mc_chunk_record(pm->splits, pm->record_shift, ib + 1, s)[ib];
        if (v >= V || rank[v] != UINT32_MAX) { PROBLEM("split %u brings back vertex %u twice or out of range", s, v); break; }
        rank[v] = V0 + s;
        if (nf < 1 || nf > 2) PROBLEM("split %u adds %u faces", s, nf);
        fcount[V0 + s + 1] = fcount[V0 + s] + nf;
    }
    if (fcount[V] != pm->faces) PROBLEM("the splits add up to %u faces, the descriptor says %u", fcount[V], pm->faces);
    uint32_t roots = 0;
    for (uint32_t v = 0; v < V && !problems; v++) {
        uint32_t parent = field(pm->tree, 2 * ib, v, 0, ib), size = field(pm->tree, 2 * ib, v, ib, ib);
        if (size < 1 || v + size > V) PROBLEM("vertex %u: subtree size %u", v, size);
        if (parent == v) {
            roots++;
            if (rank[v] != UINT32_MAX) PROBLEM("root %u is also split", v);
            rank[v] = 0;
        } else {
            uint32_t psize = field(pm->tree, 2 * ib, parent, ib, ib);
            if (parent > v || v >= parent + psize) PROBLEM("vertex %u lies outside its parent %u's subtree", v, parent);
            if (rank[v] == UINT32_MAX || rank[parent] >= rank[v]) PROBLEM("vertex %u splits before its parent %u", v, parent);
        }
    }
    if (roots != V0) PROBLEM("%u roots, the descriptor says %u base vertices", roots, V0);
    /* the levels, shuffled */
    uint32_t *levels = malloc(sizeof(uint32_t) * (V - V0 + 1)), nl = 0;
    if (!levels) return 2;
    for (uint32_t n = V0; n <= V; n++)
        if (V <= 4000 || n < V0 + 200 || n + 200 > V || (n - V0) % ((V - V0) / 400 + 1) == 0) levels[nl++] = n;
    uint64_t x = 88172645463325252ull;
    for (uint32_t i = nl; i > 1; i--) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        uint32_t j = (uint32_t)(x % i), t = levels[i - 1];
        levels[i - 1] = levels[j], levels[j] = t;
    }
    uint64_t faces_checked = 0;
    for (uint32_t i = 0; i < nl && !problems; i++) {
        uint32_t n = levels[i];
        if (mc_pmesh_lod_set(&lod, n) != n || lod.level != n) PROBLEM("level %u not set", n);
        if (lod.faces != fcount[n]) PROBLEM("level %u: %u faces, want %u", n, lod.faces, fcount[n]);
        for (uint32_t f = 0; f < lod.faces; f++) {
            uint32_t c[3];
            mc_pmesh_lod_face(&lod, f, c);
            for (int k = 0; k < 3; k++)
                if (c[k] >= V || rank[c[k]] >= n) PROBLEM("level %u face %u: corner %u is not present", n, f, c[k]);
            if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
                PROBLEM("level %u face %u: corners %u %u %u repeat", n, f, c[0], c[1], c[2]);
        }
        faces_checked += lod.faces;
    }
    if (problems)
        printf("not ok: %lu problems; first: %s\n", problems, first);
    else
        printf("ok: %u vertices (%u base), %u faces (%u base), %u levels, %llu faces checked\n", V, V0, pm->faces,
               pm->base_faces, nl, (unsigned long long)faces_checked);
    free(levels), free(anc), free(rank), free(fcount);
    return problems ? 1 : 0;
}
