/* The modelc side of the progressive-mesh benchmark (tests/bench/pmesh.sh): mc_pmesh_lod_set over a
 * bake's whole range, from the base level to the full one and back, as openmesh_pm does on
 * OpenMesh's half-edge mesh. Built with -DPM=mc_pmesh_NAME -include NAME.h and the bake's files.
 *
 *   pmesh_lod ROUNDS     per round "ns per level change X" (wall clock, 2 * splits changes)
 *   pmesh_lod --sweeps N N sweeps and nothing else, for callgrind (--toggle-collect=mc_pmesh_lod_set)
 *   --neighbours first:  the state keeps a neighbour table (pmesh.h mc_pmesh_lod_neighbours) through
 *                        the changes
 * and "mean subtree size X": the ancestor-map entries a split rewrites, on average.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/pmesh.h"

extern const mc_pmesh PM;

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e9 + t.tv_nsec;
}

int main(int argc, char **argv)
{
    static uint32_t anc[1u << 22];   /* V entries of up to 4 bytes */
    if (PM.vertices > sizeof anc / sizeof anc[0]) return 2;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    if (argc > 1 && !strcmp(argv[1], "--neighbours")) {
        static uint8_t nbr[MC_PMESH_NEIGHBOUR_BYTES(1u << 23, 4)];
        if (PM.faces > 1u << 23) return 2;
        mc_pmesh_lod_neighbours(&lod, nbr);
        argc--, argv++;
    }
    const double changes = 2.0 * (PM.vertices - PM.base_vertices);
    if (argc == 3 && !strcmp(argv[1], "--sweeps")) {
        for (int r = atoi(argv[2]); r > 0; r--) {
            mc_pmesh_lod_set(&lod, PM.vertices);
            mc_pmesh_lod_set(&lod, PM.base_vertices);
        }
        printf("level changes %.0f\n", changes * atoi(argv[2]));
        return 0;
    }
    if (argc != 2) { fprintf(stderr, "usage: pmesh_lod [--neighbours] ROUNDS | --sweeps N\n"); return 2; }
    uint64_t work = 0;
    for (uint32_t s = 0; s < PM.vertices - PM.base_vertices; s++)   /* each split vertex's subtree size */
        work += mc_le_index(mc_chunk_record(PM.tree, PM.record_shift, PM.index_bytes, mc_pmesh_split_vertex(&PM, s)),
                            PM.index_bytes);
    printf("mean subtree size %.2f\n", (double)work / (PM.vertices - PM.base_vertices));
    for (int r = atoi(argv[1]); r > 0; r--) {
        double t0 = now_ns();
        mc_pmesh_lod_set(&lod, PM.vertices);
        mc_pmesh_lod_set(&lod, PM.base_vertices);
        printf("ns per level change %.2f\n", (now_ns() - t0) / changes);
    }
    return 0;
}
