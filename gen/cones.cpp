// Normal cones of octree nodes: see cones.hpp.
#include "cones.hpp"
#include "cgal_mesh.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace mc {

using Triangle = K::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

struct ConeSource::Impl {
    std::vector<Triangle> tris;
    std::vector<Vector> normals;   // unit, outward, one per triangle
    Tree tree;
    GridCube cube;
};

ConeSource cone_source(const Model &model, const GridCube &cube) {
    ConeSource src;
    if (!model.is_mesh) return src.why = "a point set has no surface orientation", src;
    Mesh mesh = to_cgal(model);
    if (mesh.number_of_faces() != model.tris.size()) return src.why = "non-manifold faces", src;
    if (!CGAL::is_closed(mesh)) return src.why = "not closed: a border edge", src;
    if (PMP::does_self_intersect(mesh)) return src.why = "self-intersecting", src;
    PMP::orient_to_bound_a_volume(mesh);
    auto impl = std::make_shared<ConeSource::Impl>();
    for (auto f : mesh.faces()) {
        auto h = mesh.halfedge(f);
        const Point &a = mesh.point(mesh.source(h)), &b = mesh.point(mesh.target(h)),
                    &c = mesh.point(mesh.target(mesh.next(h)));
        const Vector n = CGAL::cross_product(b - a, c - a);
        const double len = std::sqrt(n.squared_length());
        if (!(len > 0)) continue;   // no area: no samples on it, no direction
        impl->tris.emplace_back(a, b, c);
        impl->normals.push_back(n / len);
    }
    impl->tree.insert(impl->tris.begin(), impl->tris.end());
    impl->tree.build();
    impl->cube = cube;
    src.impl = impl;
    return src;
}

namespace {

struct Node {
    std::array<uint32_t, 3> at;   // integer coordinates at its level
    uint32_t below2 = 0, below3 = 0;   // nodes of its subtree two and three levels down
};

// Every node of levels 0 .. depth - 1, level by level in depth-first order (as the levels are
// stored: a level's nodes in order are its parents' children in order).
std::vector<std::vector<Node>> nodes_of(const Octree &t) {
    std::vector<std::vector<Node>> at(t.depth);
    std::vector<size_t> cursor(t.depth, 0);
    // depth first; a node's subtree counts are added to its ancestors when it is met
    struct Item { std::array<uint32_t, 3> p; int l; };
    std::vector<Item> stack{{{0, 0, 0}, 0}};
    std::vector<size_t> path;   // index of the current ancestor at each level
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        path.resize(static_cast<size_t>(it.l));
        if (it.l >= 2) at[it.l - 2][path[it.l - 2]].below2++;
        if (it.l >= 3) at[it.l - 3][path[it.l - 3]].below3++;
        if (it.l < t.depth) {
            path.push_back(at[it.l].size());
            at[it.l].push_back({it.p});
        }
        if (it.l + 1 > t.depth || it.l == t.depth) continue;
        const uint8_t m = t.masks[it.l][cursor[it.l]++];
        for (int k = 7; k >= 0; k--)   // pushed last first: popped in child order
            if (m >> k & 1)
                stack.push_back({{2 * it.p[0] + (k & 1), 2 * it.p[1] + (k >> 1 & 1), 2 * it.p[2] + (k >> 2 & 1)}, it.l + 1});
    }
    return at;
}

// The record of the cone around normals ns: axis = their mean direction, quantized; the half-angle
// measured about the quantized axis.
std::array<uint8_t, 4> cone_record(const std::vector<Vector> &ns) {
    std::array<uint8_t, 4> never{0, 0, 0, 255};
    Vector sum(0, 0, 0);
    for (const Vector &n : ns) sum = sum + n;
    const double len = std::sqrt(sum.squared_length());
    if (ns.empty() || !(len > 1e-9 * static_cast<double>(ns.size()))) return never;
    int8_t a[3];
    const double c[3] = {sum.x() / len, sum.y() / len, sum.z() / len};
    for (int i = 0; i < 3; i++) a[i] = static_cast<int8_t>(std::lround(127 * c[i]));
    const Vector A(a[0], a[1], a[2]);
    const double alen = std::sqrt(A.squared_length());
    double lo = 1;   // least cosine between a normal and the quantized axis
    for (const Vector &n : ns) lo = std::min(lo, (n * A) / alen);
    if (!(lo > 1e-6)) return never;   // wider than a half-space
    // sin of the half-angle times |A|, rounded up, with room for the cosine's rounding
    const double s = std::sqrt(std::max(0.0, 1 - lo * lo)) * alen + 1e-6 * alen;
    const double up = std::ceil(s);
    if (up >= 255) return never;
    return {static_cast<uint8_t>(a[0]), static_cast<uint8_t>(a[1]), static_cast<uint8_t>(a[2]), static_cast<uint8_t>(up)};
}

}  // namespace

void add_cones(Octree &t, const ConeSource &src) {
    t.cones.assign(t.depth + 1, {});
    if (!src.impl || t.depth < 4) return;
    const ConeSource::Impl &s = *src.impl;
    const std::vector<std::vector<Node>> at = nodes_of(t);
    std::vector<Primitive::Id> hits;
    std::vector<Vector> ns;
    for (int l = 1; l <= t.depth - 3; l++) {
        const double side = s.cube.side / static_cast<double>(1u << l), pad = 1e-9 * s.cube.side;
        for (const Node &n : at[l]) {
            const auto &p = n.at;
            double lo[3], hi[3];
            for (int i = 0; i < 3; i++)
                lo[i] = s.cube.origin[i] + p[i] * side - pad, hi[i] = s.cube.origin[i] + (p[i] + 1) * side + pad;
            hits.clear();
            s.tree.all_intersected_primitives(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]),
                                              std::back_inserter(hits));
            ns.clear();
            for (auto it : hits) ns.push_back(s.normals[static_cast<size_t>(it - s.tris.begin())]);
            const auto r = cone_record(ns);
            t.cones[l].insert(t.cones[l].end(), r.begin(), r.end());
            // what a culled subtree steps over (octree.h): at most 64 masks, 512 leaves
            t.cones[l].push_back(static_cast<uint8_t>(n.below2));
            t.cones[l].push_back(static_cast<uint8_t>(n.below3 & 0xFF));
            t.cones[l].push_back(static_cast<uint8_t>(n.below3 >> 8));
        }
    }
}

}  // namespace mc
