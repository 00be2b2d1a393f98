/* What a face's corners decide, in integers: its shade (the palette index mc_mesh_render draws it
 * in) and whether its edge with a neighbour is a crease (mesh_lines.h); and the byte a bake stores for
 * each face of the full mesh with both (pmesh.h face_bits).
 *
 * Shade: as the point renderer's baked colours of uncoloured models (gen/light.hpp), a frontal light
 * fixed to the model: intensity (3 + 17 |n.z| / |n|) / 20 for the face's normal n in the model's frame
 * (+y up, +z towards the viewer at the default view), so the light turns with the model. The face
 * gets palette index k, 0 .. MC_MESH_SHADES - 1, the k whose |n.z| / |n| = k / (MC_MESH_SHADES - 1)
 * is nearest, decided in integers on the normal's 15 leading bits: within 1/100 of a step of the
 * rounding point a face may take either neighbour (the truncation moves |n.z| / |n| by under 2^-13).
 * A face of zero area is index MC_MESH_SHADES / 2. The part's palette (pmesh.h) holds the matching
 * greys.
 *
 * Crease: the angle between the two faces' normals exceeds the part's crease angle, decided on each
 * normal's 15 leading bits (mc_mesh_normal15: a small face's normal scaled up to them) with the
 * cosine's square compared in 64 bits: within 1/1000 of the crease angle's cosine either answer.
 *
 * Face bits (pmesh.h face_bits): bits 0-4 the face's shade, bit 5 + k set when its edge k is a crease
 * in the full mesh (a border edge never is).
 *
 * mc_mesh_face_bits works the byte out for every face of a whole progressive mesh: the generator
 * stores what it gives, and a stream's reader (stream.h) calls it once its mesh is whole.
 *
 * Promise: every function here is a function of its arguments alone (the shade and a normal's
 * magnitude do not depend on the corners' order), in integers, the same on every target and in C++:
 * the generator includes this header to store the face bits, so a drawing that reads them and one
 * that works them out give the same pixels. No heap, no floating point, no 64-bit division.
 * Freestanding.
 */
#ifndef MODELC_MESH_FACE_H
#define MODELC_MESH_FACE_H

#include <stdint.h>
#include "bits.h"    /* mc_fit_shift */
#include "fixed.h"   /* mc_mag64 */
#include "pmesh.h"   /* mc_mesh_face_bits: the part's arrays */

#define MC_MESH_SHADES 32   /* a shade fits the face bits' low 5 bits */

#define MC_FACE_BITS_SHADE(b) ((unsigned)(b) & 31u)
#define MC_FACE_BITS_CREASE(b, k) (((unsigned)(b) >> (5u + (k))) & 1u)

/* The palette index of a face whose normal's 15 leading bits have magnitudes x, y, z (each below
 * 2^15: the components divided by 2^s toward zero, s the smallest shift that leaves every one below
 * 2^15; only their squares count, so only their magnitudes). */
MC_ALWAYS_INLINE unsigned mc_mesh_shade_xyz(uint64_t x, uint64_t y, uint64_t z)
{
    /* ((2j - 1) / 62)^2 in Q30, j = 1 .. 31: |n.z| / |n| at least (j - 1/2) / 31 means shade j or more */
    static const uint32_t limit[MC_MESH_SHADES - 1] = {
        279329, 2513964, 6983232, 13687136, 22625673, 33798845, 47206651, 62849092, 80726167, 100837877,
        123184221, 147765199, 174580812, 203631059, 234915940, 268435456, 304189606, 342178391, 382401810,
        424859863, 469552551, 516479873, 565641830, 617038421, 670669646, 726535506, 784636000, 844971128,
        907540891, 972345289, 1039384320,
    };
    /* squares below 2^30, so the products below stay in 64 bits */
    const uint64_t len2 = x * x + y * y + z * z, z2 = z * z << 30;
    if (len2 == 0) return MC_MESH_SHADES / 2;
    /* the number of limits z2 / len2 reaches: a binary search over the 31, without branches */
    unsigned k = 0;
    k += (unsigned)(z2 >= (uint64_t)limit[k + 15] * len2) << 4;
    k += (unsigned)(z2 >= (uint64_t)limit[k + 7] * len2) << 3;
    k += (unsigned)(z2 >= (uint64_t)limit[k + 3] * len2) << 2;
    k += (unsigned)(z2 >= (uint64_t)limit[k + 1] * len2) << 1;
    k += (unsigned)(z2 >= (uint64_t)limit[k] * len2);
    return k;
}

/* The palette index of a face with corners p0, p1, p2 (unit-cube Q16, pmesh.h). */
MC_ALWAYS_INLINE unsigned mc_mesh_shade_of(const int32_t p0[3], const int32_t p1[3], const int32_t p2[3])
{
    const int64_t a0 = (int64_t)p1[0] - p0[0], a1 = (int64_t)p1[1] - p0[1], a2 = (int64_t)p1[2] - p0[2];
    const int64_t b0 = (int64_t)p2[0] - p0[0], b1 = (int64_t)p2[1] - p0[1], b2 = (int64_t)p2[2] - p0[2];
    /* |a|, |b| < 2^17 a component: |n| < 2^35 */
    const uint64_t m0 = mc_mag64(a1 * b2 - a2 * b1), m1 = mc_mag64(a2 * b0 - a0 * b2), m2 = mc_mag64(a0 * b1 - a1 * b0);
    const uint64_t m = m0 | m1 | m2;
    if (m == 0) return MC_MESH_SHADES / 2;
    const unsigned s = mc_fit_shift(m, 15u);
    return mc_mesh_shade_xyz(m0 >> s, m1 >> s, m2 >> s);
}

/* The normal of the face with corners p, its components scaled together by a power of two so that
 * the largest magnitude has 15 bits (2^14 .. 2^15 - 1): shifted right (towards zero, signs kept)
 * when larger, left (exactly) when smaller; all zero for a face with no area. A small face's normal
 * is scaled up so that the crease test's products keep their precision (without it a face a few
 * units across lost every crease under 90 degrees). The edges (17 bits) and the components (15
 * bits) are int32, so that a 32-bit core takes each product in one step. */
MC_ALWAYS_INLINE void mc_mesh_normal15(const int32_t p[3][3], int32_t n[3])
{
    int32_t a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = p[1][i] - p[0][i], b[i] = p[2][i] - p[0][i];
    int64_t w[3];   /* components below 2^35 */
    w[0] = (int64_t)a[1] * b[2] - (int64_t)a[2] * b[1];
    w[1] = (int64_t)a[2] * b[0] - (int64_t)a[0] * b[2];
    w[2] = (int64_t)a[0] * b[1] - (int64_t)a[1] * b[0];
    const uint64_t m = mc_mag64(w[0]) | mc_mag64(w[1]) | mc_mag64(w[2]);
    const unsigned s = mc_fit_shift(m, 15u);   /* (m below 2^35) */
    /* m below 2^15 (s 0): the left shift that brings its top bit to bit 14 (none for 0) */
    const unsigned up = s || m == 0 ? 0u : mc_clz32((uint32_t)m) - 17u;
    /* w / 2^s truncated, as a shift of the magnitude with the sign put back (a 64-bit division is a
     * library call on a 32-bit core; the sign is a coin toss to a predictor), or w 2^up */
    for (int i = 0; i < 3; i++) {
        const uint32_t neg = 0u - (uint32_t)(w[i] < 0);
        n[i] = (int32_t)(((((uint32_t)(mc_mag64(w[i]) >> s)) << up) ^ neg) - neg);
    }
}

/* mc_mesh_shade_of of the face whose mc_mesh_normal15 normal is n: its components' magnitudes are
 * the 15 leading bits mc_mesh_shade_of takes, so the same index. */
MC_ALWAYS_INLINE unsigned mc_mesh_shade_normal15(const int32_t n[3])
{
    return mc_mesh_shade_xyz(mc_mag64(n[0]), mc_mag64(n[1]), mc_mag64(n[2]));
}

/* Whether faces with mc_mesh_normal15 normals n and m meet at more than the crease angle whose
 * cosine is crease_cos (Q14); never for a face with no area. */
MC_ALWAYS_INLINE int mc_mesh_crease_normals(const int32_t n[3], const int32_t m[3], int32_t crease_cos)
{
    const int64_t d = (int64_t)n[0] * m[0] + (int64_t)n[1] * m[1] + (int64_t)n[2] * m[2];   /* |d| < 3 * 2^30 */
    const uint32_t ln = (uint32_t)(n[0] * n[0]) + (uint32_t)(n[1] * n[1]) + (uint32_t)(n[2] * n[2]);   /* < 3 * 2^30 */
    const uint32_t lm = (uint32_t)(m[0] * m[0]) + (uint32_t)(m[1] * m[1]) + (uint32_t)(m[2] * m[2]);
    if (ln == 0 || lm == 0) return 0;
    /* cos = d / sqrt(ln lm) < c = crease_cos / 2^14; squared: d^2 against c^2 ln lm / 2^28, with
     * ln lm < 9 * 2^60 and (ln lm >> 28) c^2 < 9 * 2^60: no overflow */
    const uint64_t d2 = mc_mag64(d) * mc_mag64(d), rhs = (((uint64_t)ln * lm) >> 28) * (uint64_t)((int64_t)crease_cos * crease_cos);
    if (crease_cos >= 0) return d < 0 || d2 < rhs;
    return d < 0 && d2 > rhs;
}

/* Face f's mc_mesh_normal15 normal in the full mesh of pm. */
static inline void mc_mesh_face_normal15(const mc_pmesh *pm, uint32_t f, int32_t n[3])
{
    const unsigned ib = pm->index_bytes;
    const uint8_t *r = mc_chunk_record(pm->corners, pm->record_shift, 3u * ib, f);
    int32_t p[3][3];
    for (unsigned k = 0; k < 3; k++)
        mc_pmesh_position_at(mc_chunk_record(pm->positions, pm->record_shift, 6u, mc_le_index(r + k * ib, ib)), p[k]);
    mc_mesh_normal15((const int32_t(*)[3])p, n);
}

/* The face bits of each face of pm (pmesh.h: its corners, positions and opposites whole) into
 * bits[0 .. pm->faces - 1]: what a bake stores (the generator calls this on its own arrays) and what
 * a stream's reader works out once its mesh is whole. Each face's normal once, its shade from it;
 * each edge once, from its face of the lower number, with the normal of the face across. Inline here
 * so that the generator (C++) and the reader share it; the one runtime file that calls it,
 * stream_mesh.c, holds its code. */
static inline void mc_mesh_face_bits(const mc_pmesh *pm, uint8_t *bits)
{
    const unsigned hb = pm->half_bytes;
    for (uint32_t f = 0; f < pm->faces; f++) bits[f] = 0;
    for (uint32_t f = 0; f < pm->faces; f++) {
        int32_t n[3];
        mc_mesh_face_normal15(pm, f, n);
        bits[f] = (uint8_t)(bits[f] | mc_mesh_shade_normal15(n));
        const uint8_t *r = mc_chunk_record(pm->opposite, pm->record_shift, 3u * hb, f);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t o = mc_pmesh_half(r + k * hb, hb);
            if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) <= f) continue;
            int32_t m[3];
            mc_mesh_face_normal15(pm, MC_HALF_FACE(o), m);
            if (mc_mesh_crease_normals(n, m, pm->crease_cos)) {
                bits[f] = (uint8_t)(bits[f] | 1u << (5u + k));
                bits[MC_HALF_FACE(o)] = (uint8_t)(bits[MC_HALF_FACE(o)] | 1u << (5u + MC_HALF_EDGE_INDEX(o)));
            }
        }
    }
}

#endif
