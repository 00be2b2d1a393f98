// The progressive-mesh part: see pmesh.hpp.
// OpenMesh's property containers warn of a default-constructed point gcc cannot see initialised
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "pmesh.hpp"
#include "modelc/mesh_lines.h"   // MC_MESH_SHADES, MC_MESH_PALETTE_SIZE

// OpenMesh's headers are read with NDEBUG: their property accessors otherwise assert, on every
// call, that the property's type name is the one asked for (a string compare), which took a sixth
// of the decimation's time. The checks are of OpenMesh's own bookkeeping, not of the input; the
// fuzzers' builds keep them (MC_OPENMESH_ASSERTS, Makefile FUZZ_CXXFLAGS).
#if !defined(NDEBUG) && !defined(MC_OPENMESH_ASSERTS)
#define NDEBUG
#define MC_OPENMESH_NDEBUG
#endif
#include <cassert>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#ifdef MC_OPENMESH_NDEBUG
#undef NDEBUG
#undef MC_OPENMESH_NDEBUG
#include <cassert>   // assert as the build has it again, for what follows
#endif

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>
#include <unordered_map>

namespace mc {
namespace {

struct Traits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
    FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

// A binary module that allows every collapse and writes down each one made: the removed vertex,
// the vertex it went into, and the faces that went with the edge.
template <class MeshT>
class ModRecordT : public OpenMesh::Decimater::ModBaseT<MeshT> {
  public:
    DECIMATING_MODULE(ModRecordT, MeshT, Record);
    struct Collapse { int v0, v1, fl, fr; };
    explicit ModRecordT(MeshT &m) : Base(m, true) {}
    void postprocess_collapse(const CollapseInfo &ci) override {
        log.push_back({ci.v0.idx(), ci.v1.idx(), ci.fl.idx(), ci.fr.idx()});
    }
    std::vector<Collapse> log;
};

uint16_t quantize(double u) {
    const long long q = std::llround((u + 0.5) * 65536.0);
    return static_cast<uint16_t>(std::clamp(q, 0LL, 65535LL));
}

// The full mesh in OpenMesh: every face with distinct corners, non-manifold ones on their own
// vertices (pmesh.hpp).
struct FullMesh {
    Mesh mesh;
    std::vector<int> vertex_point;                  // OpenMesh vertex -> model point
    std::vector<std::array<int, 3>> face_corners;   // OpenMesh face -> its corners in the full mesh
    size_t dropped_faces = 0, split_vertices = 0;
};

void make_mesh(const Model &m, FullMesh &fm) {
    if (!m.is_mesh || m.tris.empty()) throw std::invalid_argument("a point set has no faces to build a mesh from");
    Mesh &mesh = fm.mesh;
    for (const auto &p : m.points) {
        mesh.add_vertex(Mesh::Point(p[0], p[1], p[2]));
        fm.vertex_point.push_back(static_cast<int>(fm.vertex_point.size()));
    }
    omerr().disable();   // OpenMesh reports each face it refuses; they are counted instead
    for (const auto &t : m.tris) {
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) { fm.dropped_faces++; continue; }
        std::array<Mesh::VertexHandle, 3> vh;
        for (int k = 0; k < 3; k++) vh[k] = Mesh::VertexHandle(static_cast<int>(t[k]));
        Mesh::FaceHandle f = mesh.add_face(vh[0], vh[1], vh[2]);
        if (!f.is_valid()) {
            for (int k = 0; k < 3; k++) {
                vh[k] = mesh.add_vertex(mesh.point(vh[k]));
                fm.vertex_point.push_back(static_cast<int>(t[k]));
                fm.split_vertices++;
            }
            f = mesh.add_face(vh[0], vh[1], vh[2]);
        }
        if (!f.is_valid()) {
            omerr().enable();
            throw std::logic_error("OpenMesh refused an isolated triangle");
        }
        fm.face_corners.push_back({vh[0].idx(), vh[1].idx(), vh[2].idx()});
    }
    omerr().enable();
    if (fm.face_corners.empty()) throw std::invalid_argument("every face has a repeated corner: nothing to draw");
    mesh.request_face_normals();
    mesh.update_face_normals();
}

// Collapses half-edges of fm.mesh by quadric error, no face normal flipped, until `vertices` are
// left (vertices no face uses included) or no collapse is legal; returns the record of collapses.
std::vector<ModRecordT<Mesh>::Collapse> decimate(FullMesh &fm, size_t vertices) {
    Mesh &mesh = fm.mesh;
    OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
    OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle flipping;
    ModRecordT<Mesh>::Handle record;
    dec.add(quadric);
    dec.add(flipping);
    dec.add(record);
    dec.module(quadric).unset_max_err();
    if (!dec.initialize()) throw std::logic_error("OpenMesh's decimater did not initialize");
    dec.decimate_to(vertices);
    return dec.module(record).log;
}

size_t isolated_vertices(const Mesh &mesh) {
    size_t n = 0;
    for (const auto &v : mesh.vertices()) n += mesh.is_isolated(v);
    return n;
}

// Starts each split's faces at the corner that is the split vertex or its parent at the split's
// level, so that edge 0 is the edge the collapse removes and edges 1 and 2 the two that merge
// (the runtime's neighbour search, mesh_lines.h, relies on it).
void orient_split_faces(PMesh &pm) {
    const uint32_t V = static_cast<uint32_t>(pm.vertices());
    std::vector<int64_t> split_of(V, -1);   // -1: a base vertex
    for (size_t s = 0; s < pm.split_vertex.size(); s++) split_of[pm.split_vertex[s]] = static_cast<int64_t>(s);
    size_t f = pm.base_faces;
    for (size_t s = 0; s < pm.split_vertex.size(); s++) {
        const uint32_t v = pm.split_vertex[s], p = pm.parent[v];
        for (unsigned i = 0; i < pm.split_faces[s]; i++, f++) {
            auto &c = pm.faces[f];
            std::array<uint32_t, 3> at;   // the corners at level s
            for (int j = 0; j < 3; j++) {
                uint32_t x = c[j];
                while (split_of[x] > static_cast<int64_t>(s)) x = pm.parent[x];
                at[j] = x;
            }
            int k = 0;
            while (k < 3 && !((at[k] == v && at[(k + 1) % 3] == p) || (at[k] == p && at[(k + 1) % 3] == v))) k++;
            if (k == 3) throw std::logic_error("progressive mesh: a split's face lacks the split edge");
            std::rotate(c.begin(), c.begin() + k, c.end());
        }
    }
}

// The half-edge across each face edge in the full level: the face holding the same two corners the
// other way round (the full level is manifold: OpenMesh built it).
void link_half_edges(PMesh &pm) {
    std::unordered_map<uint64_t, uint32_t> directed;
    auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
    for (size_t f = 0; f < pm.faces.size(); f++)
        for (uint32_t k = 0; k < 3; k++)
            if (!directed.emplace(key(pm.faces[f][k], pm.faces[f][(k + 1) % 3]), uint32_t(4 * f + k)).second)
                throw std::logic_error("progressive mesh: a directed edge used twice");
    pm.opposite.assign(pm.faces.size(), {kNoHalfEdge, kNoHalfEdge, kNoHalfEdge});
    for (size_t f = 0; f < pm.faces.size(); f++)
        for (uint32_t k = 0; k < 3; k++) {
            auto it = directed.find(key(pm.faces[f][(k + 1) % 3], pm.faces[f][k]));
            if (it != directed.end()) pm.opposite[f][k] = it->second;
        }
}

std::array<double, 3> face_normal(const PMesh &pm, size_t f) {
    std::array<std::array<double, 3>, 3> p;
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) p[j][i] = pm.positions[pm.faces[f][j]][i];
    const double a[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double b[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Each full-level edge once, as the half-edge of its first-created face, borders first, then the
// sharpest first (cosine of the angle between the normals, ascending; ties by half-edge).
void order_edges(PMesh &pm) {
    std::vector<std::pair<double, uint32_t>> keyed;
    for (size_t f = 0; f < pm.faces.size(); f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = uint32_t(4 * f + k), o = pm.opposite[f][k];
            if (o != kNoHalfEdge && o < h) continue;
            double c = -2.0;   // a border
            if (o != kNoHalfEdge) {
                const auto n = face_normal(pm, f), m = face_normal(pm, o / 4);
                const double l = std::sqrt((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]));
                c = l > 0 ? (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]) / l : 1.0;
            }
            keyed.push_back({c, h});
        }
    std::sort(keyed.begin(), keyed.end());
    pm.edge_order.clear();
    for (const auto &e : keyed) pm.edge_order.push_back(e.second);
}

}  // namespace

PMesh build_pmesh(const Model &m, const GridCube &cube, const PMeshOptions &opt) {
    PMesh pm;
    FullMesh fm;
    make_mesh(m, fm);
    Mesh &mesh = fm.mesh;
    const std::vector<int> &vertex_point = fm.vertex_point;
    const std::vector<std::array<int, 3>> &face_corners = fm.face_corners;
    pm.dropped_faces = fm.dropped_faces;
    pm.split_vertices = fm.split_vertices;
    const int nv_all = static_cast<int>(mesh.n_vertices());

    // ---- decimation, recorded
    const auto log = decimate(fm, 1 + isolated_vertices(mesh));

    // ---- max_faces: the finest collapses applied for good
    const size_t F_all = face_corners.size();
    size_t k = 0, faces_now = F_all;
    auto removed = [&](const ModRecordT<Mesh>::Collapse &c) { return size_t(c.fl >= 0) + size_t(c.fr >= 0); };
    if (opt.max_faces)
        while (faces_now > opt.max_faces && k < log.size()) faces_now -= removed(log[k++]);
    pm.capped_collapses = k;

    // ---- the forest: parent of each removed vertex; roots are the vertices never removed
    std::vector<int> parent(nv_all, -1), removed_at(nv_all, -1), face_removed_at(F_all, -1);
    for (size_t i = 0; i < log.size(); i++) {
        parent[log[i].v0] = log[i].v1;
        removed_at[log[i].v0] = static_cast<int>(i);
        if (log[i].fl >= 0) face_removed_at[log[i].fl] = static_cast<int>(i);
        if (log[i].fr >= 0) face_removed_at[log[i].fr] = static_cast<int>(i);
    }
    // a vertex of the full level: used by a face and not removed by a capped collapse
    std::vector<char> used_v(nv_all, 0);
    for (const auto &fc : face_corners)
        for (int c : fc) used_v[c] = 1;
    auto in_full = [&](int v) { return used_v[v] && (removed_at[v] < 0 || removed_at[v] >= static_cast<int>(k)); };
    // the vertex of the full level a vertex went into through the capped collapses
    auto full_of = [&](int v) {
        while (removed_at[v] >= 0 && removed_at[v] < static_cast<int>(k)) v = parent[v];
        return v;
    };
    // children in split order: splits are the collapses reversed, so the last collapse splits first
    std::vector<std::vector<int>> children(nv_all);
    std::vector<int> roots;
    for (int v = 0; v < nv_all; v++)
        if (in_full(v) && removed_at[v] < 0) roots.push_back(v);
    for (size_t i = log.size(); i-- > k;) children[log[i].v1].push_back(log[i].v0);

    // ---- depth-first numbering
    std::vector<uint32_t> number(nv_all, UINT32_MAX);
    std::vector<int> order;   // number -> OpenMesh vertex
    std::vector<std::pair<int, size_t>> stack;
    for (int r : roots) {
        stack.push_back({r, 0});
        number[r] = static_cast<uint32_t>(order.size());
        order.push_back(r);
        while (!stack.empty()) {
            auto &[v, next] = stack.back();
            if (next < children[v].size()) {
                int c = children[v][next++];
                number[c] = static_cast<uint32_t>(order.size());
                order.push_back(c);
                stack.push_back({c, 0});
            } else {
                stack.pop_back();
            }
        }
    }
    const uint32_t V = static_cast<uint32_t>(order.size());
    pm.base_vertices = static_cast<uint32_t>(roots.size());
    pm.positions.resize(V);
    pm.parent.resize(V);
    pm.size.assign(V, 1);
    for (uint32_t i = 0; i < V; i++) {
        const int v = order[i];
        const auto u = cube.to_unit(m.points[vertex_point[v]]);
        pm.positions[i] = {quantize(u[0]), quantize(u[1]), quantize(u[2])};
        pm.parent[i] = removed_at[v] < 0 ? i : number[parent[v]];
    }
    for (uint32_t i = V; i-- > 0;)   // children come after their parent
        if (pm.parent[i] != i) pm.size[pm.parent[i]] += pm.size[i];

    // ---- faces: the base's, then each split's
    auto corners_of = [&](size_t f) {
        std::array<uint32_t, 3> c;
        for (int j = 0; j < 3; j++) c[j] = number[full_of(face_corners[f][j])];
        return c;
    };
    for (size_t f = 0; f < F_all; f++)
        if (face_removed_at[f] < 0) pm.faces.push_back(corners_of(f));
    pm.base_faces = static_cast<uint32_t>(pm.faces.size());
    for (size_t i = log.size(); i-- > k;) {
        pm.split_vertex.push_back(number[log[i].v0]);
        pm.split_faces.push_back(static_cast<uint8_t>(removed(log[i])));
        if (log[i].fl >= 0) pm.faces.push_back(corners_of(log[i].fl));
        if (log[i].fr >= 0) pm.faces.push_back(corners_of(log[i].fr));
    }
    orient_split_faces(pm);
    link_half_edges(pm);
    order_edges(pm);
    pm.crease_cos = static_cast<int16_t>(std::lround(16384.0 * std::cos(opt.crease_angle * M_PI / 180.0)));
    for (int k = 0; k < MC_MESH_SHADES; k++) {
        const auto g = static_cast<uint8_t>(std::lround(255.0 * (0.15 + 0.85 * k / (MC_MESH_SHADES - 1))));
        pm.palette.push_back({g, g, g});
    }
    // the line drawings' (mesh_lines.h): paper, silhouettes, creases, borders
    pm.palette.push_back({255, 255, 255});
    pm.palette.push_back({0, 0, 0});
    pm.palette.push_back({110, 110, 110});
    pm.palette.push_back({30, 60, 150});
    static_assert(MC_MESH_PALETTE_SIZE == MC_MESH_SHADES + 4, "the line colours in mesh_lines.h");
    if (pm.split_vertex.size() + pm.base_vertices != V || pm.faces.size() != faces_now)
        throw std::logic_error("progressive mesh: the collapse record does not add up");
    return pm;
}

void dump_decimated(const Model &m, const GridCube &cube, size_t vertices, std::ostream &out) {
    FullMesh fm;
    make_mesh(m, fm);
    decimate(fm, vertices + isolated_vertices(fm.mesh));
    for (const auto &f : fm.mesh.faces()) {
        if (fm.mesh.status(f).deleted()) continue;
        for (const auto &v : fm.mesh.fv_range(f)) {
            const auto u = cube.to_unit(m.points[fm.vertex_point[v.idx()]]);
            out << quantize(u[0]) << ' ' << quantize(u[1]) << ' ' << quantize(u[2]) << ' ';
        }
        out << '\n';
    }
}

std::vector<std::array<size_t, 3>> decimated_faces(const Model &m, size_t vertices) {
    FullMesh fm;
    make_mesh(m, fm);
    decimate(fm, vertices + isolated_vertices(fm.mesh));
    std::vector<std::array<size_t, 3>> faces;
    for (const auto &f : fm.mesh.faces()) {
        if (fm.mesh.status(f).deleted()) continue;
        std::array<size_t, 3> t;
        int k = 0;
        for (const auto &v : fm.mesh.fv_range(f)) t[k++] = static_cast<size_t>(fm.vertex_point[v.idx()]);
        faces.push_back(t);
    }
    return faces;
}

}  // namespace mc
