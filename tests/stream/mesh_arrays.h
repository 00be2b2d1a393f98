/* Two progressive-mesh descriptors' arrays compared record by record, for the stream checks
 * (stream_check.c: a stream's against its bake's; stream_same.c: two streams' of one mesh). The
 * counts and widths must already be equal (the callers check them). */
#ifndef MODELC_TESTS_MESH_ARRAYS_H
#define MODELC_TESTS_MESH_ARRAYS_H

#include <string.h>
#include <modelc/pmesh.h>

/* NULL when positions, tree, splits, corners, opposites, edge order, face bits and split faces hold the
 * same bytes (*bytes: how many were compared; a split's face count as one byte); else the name of the
 * first array that differs, its record in *record. */
static const char *mesh_arrays_differ(const mc_pmesh *a, const mc_pmesh *b, uint32_t *record, uint64_t *bytes)
{
    const unsigned ib = a->index_bytes, hb = a->half_bytes;
    const uint32_t V = a->vertices, F = a->faces, S = V - a->base_vertices;
    const struct { const char *name; const mc_chunk *a, *b; uint32_t n, size; } list[] = {
        {"positions", a->positions, b->positions, V, 6},  {"tree", a->tree, b->tree, V, ib},
        {"splits", a->splits, b->splits, S, ib},          {"corners", a->corners, b->corners, F, 3 * ib},
        {"opposite", a->opposite, b->opposite, F, 3 * hb}, {"edge order", a->edge_order, b->edge_order, a->edges, hb},
        {"face bits", a->face_bits, b->face_bits, F, 1}};
    *bytes = 0;
    for (unsigned k = 0; k < sizeof list / sizeof list[0]; k++) {
        if (!list[k].a || !list[k].b) {   /* (one has no such array) */
            *record = 0;
            return list[k].name;
        }
        for (uint32_t i = 0; i < list[k].n; i++, *bytes += list[k].size)
            if (memcmp(mc_chunk_record(list[k].a, a->record_shift, list[k].size, i),
                       mc_chunk_record(list[k].b, b->record_shift, list[k].size, i), list[k].size)) {
                *record = i;
                return list[k].name;
            }
    }
    if (!a->split_faces || !b->split_faces) {
        *record = 0;
        return "split faces";
    }
    for (uint32_t i = 0; i < S; i++, (*bytes)++)   /* bits: the chunks' byte layouts may differ */
        if (mc_pmesh_split_faces(a, i) != mc_pmesh_split_faces(b, i)) {
            *record = i;
            return "split faces";
        }
    return NULL;
}

#endif
