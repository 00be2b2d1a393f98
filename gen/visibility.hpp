// Hidden-cell removal at bake time (--views): the bake keeps only the cells that are visible from at
// least one of the directions the model will be seen from, as the source paper merges the cells
// visible from several viewpoints. A cell is visible from a direction when no nearer cell covers it
// (projected centres binned per direction at the octree's resolution, a z-buffer of points) and, for
// meshes, when a ray from its point on the original surface toward the viewer meets no triangle
// (CGAL AABB tree). In every case the cells that the
// runtime's frontal view (yaw = pitch = roll = 0, orthographic) draws at any level are kept, so the
// frontal image stays pixel-identical to the unpruned model's.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>
#include "model.hpp"
#include "octree.hpp"
#include "progress.hpp"
#include "voxel.hpp"

namespace mc {

// A parsed --views SPEC: "all" (no pruning), or a comma list of
//   front:DEG          every direction within DEG degrees (0..180) of the front axis
//   YAW:PITCH          the one direction the viewer's --yaw YAW --pitch PITCH (degrees) looks along
//   YAW:PITCH:DEG      every direction within DEG degrees of that one
// each optionally followed by @N: sample the cone with N directions instead of the default density.
struct ViewSpec {
    struct Cone {
        double yaw = 0, pitch = 0, deg = 0;  // axis (viewer angles, degrees) and half-angle
        int count = 0;                       // directions; 0 = from the density (cone_directions)
    };
    std::string text;        // the SPEC as given (recorded in budget.json)
    bool all = true;         // no pruning
    std::vector<Cone> cones;
};

// Parses SPEC. Throws std::invalid_argument with a message that completes "--views SPEC: ...".
ViewSpec parse_views(const std::string &spec);

// Directions sampled for a cone of half-angle deg when no @N is given: proportional to the cone's
// solid angle, kFrontDirections for 60 degrees (see visibility.cpp for why that many), at least 1.
int cone_directions(double deg);
constexpr int kFrontDirections = 400;

// Unit vectors toward the viewer, in model space (x right, y up, z toward the frontal viewer), of
// every direction of the spec: for the viewer's yaw y and pitch p, (-cos p sin y, sin p, cos p cos y)
// (the third row of the runtime's rotation Rz Rx Ry). Fibonacci points on each cone, axis and rim
// included.
std::vector<std::array<double, 3>> view_directions(const ViewSpec &spec);

struct PruneStats {
    size_t directions = 0;
    size_t cells_before = 0, cells_removed = 0;
    size_t kept_for_front = 0;   // cells kept only because the frontal view draws them
};

// One flag per cell of vox (1 = keep): the cells visible from at least one of dirs (meshes, with
// vox.surface filled, also cast rays against model's triangles), then the frontal view's winners
// at every level.
std::vector<uint8_t> visible_cells(const Model &model, const Voxels &vox,
                                   const std::vector<std::array<double, 3>> &dirs, Progress &progress,
                                   PruneStats &stats);

// budget.json's "pruning" entry (JSON text) and the one line the bake prints about it.
std::string pruning_json(const ViewSpec &spec, const PruneStats &stats);
std::string pruning_report(const ViewSpec &spec, const PruneStats &stats);

}  // namespace mc
