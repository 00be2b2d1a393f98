/* The edge-model part of a baked model: what a tracker draws to score a pose (track.h). The lines
 * to match against a camera's image edges, and the triangles that hide them (the object's surface;
 * the lines usually lie on it), in the model's own metric frame.
 *
 * Data layout (every array chunked, chunk.h indexed records: each chunk but the last holds exactly
 * 2^record_shift records; multi-byte fields little-endian; an index field is index_bytes wide):
 *   positions  per vertex: x, y, z as int32, micrometres (camera.h's units), |x|, |y|, |z| < 2^28
 *   lines      per line: its two vertices
 *   faces      per triangle: its three vertices, counter-clockwise seen from outside when closed
 *   line_faces per line: the two faces it lies between (convex models only; empty otherwise)
 * closed: 1 when the faces bound a solid (every edge of them shared by two faces), so that a face
 * seen from behind is hidden by another and a tracker may cull it.
 * convex: 1 when closed, convex, and every line the edge of exactly two faces: a line is then seen
 * exactly when one of its faces is seen from outside, and hidden wholly otherwise.
 *
 * Promise: the accessors read one record each, at one shift, one mask and one multiply (chunk.h);
 * no heap, no floating point. Freestanding.
 */
#ifndef MODELC_EDGES_H
#define MODELC_EDGES_H

#include <stdint.h>
#include "chunk.h"

typedef struct mc_edges {
    uint32_t vertices, lines, faces;
    uint8_t index_bytes;         /* 2 or 4 */
    uint8_t record_shift;        /* 2^record_shift records in each chunk but the last, every array */
    uint8_t closed;              /* 1: the faces bound a solid */
    uint8_t convex;              /* 1: closed, convex, line_faces recorded */
    const mc_chunk *positions;   /* vertices records of 12 bytes */
    const mc_chunk *line_list;   /* lines records of 2 index_bytes */
    const mc_chunk *face_list;   /* faces records of 3 index_bytes */
    const mc_chunk *line_faces;  /* convex: lines records of 2 index_bytes; else an empty list */
} mc_edges;

/* Vertex v's position, um. */
static inline void mc_edges_position(const mc_edges *m, uint32_t v, int32_t p[3])
{
    const uint8_t *r = mc_chunk_record(m->positions, m->record_shift, 12u, v);
    for (int k = 0; k < 3; k++) {
        const uint32_t u = mc_le32(r + 4 * k);   /* two's complement, converted without an implementation-defined cast */
        p[k] = u < 0x80000000u ? (int32_t)u : -(int32_t)(~u) - 1;
    }
}

/* Line i's two vertices. */
static inline void mc_edges_line(const mc_edges *m, uint32_t i, uint32_t v[2])
{
    const unsigned ib = m->index_bytes;
    const uint8_t *r = mc_chunk_record(m->line_list, m->record_shift, 2u * ib, i);
    v[0] = mc_le_index(r, ib), v[1] = mc_le_index(r + ib, ib);
}

/* Face i's three vertices. */
static inline void mc_edges_face(const mc_edges *m, uint32_t i, uint32_t v[3])
{
    const unsigned ib = m->index_bytes;
    const uint8_t *r = mc_chunk_record(m->face_list, m->record_shift, 3u * ib, i);
    v[0] = mc_le_index(r, ib), v[1] = mc_le_index(r + ib, ib), v[2] = mc_le_index(r + 2u * ib, ib);
}

/* Line i's two faces (convex models only). */
static inline void mc_edges_line_faces(const mc_edges *m, uint32_t i, uint32_t f[2])
{
    const unsigned ib = m->index_bytes;
    const uint8_t *r = mc_chunk_record(m->line_faces, m->record_shift, 2u * ib, i);
    f[0] = mc_le_index(r, ib), f[1] = mc_le_index(r + ib, ib);
}

#endif
