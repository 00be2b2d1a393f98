// Normalization: see normalize.hpp.
#include "normalize.hpp"

#include <algorithm>

namespace mc {

void make_z_up_y_up(Model &m) {
    for (auto *v : {&m.points, &m.normals})
        for (auto &p : *v) p = {p[0], p[2], -p[1]};
}

std::array<double, 3> file_frame(const std::array<double, 3> &p, UpAxis up) {
    return up == UpAxis::z ? std::array<double, 3>{p[0], -p[2], p[1]} : p;
}

GridCube grid_cube(const Model &m) {
    std::array<double, 3> lo = m.points[0], hi = m.points[0];
    for (const auto &p : m.points)
        for (int a = 0; a < 3; a++) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
    double ext = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    GridCube c;
    c.side = ext * (1 + 1e-9);  // keeps the max corner inside the last cell
    for (int a = 0; a < 3; a++) c.origin[a] = (lo[a] + hi[a]) / 2 - c.side / 2;
    return c;
}

GridCube normalize(Model &m, UpAxis up) {
    if (up == UpAxis::z) make_z_up_y_up(m);
    return grid_cube(m);
}

}  // namespace mc
