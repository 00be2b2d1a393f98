// Sampling and voxelization: a model becomes one coloured point per occupied cell of a 2^D grid.
#pragma once
#include <array>
#include <cstdint>
#include <vector>
#include "model.hpp"
#include "normalize.hpp"
#include "point_fill.hpp"
#include "progress.hpp"

namespace mc {

struct VoxelOptions {
    int depth = 8;            // grid of 2^depth cells per side
    double spacing = 0.5;     // mesh sampling grid spacing, in cells
    bool point_fill = true;   // point sets: fill the surface between sparse points (point_fill.hpp)
};

struct Voxels {
    int depth = 0;
    std::array<double, 3> origin{};   // model-space corner of the grid cube (GridCube::origin)
    double cell = 0;                  // model-space side of one cell (GridCube::cell(depth))
    std::vector<uint64_t> codes;      // Morton codes of occupied cells, ascending (bit 0 = x, 1 = y, 2 = z)
    std::vector<std::array<double, 3>> rgb;  // colour per cell, 0..255
    uint64_t samples = 0;             // surface samples (meshes) or input points (point sets)
    // meshes: one point on the surface per cell (the surface point nearest its samples' centroid),
    // where visibility rays start; empty for point sets
    std::vector<std::array<double, 3>> surface;
    PointFill fill;                   // point sets: what point_fill.hpp added
    // The grid cube the cells divide (origin and cell are all it takes).
    GridCube cube() const {
        GridCube c;
        c.origin = origin;
        c.side = cell * static_cast<double>(1u << depth);
        return c;
    }
};

// The cells of cube's 2^opt.depth grid that model occupies. Throws InputError (Where::none) when the
// model cannot be voxelized (e.g. nothing lands in the grid).
Voxels voxelize(const Model &model, const GridCube &cube, const std::string &file, const VoxelOptions &opt,
                Progress &progress);

// Morton helpers shared with the octree builder and the tests.
uint64_t morton_encode(uint32_t x, uint32_t y, uint32_t z, int depth);
std::array<uint32_t, 3> morton_decode(uint64_t code, int depth);

}  // namespace mc
