// Normalization: where a model stands in the generator's frame, decided once for every later stage.
//
// Promise: normalize() turns the model so that its up axis is +y (the runtime's views look at it
// that way) and returns its grid cube: the smallest axis-aligned cube around its points, centred on
// their bounding box, a hair larger so that the largest coordinates fall inside the last cell. The
// octree's 2^D grid divides that cube; the unit cube [-1/2, 1/2]^3 the runtime draws is that cube
// scaled. The model's coordinates themselves are not rescaled: every stage maps them through the
// cube, so the voxels and the reference renderer see the same numbers.
#pragma once
#include <array>
#include "model.hpp"

namespace mc {

// The up axis of the model file (--up).
enum class UpAxis { y, z };

struct GridCube {
    std::array<double, 3> origin{};   // model-space corner of the cube (its smallest coordinates)
    double side = 0;                  // model-space side
    // The side of one cell of a grid of 2^depth cells per side.
    double cell(int depth) const { return side / (1u << depth); }
    // p mapped into the unit cube [-1/2, 1/2]^3.
    std::array<double, 3> to_unit(const std::array<double, 3> &p) const {
        return {(p[0] - origin[0]) / side - 0.5, (p[1] - origin[1]) / side - 0.5, (p[2] - origin[2]) / side - 0.5};
    }
};

// Turns a model whose up axis is +z so that it stands along +y: (x, y, z) -> (x, z, -y), for points
// and normals alike (a rotation, so orientation is kept).
void make_z_up_y_up(Model &m);

// The inverse for one point: a y-up point back in the file's frame, (x, y, z) -> (x, -z, y) when up
// is z, unchanged when it is y.
std::array<double, 3> file_frame(const std::array<double, 3> &p, UpAxis up);

// The grid cube of m's points. m has at least one point (every reader guarantees it).
GridCube grid_cube(const Model &m);

// make_z_up_y_up when up is z, then grid_cube.
GridCube normalize(Model &m, UpAxis up);

}  // namespace mc
