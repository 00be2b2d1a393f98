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

// Meshes: the deepest level sampled on its own over the whole surface. A mesh baked deeper has levels
// 0..kSampledLevel exactly as a bake of that depth has them (the same cells, the same colours before
// the palette), and each finer level l refines level l - 1 with level l's own sampling (voxel.cpp,
// drop_orphans and adopt): so levels 0..l of a depth-D bake are a depth-l bake's for every l from
// kSampledLevel to D, and the level of detail draws a deeper bake as the shallower bake it stands
// for. 8: the default --depth, the catalogue's and the firmware's, whose bakes this leaves byte for
// byte as they were (a bake of depth 8 or less samples once, at its own depth; its levels above
// still come from that one finer sampling).
constexpr int kSampledLevel = 8;

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
    uint64_t samples = 0;             // surface samples (meshes: of every level sampled) or input points
    // meshes deeper than kSampledLevel: level_rgb[l] (kSampledLevel <= l < depth) holds the colour of
    // each node of level l, in ascending code order, from level l's own samples (build_levels takes
    // these instead of the mean of the leaves under the node); empty elsewhere and for shallower bakes
    std::vector<std::vector<std::array<double, 3>>> level_rgb;
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
