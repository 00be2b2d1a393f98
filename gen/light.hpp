// The fixed frontal light that shades models without colours (voxel.cpp) and the mesh reference the
// tests compare against (reference.cpp): one definition, so the two renders cannot drift apart.
#pragma once

#include <cmath>

namespace mc {

// As the source paper's scans: from the viewer (+z), two-sided so that meshes with inconsistent
// orientation still shade, with some ambient so grazing surfaces stay visible. (nx, ny, nz) need not
// be unit length; a zero normal gets a middle grey.
inline double frontal_light(double nx, double ny, double nz) {
    double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0)) return 0.6;
    return 0.15 + 0.85 * std::fabs(nz / len);
}

}  // namespace mc
