// Normal cones: for nodes of the octree, a cone that holds the outward normal of every face the
// node's cube meets, so the renderer can skip a subtree whose surface all faces away (QSplat).
//
// Promise: cones are made only for a closed mesh (every edge shared by two faces, no face dropped
// as non-manifold, no self-intersection), oriented by CGAL to bound a volume. On such a surface a
// point whose outward normal faces away from the viewer is hidden by the surface in front of it,
// so culling it changes only pixels where the far side showed through gaps between drawn leaves.
// A node's cone holds the normals of every face its closed cube meets (CGAL AABB tree, box
// queries): every sample, so every leaf under the node, comes from one of them. Each cone is
// stored as octree.h says: an axis of three int8 (about 127 long) and the sine of its half-angle
// about that quantized axis, times the axis length, rounded up; 255 where the cone is wider than a
// half-space (never culled); then how much data the node's subtree holds two and three levels
// down, so the renderer steps over a culled subtree without reading it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>
#include "model.hpp"
#include "normalize.hpp"
#include "octree.hpp"

namespace mc {

// What the cones are made from: the model's outward face normals in an AABB tree, or nothing when
// the model is a point set or not a closed, non-self-intersecting mesh (then why says which).
struct ConeSource {
    struct Impl;
    std::shared_ptr<Impl> impl;   // null: no cones
    std::string why;              // when null: the reason, for budget.json
};

ConeSource cone_source(const Model &model, const GridCube &cube);

// Bytes per cone record (octree.h).
constexpr int kConeBytes = 7;

// The cone records of levels 1 .. depth - 3 of t (t.cones[l], in the level's depth-first order;
// every other level, and every level without a source, empty).
void add_cones(Octree &t, const ConeSource &src);

}  // namespace mc
