// CGAL conversions: see cgal_mesh.hpp.
#include "cgal_mesh.hpp"

#include <CGAL/pca_estimate_normals.h>

namespace mc {

Mesh to_cgal(const Model &m) {
    Mesh mesh;
    std::vector<Mesh::Vertex_index> v;
    v.reserve(m.points.size());
    for (const auto &p : m.points) v.push_back(mesh.add_vertex(Point(p[0], p[1], p[2])));
    for (const auto &t : m.tris) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);  // non-manifold faces are dropped
    return mesh;
}

std::vector<std::array<double, 3>> pca_normals(const Model &m) {
    std::vector<std::pair<Point, Vector>> pts;
    pts.reserve(m.points.size());
    for (const auto &p : m.points) pts.emplace_back(Point(p[0], p[1], p[2]), Vector(0, 0, 0));
    CGAL::pca_estimate_normals<CGAL::Sequential_tag>(
        pts, 12,
        CGAL::parameters::point_map(CGAL::First_of_pair_property_map<std::pair<Point, Vector>>())
            .normal_map(CGAL::Second_of_pair_property_map<std::pair<Point, Vector>>()));
    std::vector<std::array<double, 3>> n;
    n.reserve(pts.size());
    for (const auto &pn : pts) n.push_back({pn.second.x(), pn.second.y(), pn.second.z()});
    return n;
}

std::vector<std::array<double, 3>> point_normals(const Model &m) {
    if (m.colors.empty() && m.normals.empty()) return pca_normals(m);
    return m.normals;
}

}  // namespace mc
