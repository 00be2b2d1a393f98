/* Between the stream reader's files (not part of the runtime's interface): stream.c frames the
 * records and reads the octree's, and hands a version-2 or -3 stream's mesh records to
 * stream_mesh.c, which hands version 3's packed splits to stream_packed.c. */
#ifndef MODELC_STREAM_MESH_H
#define MODELC_STREAM_MESH_H

#include "modelc/stream.h"

#define MC_STREAM_KIND_PALETTE 1
#define MC_STREAM_KIND_LEVEL 2
#define MC_STREAM_KIND_END 3
#define MC_STREAM_KIND_MESH 4
#define MC_STREAM_KIND_BASE 5
#define MC_STREAM_KIND_SPLITS 6
#define MC_STREAM_KIND_ADJACENCY 7
#define MC_STREAM_KIND_PACKED 8
#define MC_STREAM_KIND_PACKED_ADJACENCY 9

/* Records the first error (and where it was found); returns the stream's error. Inline here, so
 * that stream_mesh.c needs nothing of stream.c: the calls go one way, stream.c to stream_mesh.c. */
static inline int mc_stream_fail(mc_stream *s, int error, uint32_t at)
{
    if (s->error == MC_STREAM_OK) {
        s->error = error;
        s->error_at = at;
    }
    return s->error;
}

/* The buffer's mesh arrays, as mesh_header lays them out (k: 0 positions, 1 tree, 2 splits, 3 corners,
 * 6 face bits, 7 split faces), a vertex's tree record in them (its subtree size: 0 until it came),
 * and a little-endian field written. */
static inline uint8_t *mc_stream_array(mc_stream *s, unsigned k) { return (uint8_t *)s->mesh_chunks[k][0].data; }
static inline uint8_t *mc_stream_tree(mc_stream *s, uint32_t v)
{
    return mc_stream_array(s, 1) + v * s->pmesh.index_bytes;
}
static inline void mc_stream_put(uint8_t *p, uint32_t v, unsigned bytes)
{
    for (unsigned i = 0; i < bytes; i++) p[i] = (uint8_t)(v >> (8 * i));
}
/* Split i's records: the vertex v it brings back and its split_faces bit (nf: 1 or 2 faces; the bits
 * start cleared). */
static inline void mc_stream_put_split(mc_stream *s, uint32_t i, uint32_t v, uint32_t nf)
{
    const unsigned ib = s->pmesh.index_bytes;
    mc_stream_put(mc_stream_array(s, 2) + i * ib, v, ib);
    if (nf == 2u) mc_stream_array(s, 7)[i >> 3] |= (uint8_t)(1u << (i & 7u));
}

/* A checked record of a mesh kind (payload of n bytes at offset at in buf; the record at at_record):
 * MC_STREAM_OK, or the error, recorded. */
int mc_stream_mesh_record(mc_stream *s, unsigned kind, uint32_t at, uint32_t n, uint32_t at_record);

/* The adjacency checked and taken: opposite (3 F half-edges) and order (E), hb bytes each, where
 * they lie in the buffer; an error is recorded at at, plus the entry's offset when in_place (the
 * arrays are the record's payload at at, one after the other). MC_STREAM_OK, or the error. */
int mc_stream_adjacency(mc_stream *s, const uint8_t *opposite, const uint8_t *order, uint32_t at, int in_place);

/* Version 3's packed splits (stream_packed.c). start: the decoder's state at area (the buffer after
 * the mesh arrays, MC_STREAM_PACKED_BYTES of it), once the mesh header is read.
 * base: the base faces' corners placed at their roots (roots: the base record's vertex entries,
 * per bytes apart). splits: a kind-8 payload of n bytes at p (at: its offset in the buffer),
 * decoded into the mesh arrays: MC_STREAM_OK, or the error, recorded. */
void mc_stream_packed_start(mc_stream *s, uint8_t *area);
void mc_stream_packed_base(mc_stream *s, const uint8_t *roots, uint32_t per);
int mc_stream_packed_splits(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at);
/* Version 3's adjacency (kind 9): the opposites found from the full mesh the splits built, the edge
 * order decoded; both into the decoder's state, which the full mesh no longer needs. */
int mc_stream_packed_adjacency(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at);

#endif
