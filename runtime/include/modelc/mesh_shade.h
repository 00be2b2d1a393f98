/* A face's shade: the palette index mc_mesh_render draws it in, from its corners' positions.
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
 * Promise: mc_mesh_shade_of is a function of the three positions alone (their order does not
 * matter), in integers, the same on every target and in C++: the generator includes this header to
 * store each full-mesh face's shade (pmesh.h `shades`), so a drawing that reads the stored shade and
 * one that works it out give the same pixels. No heap, no floating point, no 64-bit division.
 * Freestanding.
 */
#ifndef MODELC_MESH_SHADE_H
#define MODELC_MESH_SHADE_H

#include <stdint.h>
#include "bits.h"    /* mc_fit_shift */
#include "fixed.h"   /* mc_mag64 */

#define MC_MESH_SHADES 32

/* The palette index of a face with corners p0, p1, p2 (unit-cube Q16, pmesh.h). */
MC_ALWAYS_INLINE unsigned mc_mesh_shade_of(const int32_t p0[3], const int32_t p1[3], const int32_t p2[3])
{
    /* ((2j - 1) / 62)^2 in Q30, j = 1 .. 31: |n.z| / |n| at least (j - 1/2) / 31 means shade j or more */
    static const uint32_t limit[MC_MESH_SHADES - 1] = {
        279329, 2513964, 6983232, 13687136, 22625673, 33798845, 47206651, 62849092, 80726167, 100837877,
        123184221, 147765199, 174580812, 203631059, 234915940, 268435456, 304189606, 342178391, 382401810,
        424859863, 469552551, 516479873, 565641830, 617038421, 670669646, 726535506, 784636000, 844971128,
        907540891, 972345289, 1039384320,
    };
    const int64_t a0 = (int64_t)p1[0] - p0[0], a1 = (int64_t)p1[1] - p0[1], a2 = (int64_t)p1[2] - p0[2];
    const int64_t b0 = (int64_t)p2[0] - p0[0], b1 = (int64_t)p2[1] - p0[1], b2 = (int64_t)p2[2] - p0[2];
    /* |a|, |b| < 2^17 a component: |n| < 2^35 */
    const uint64_t m0 = mc_mag64(a1 * b2 - a2 * b1), m1 = mc_mag64(a2 * b0 - a0 * b2), m2 = mc_mag64(a0 * b1 - a1 * b0);
    const uint64_t m = m0 | m1 | m2;
    if (m == 0) return MC_MESH_SHADES / 2;
    /* the normal's 15 leading bits: each component divided by 2^s toward zero, s the smallest shift
     * that leaves every one below 2^15; only their squares count, so only their magnitudes */
    const unsigned s = mc_fit_shift(m, 15u);
    const uint64_t x = m0 >> s, y = m1 >> s, z = m2 >> s;
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

#endif
