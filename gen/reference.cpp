// --dump-reference (see reference.hpp): what the tests' mesh reference renderer needs.
#include "reference.hpp"

#include "cgal_mesh.hpp"
#include "light.hpp"

#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/compute_average_spacing.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace mc {
namespace {

double frontal_light(const std::array<double, 3> &n) { return mc::frontal_light(n[0], n[1], n[2]); }

struct Writer {
    std::FILE *f;
    void bytes(const void *p, size_t n) {
        if (std::fwrite(p, 1, n, f) != n) throw std::runtime_error("write failed");
    }
    void u32(uint32_t v) { bytes(&v, 4); }
    void f64(double v) { bytes(&v, 8); }
};

}  // namespace

void dump_reference(const Model &m, const Voxels &vox, const std::string &file) {
    const GridCube cube = vox.cube();
    const double side = cube.side;
    auto norm = [&](const std::array<double, 3> &p) { return cube.to_unit(p); };
    std::vector<std::array<double, 3>> pos, nrm, rgb;
    std::vector<std::array<uint32_t, 3>> tris;
    uint32_t shade = 0;
    double radius = 0;
    if (m.is_mesh) {
        // the voxelizer's mesh: the same faces kept, the same vertex normals
        Mesh mesh = to_cgal(m);
        auto vnormal = mesh.add_property_map<Mesh::Vertex_index, Vector>("v:n", Vector(0, 0, 0)).first;
        PMP::compute_vertex_normals(mesh, vnormal);
        shade = m.colors.empty() ? 1 : 0;
        for (auto vi : mesh.vertices()) {
            const Point &p = mesh.point(vi);
            pos.push_back(norm({p.x(), p.y(), p.z()}));
            nrm.push_back({vnormal[vi].x(), vnormal[vi].y(), vnormal[vi].z()});
            if (shade) rgb.push_back({0, 0, 0});
            else rgb.push_back({double(m.colors[vi.idx()][0]), double(m.colors[vi.idx()][1]), double(m.colors[vi.idx()][2])});
        }
        for (auto f : mesh.faces()) {
            auto h = mesh.halfedge(f);
            tris.push_back({static_cast<uint32_t>(mesh.source(h).idx()), static_cast<uint32_t>(mesh.target(h).idx()),
                            static_cast<uint32_t>(mesh.target(mesh.next(h)).idx())});
        }
    } else {
        // as the voxelizer: file colours, else the frontal light of point_normals
        const std::vector<std::array<double, 3>> normals = point_normals(m);
        std::vector<Point> pts;
        for (const auto &p : m.points) pts.emplace_back(p[0], p[1], p[2]);
        for (size_t i = 0; i < m.points.size(); i++) {
            pos.push_back(norm(m.points[i]));
            nrm.push_back(normals.empty() ? std::array<double, 3>{0, 0, 0} : normals[i]);
            if (!m.colors.empty()) rgb.push_back({double(m.colors[i][0]), double(m.colors[i][1]), double(m.colors[i][2])});
            else { double g = 255.0 * frontal_light(normals[i]); rgb.push_back({g, g, g}); }
        }
        // splat radius, in cube sides: 3/4 of the mean distance to the 6 nearest neighbours, so that the
        // discs of neighbouring points overlap and close the surface (half of it leaves gaps)
        radius = 0.75 * CGAL::compute_average_spacing<CGAL::Sequential_tag>(pts, 6) / side;
    }

    const std::string tmp = file + ".tmp";
    std::FILE *f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error("--dump-reference " + file + ": cannot write: " + std::strerror(errno));
    try {
        Writer w{f};
        w.bytes("MCREF01\n", 8);
        w.u32(m.is_mesh ? 0 : 1);
        w.u32(shade);
        w.u32(static_cast<uint32_t>(pos.size()));
        w.u32(static_cast<uint32_t>(tris.size()));
        w.f64(side);
        for (int a = 0; a < 3; a++) w.f64(vox.origin[a]);
        w.f64(radius);
        for (size_t i = 0; i < pos.size(); i++) {
            for (int a = 0; a < 3; a++) w.f64(pos[i][a]);
            for (int a = 0; a < 3; a++) w.f64(nrm[i][a]);
            for (int a = 0; a < 3; a++) w.f64(rgb[i][a]);
        }
        for (const auto &t : tris)
            for (int a = 0; a < 3; a++) w.u32(t[a]);
    } catch (...) {
        std::fclose(f);
        std::remove(tmp.c_str());
        throw std::runtime_error("--dump-reference " + file + ": write failed");
    }
    if (std::fclose(f) != 0) {
        std::remove(tmp.c_str());
        throw std::runtime_error("--dump-reference " + file + ": write failed");
    }
    std::filesystem::rename(tmp, file);
}

}  // namespace mc
