/* The face bits of a whole progressive mesh worked out (mesh_face.h): what a bake stores, for a mesh
 * that came without them (a stream, stream.h). */
#include "modelc/mesh_face.h"
#include "modelc/bytes.h"
#include "modelc/pmesh.h"

/* Face f's mc_mesh_normal15 normal in the full mesh (apart: one copy for both calls). */
static MC_NOINLINE void face_normal(const mc_pmesh *pm, uint32_t f, int32_t n[3])
{
    const unsigned ib = pm->index_bytes;
    const uint8_t *r = mc_chunk_record(pm->corners, pm->record_shift, 3u * ib, f);
    int32_t p[3][3];
    for (unsigned k = 0; k < 3; k++)
        mc_pmesh_position_at(mc_chunk_record(pm->positions, pm->record_shift, 6u, mc_le_index(r + k * ib, ib)), p[k]);
    mc_mesh_normal15((const int32_t(*)[3])p, n);
}

void mc_mesh_face_bits(const mc_pmesh *pm, uint8_t *bits)
{
    const unsigned hb = pm->half_bytes;
    mc_bytes_zero(bits, pm->faces);
    /* each face's normal once, its shade from it (mc_mesh_shade_normal15); each edge once, from its
     * face of the lower number, with the normal of the face across: both faces' bits */
    for (uint32_t f = 0; f < pm->faces; f++) {
        int32_t n[3];
        face_normal(pm, f, n);
        bits[f] = (uint8_t)(bits[f] | mc_mesh_shade_normal15(n));
        const uint8_t *r = mc_chunk_record(pm->opposite, pm->record_shift, 3u * hb, f);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t o = mc_pmesh_half(r + k * hb, hb);
            if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) <= f) continue;
            int32_t m[3];
            face_normal(pm, MC_HALF_FACE(o), m);
            if (mc_mesh_crease_normals(n, m, pm->crease_cos)) {
                bits[f] = (uint8_t)(bits[f] | 1u << (5u + k));
                bits[MC_HALF_FACE(o)] = (uint8_t)(bits[MC_HALF_FACE(o)] | 1u << (5u + MC_HALF_EDGE_INDEX(o)));
            }
        }
    }
}
