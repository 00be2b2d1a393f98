// --dump-reference: the original model, normalised exactly as the octree is, for the double-precision
// mesh reference renderer of the tests and benchmarks (runtime/ref/mesh_ref.h). Never read by the runtime.
#pragma once
#include <string>
#include "model.hpp"
#include "voxel.hpp"

namespace mc {

// Writes FILE (format in runtime/ref/mesh_ref.h): the model's triangles (meshes: the faces the
// voxelizer's CGAL mesh keeps, with its per-vertex normals or the file's per-vertex colours) or points
// (point sets: each point's colour, from the file or the same frontal light of its normal as the
// voxelizer's, and one splat radius), every position mapped into the unit cube [-1/2, 1/2]^3 by the
// voxels' grid cube (GridCube::to_unit). Throws std::runtime_error when the file cannot be written
// (nothing is left behind).
void dump_reference(const Model &model, const Voxels &voxels, const std::string &file);

}  // namespace mc
