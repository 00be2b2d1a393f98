// The CGAL kernel and mesh types the generator samples, shades and dumps meshes with (voxel.cpp,
// reference.cpp), and the two conversions both make: one definition, so the voxelizer and the mesh
// reference see the same geometry and the same normals.
#pragma once

#include <array>
#include <vector>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include "model.hpp"

namespace CGAL::Polygon_mesh_processing {}

namespace mc {

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Vector = K::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

// The model's triangles as a CGAL mesh, one vertex per model point (vertex i is point i); faces CGAL
// cannot add without breaking manifoldness are dropped.
Mesh to_cgal(const Model &m);

// A point set's normals for shading: the file's, or, when it has neither colours nor normals, PCA
// estimates from each point's 12 nearest neighbours (CGAL); empty when it has colours and no normals.
std::vector<std::array<double, 3>> point_normals(const Model &m);

// CGAL's PCA normal estimate from each point's 12 nearest neighbours (unoriented).
std::vector<std::array<double, 3>> pca_normals(const Model &m);

}  // namespace mc
