/* The line drawings' memory and the crease bits it keeps (private to the runtime: mesh_lines.c
 * draws from them, mesh_creases.c keeps them).
 *
 * Memory (mesh_lines.h MC_MESH_LINES_BYTES): a tag, the level the crease bits are for plus one (0:
 * none yet) in its low 31 bits and in bit 31 whether that level has a crease; the facing bits of the
 * last frame, a bit a face; the crease bits, four bits a face (face f's in the low half of byte
 * f / 2 for even f, the high half for odd), bit k set when edge k is a crease (mesh_lines.h: the
 * angle between the normals of the faces across it at the level exceeds the part's crease angle).
 *
 * Promise: after mc_mesh_creases_update the tag and the crease bits are those of the current level,
 * the same bytes however the level was reached and whichever levels the memory saw before (a
 * function of the level, as pmesh.h's ancestor map is). Work: none while the level is unchanged;
 * after a change of under a 16th of the level's faces (a 256th to the full level of a part with
 * stored bits), the faces around the vertices the splits between moved (the bits brought over);
 * else every edge of the level, where an edge between two faces as in the full mesh takes the
 * part's stored bit (pmesh.h face_bits: no normals; at the full level every bit is read in order)
 * and any other its faces' normals. Freestanding, no heap, bounded stack.
 */
#ifndef MODELC_MESH_CREASES_H
#define MODELC_MESH_CREASES_H

#include <stdint.h>
#include "modelc/bits.h"
#include "modelc/mesh_lines.h"

MC_ALWAYS_INLINE uint32_t *mc_lines_tag(uint8_t *mem) { return (uint32_t *)(void *)mem; }
MC_ALWAYS_INLINE uint8_t *mc_lines_facing(uint8_t *mem) { return mem + 4; }
MC_ALWAYS_INLINE uint8_t *mc_lines_creases(uint8_t *mem, uint32_t faces) { return mem + 4 + MC_MESH_FACING_BYTES(faces); }

/* Face f's crease bits: bit k set when its edge k is a crease. */
MC_ALWAYS_INLINE uint32_t mc_lines_face_creases(const uint8_t *cr, uint32_t f)
{
    return (cr[f >> 1] >> ((f & 1u) * 4u)) & 7u;
}

/* Whether the level the tag is for has a crease. */
MC_ALWAYS_INLINE int mc_lines_any_crease(uint8_t *mem) { return (*mc_lines_tag(mem) >> 31) != 0; }

/* Face f's corners' positions at the level (mc_pmesh_lod_face, mc_pmesh_position, read in place). */
static inline void mc_mesh_face_positions(const mc_pmesh_lod *lod, uint32_t f, int32_t p[3][3])
{
    const mc_pmesh *pm = lod->pm;
    uint32_t c[3];
    mc_pmesh_lod_face(lod, f, c);
    for (int k = 0; k < 3; k++) mc_pmesh_position_at(mc_chunk_record(pm->positions, pm->record_shift, 6u, c[k]), p[k]);
}

/* Brings mem's tag and crease bits to the current level (above). */
void mc_mesh_creases_update(const mc_pmesh_lod *lod, uint8_t *mem);

#endif
