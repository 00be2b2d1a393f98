// The edge-model part: see edge_model.hpp.
#include "edge_model.hpp"

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "cgal_mesh.hpp"
#include "pmesh.hpp"

namespace mc {
namespace {

constexpr double kLimitUm = 268435455.0;   // 2^28 - 1: edges.h's bound

[[noreturn]] void fail(const std::string &path, const std::string &msg) {
    throw InputError(path, InputError::Where::none, 0, msg);
}

// Six times the signed volume a closed set of faces bounds (positive: they face outwards).
double signed_volume(const Mesh &mesh, const std::vector<Mesh::Face_index> &faces) {
    double v = 0;
    for (Mesh::Face_index f : faces) {
        std::array<Vector, 3> p;
        int k = 0;
        for (Mesh::Vertex_index x : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) p[k++] = mesh.point(x) - CGAL::ORIGIN;
        v += CGAL::scalar_product(p[0], CGAL::cross_product(p[1], p[2]));
    }
    return v;
}

std::string angle_text(double deg) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", deg);
    return buf;
}

// Whether every vertex lies on or behind every face's plane, within a micrometre (faces outward).
bool convex_solid(const EdgeModel &e) {
    if (static_cast<double>(e.positions.size()) * static_cast<double>(e.faces.size()) > 1e8) return false;
    auto at = [&](uint32_t v) { return Vector(e.positions[v][0], e.positions[v][1], e.positions[v][2]); };
    for (const auto &f : e.faces) {
        const Vector a = at(f[0]), n = CGAL::cross_product(at(f[1]) - a, at(f[2]) - a);
        const double len = std::sqrt(n.squared_length());
        for (size_t v = 0; v < e.positions.size(); v++)
            if (CGAL::scalar_product(at(static_cast<uint32_t>(v)) - a, n) > len) return false;
    }
    return true;
}

// convex and line_faces (edge_model.hpp).
void mark_convex(EdgeModel &e) {
    if (!e.closed || !convex_solid(e)) return;
    std::map<std::array<uint32_t, 2>, std::vector<uint32_t>> faces_of;
    for (uint32_t f = 0; f < e.faces.size(); f++)
        for (int k = 0; k < 3; k++) {
            const uint32_t a = e.faces[f][k], b = e.faces[f][(k + 1) % 3];
            faces_of[{std::min(a, b), std::max(a, b)}].push_back(f);
        }
    std::vector<std::array<uint32_t, 2>> lf;
    for (const auto &l : e.lines) {
        auto it = faces_of.find(l);
        if (it == faces_of.end() || it->second.size() != 2) return;
        lf.push_back({it->second[0], it->second[1]});
    }
    e.convex = true;
    e.line_faces = std::move(lf);
}

}  // namespace

EdgeModel build_edge_model(const Model &m, const std::string &path, const EdgeModelOptions &opt) {
    if (!m.is_mesh) fail(path, "a point set cannot be baked as an edge model (--as edges): it has no faces");
    EdgeModel e;
    std::vector<Point> points;
    points.reserve(m.points.size());
    for (const auto &p : m.points) points.emplace_back(p[0], p[1], p[2]);
    // the faces with three distinct, non-collinear corners, oriented (outwards when closed)
    auto orient = [&](std::vector<Point> &pts, std::vector<std::array<size_t, 3>> &soup, Mesh &mesh, size_t &dropped) {
        std::vector<std::array<size_t, 3>> kept;
        for (const auto &t : soup) {
            /* no area (model.hpp zero_area): hides nothing, and its normal is noise that would make creases */
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
                zero_area(m, {static_cast<uint32_t>(t[0]), static_cast<uint32_t>(t[1]), static_cast<uint32_t>(t[2])})) {
                dropped++;
                continue;
            }
            kept.push_back(t);
        }
        soup = std::move(kept);
        // one orientation across every edge two faces share (CGAL copies a vertex where it cannot)
        PMP::orient_polygon_soup(pts, soup);
        PMP::polygon_soup_to_polygon_mesh(pts, soup, mesh);
        // the mesh's vertex i is soup point i: the lines below name points by those indices
        if (mesh.number_of_vertices() != pts.size()) throw std::logic_error("CGAL's mesh lost soup points");
        for (Mesh::Vertex_index v : mesh.vertices())
            if (mesh.point(v) != pts[v.idx()]) throw std::logic_error("CGAL's mesh reordered the soup points");
        const bool closed = !soup.empty() && CGAL::is_closed(mesh);
        if (closed) {   // outwards, one connected component at a time (a nested shell would be turned wrong)
            auto comp = mesh.add_property_map<Mesh::Face_index, size_t>("f:component", 0).first;
            const size_t n = PMP::connected_components(mesh, comp);
            std::vector<std::vector<Mesh::Face_index>> faces(n);
            for (Mesh::Face_index f : mesh.faces()) faces[comp[f]].push_back(f);
            std::vector<uint8_t> flip(n);
            for (size_t c = 0; c < n; c++) flip[c] = signed_volume(mesh, faces[c]) < 0;
            for (Mesh::Face_index f : mesh.faces())
                if (flip[comp[f]]) {
                    auto &t = soup[f.idx()];
                    std::swap(t[1], t[2]);
                }
        }
        return closed;
    };
    std::vector<std::array<size_t, 3>> soup;
    for (const auto &t : m.tris) soup.push_back({t[0], t[1], t[2]});
    const size_t before = points.size();
    Mesh mesh;
    e.closed = orient(points, soup, mesh, e.dropped_faces);
    e.copied_vertices = points.size() - before;
    if (opt.hide_faces > 0 && soup.size() > opt.hide_faces) {
        // hide behind the decimated mesh: its corners are model points; its own copies go after the full mesh's
        std::vector<Point> hp(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(before));
        std::vector<std::array<size_t, 3>> hide = decimated_faces(m, std::max<size_t>(4, opt.hide_faces / 2));
        Mesh hmesh;
        size_t hdropped = 0;
        e.closed = orient(hp, hide, hmesh, hdropped);
        const size_t offset = points.size();
        for (size_t i = before; i < hp.size(); i++) points.push_back(hp[i]);
        for (auto &t : hide)
            for (auto &c : t)
                if (c >= before) c += offset - before;
        e.copied_vertices += hp.size() - before;
        soup = std::move(hide);
    }

    std::set<std::array<uint32_t, 2>> seen;
    auto add_line = [&](uint32_t a, uint32_t b) {
        std::array<uint32_t, 2> l{std::min(a, b), std::max(a, b)};
        if (seen.insert(l).second) e.lines.push_back(l);
    };
    if (!m.lines.empty()) {
        e.file_lines = true;
        for (const auto &l : m.lines) add_line(l[0], l[1]);
    } else {
        auto sharp = mesh.add_property_map<Mesh::Edge_index, bool>("e:sharp", false).first;
        PMP::detect_sharp_edges(mesh, opt.crease_angle, sharp);
        for (Mesh::Edge_index ed : mesh.edges()) {
            const bool border = mesh.is_border(ed);
            if (!border && !sharp[ed]) continue;
            (border ? e.border_lines : e.crease_lines)++;
            add_line(mesh.vertex(ed, 0).idx(), mesh.vertex(ed, 1).idx());
        }
    }
    if (e.lines.empty())
        fail(path, m.lines.empty() ? "no edge to track: no border and no crease above --crease-angle " + angle_text(opt.crease_angle) +
                                         " degrees (a smooth closed mesh has only silhouettes)"
                                   : "no edge to track");

    // only the vertices a face or a line uses, in order of their first use
    std::vector<uint32_t> index(points.size(), UINT32_MAX);
    auto use = [&](uint32_t v) {
        if (index[v] == UINT32_MAX) {
            index[v] = static_cast<uint32_t>(e.positions.size());
            std::array<int32_t, 3> q;
            for (int k = 0; k < 3; k++) {
                const double um = std::round(points[v][k] * opt.unit * 1e6);
                if (!(std::fabs(um) <= kLimitUm))
                    fail(path, "too large for the edge model: a coordinate of " + std::to_string(points[v][k] * opt.unit) +
                                   " m is beyond +-268 m (check --unit)");
                q[k] = static_cast<int32_t>(um);
            }
            e.positions.push_back(q);
        }
        return index[v];
    };
    for (auto &l : e.lines) l = {use(l[0]), use(l[1])};
    for (auto &l : e.lines)
        if (l[0] > l[1]) std::swap(l[0], l[1]);
    e.faces.reserve(soup.size());
    for (const auto &t : soup) e.faces.push_back({use(t[0]), use(t[1]), use(t[2])});
    mark_convex(e);
    return e;
}

}  // namespace mc
