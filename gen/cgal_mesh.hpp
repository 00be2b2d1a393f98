// The CGAL kernel and mesh types the generator samples, shades and dumps meshes with (voxel.cpp,
// reference.cpp): one definition, so the voxelizer and the mesh reference see the same geometry.
#pragma once

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

namespace CGAL::Polygon_mesh_processing {}

namespace mc {

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Vector = K::Vector_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace mc
