// load_model(): validating scan (validate.cpp), then OpenMesh for meshes or CGAL for point sets,
// then checks that the library read what the scan saw and that the model is usable.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

// OpenMesh's property vectors and CGAL's default property maps copy default-constructed
// (uninitialised) values, which GCC's uninitialized warnings report from inside their headers.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <CGAL/IO/read_points.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>
#pragma GCC diagnostic pop

#include "model.hpp"
#include "validate.hpp"

namespace mc {
namespace {

[[noreturn]] void fail(const std::string &path, const std::string &msg) {
    throw InputError(path, InputError::Where::none, 0, msg);
}

// Only regular files: a directory, FIFO or device (/dev/zero) would block or never end.
void check_readable(const std::string &path) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) fail(path, std::string("cannot open: ") + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) fail(path, "cannot open: Is a directory");
    if (!S_ISREG(st.st_mode)) fail(path, "cannot open: not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
}

// OpenMesh and CGAL print warnings on std::cerr / std::cout, but modelc must print exactly one
// line on error. Their output is captured while they run and only quoted in our own messages.
class Capture {
public:
    Capture()
        : err_(std::cerr.rdbuf(buf_.rdbuf())), out_(std::cout.rdbuf(buf_.rdbuf())),
          log_(std::clog.rdbuf(buf_.rdbuf())) {}
    ~Capture() {
        std::cerr.rdbuf(err_);
        std::cout.rdbuf(out_);
        std::clog.rdbuf(log_);
    }
    Capture(const Capture &) = delete;
    Capture &operator=(const Capture &) = delete;

    std::string said() const {  // the libraries' first line, if any, for an error message
        std::string s = buf_.str();
        s = s.substr(0, s.find('\n'));
        return s.empty() ? s : " (it said: " + s.substr(0, 120) + ")";
    }

private:
    std::ostringstream buf_;  // declared first: constructed before the streams are redirected to it
    std::streambuf *err_, *out_, *log_;
};

// Runs a library reader; its exceptions (a CGAL assertion, ...) become InputErrors like any other
// read failure. Running out of memory stays std::bad_alloc, which modelc reports as such.
template <class Read>
bool guarded(const std::string &path, const char *library, Read read) {
    try {
        return read();
    } catch (const std::bad_alloc &) {
        throw;
    } catch (const std::exception &e) {
        fail(path, std::string(library) + " failed on the file although it passed validation: " +
                       std::string(e.what()).substr(0, 200));
    }
}

// Clean copy of an input the library would misread as it is (see Scan::rewrite); removed again
// when the load is done.
class CleanCopy {
public:
    CleanCopy(const std::string &input, Format f) {
        const char *dir = std::getenv("TMPDIR");
        const std::string ext = extension_of(f);
        std::string name = std::string(dir && *dir ? dir : "/tmp") + "/modelc-XXXXXX" + ext;
        int fd = mkstemps(name.data(), static_cast<int>(ext.size()));
        if (fd < 0) fail(input, std::string("cannot create a temporary file: ") + std::strerror(errno));
        close(fd);
        path_ = name;
        try {
            std::ofstream out(path_, std::ios::binary);
            scan_file(input, f, &out);
            out.close();
            if (!out) fail(input, "cannot write the temporary file " + path_);
        } catch (...) {  // the destructor does not run for a constructor that throws
            std::remove(path_.c_str());
            throw;
        }
    }
    ~CleanCopy() { std::remove(path_.c_str()); }
    CleanCopy(const CleanCopy &) = delete;
    CleanCopy &operator=(const CleanCopy &) = delete;
    const std::string &path() const { return path_; }

private:
    std::string path_;
};

// ------------------------------------------------------------------------- meshes (OpenMesh)

struct MeshTraits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
};
using Mesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

// OpenMesh's importer attaches a face it cannot add to the manifold mesh through copies of its
// vertices, flagged fixed_nonmanifold. Map each copy back to the vertex at the same position, so
// the model keeps the file's vertices. Returns the model index of every mesh vertex; KEPT gets the
// mesh vertices that are not copies.
std::vector<uint32_t> map_copies(const Mesh &mesh, std::vector<Mesh::VertexHandle> &kept) {
    std::vector<uint32_t> index(mesh.n_vertices());
    std::map<std::array<double, 3>, uint32_t> at;
    bool copies = false;
    for (auto v : mesh.vertices()) {
        if (mesh.status(v).fixed_nonmanifold()) {
            copies = true;
            continue;
        }
        index[v.idx()] = static_cast<uint32_t>(kept.size());
        kept.push_back(v);
    }
    if (!copies) return index;
    for (auto v : kept) {
        const auto &p = mesh.point(v);
        at.emplace(std::array<double, 3>{p[0], p[1], p[2]}, index[v.idx()]);
    }
    for (auto v : mesh.vertices()) {
        if (!mesh.status(v).fixed_nonmanifold()) continue;
        const auto &p = mesh.point(v);
        auto it = at.find({p[0], p[1], p[2]});
        index[v.idx()] = it == at.end() ? UINT32_MAX : it->second;
    }
    return index;
}

Model read_mesh(const std::string &path, const std::string &file, Format f, const Scan &s) {
    Mesh mesh;
    mesh.request_vertex_colors();
    mesh.request_vertex_status();  // marks the vertex copies, see map_copies()
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexColor;
    bool ok = false;
    std::string said;
    {
        Capture capture;
        ok = guarded(path, "OpenMesh", [&] { return OpenMesh::IO::read_mesh(mesh, file, opt); });
        said = capture.said();
    }
    if (!ok) fail(path, "OpenMesh could not read the file although it passed validation" + said);
    // STL: triangles with corners within FLT_MIN of each other may or may not be merged away.
    const bool faces_ok = f == Format::stl ? mesh.n_faces() >= s.faces && mesh.n_faces() <= s.faces_in_file
                                           : mesh.n_faces() == s.faces;
    if (!faces_ok)
        fail(path, "OpenMesh read " + std::to_string(mesh.n_faces()) + " faces but the file has " +
                       std::to_string(s.faces) + " usable faces" + said);

    std::vector<Mesh::VertexHandle> kept;
    const std::vector<uint32_t> index = map_copies(mesh, kept);
    // STL corners are merged by the reader, so only the other formats have a vertex count to match.
    if (f != Format::stl && kept.size() != s.points)
        fail(path, "OpenMesh read " + std::to_string(kept.size()) + " vertices but the file has " +
                       std::to_string(s.points) + said);
    if (s.colors && !opt.check(OpenMesh::IO::Options::VertexColor))
        fail(path, "OpenMesh did not read the vertex colours" + said);

    Model m;
    m.is_mesh = true;
    for (auto v : kept) {
        const auto &p = mesh.point(v);
        m.points.push_back({p[0], p[1], p[2]});
        if (s.colors) {
            const auto &c = mesh.color(v);
            m.colors.push_back({c[0], c[1], c[2]});
        }
    }
    std::vector<uint32_t> corner;
    for (auto face : mesh.faces()) {
        corner.clear();
        for (auto v : mesh.fv_range(face)) corner.push_back(index[v.idx()]);
        for (uint32_t c : corner)
            if (c == UINT32_MAX) fail(path, "OpenMesh created a vertex that is not in the file" + said);
        for (size_t k = 1; k + 1 < corner.size(); ++k) m.tris.push_back({corner[0], corner[k], corner[k + 1]});
    }
    return m;
}

// ------------------------------------------------------------------------- point sets (CGAL)

using Kernel = CGAL::Simple_cartesian<double>;
using Record = std::tuple<Kernel::Point_3, Kernel::Vector_3, std::array<double, 3>>;
using PointMap = CGAL::Nth_of_tuple_property_map<0, Record>;
using NormalMap = CGAL::Nth_of_tuple_property_map<1, Record>;
using ColorMap = CGAL::Nth_of_tuple_property_map<2, Record>;

struct MakeColor {
    template <class T>
    std::array<double, 3> operator()(T r, T g, T b) const {
        return {static_cast<double>(r), static_cast<double>(g), static_cast<double>(b)};
    }
};

// CGAL requires each PLY property to be requested with exactly its type in the file.
template <class T>
auto color_reader() {
    return std::make_tuple(ColorMap(), MakeColor(), CGAL::IO::PLY_property<T>("red"),
                           CGAL::IO::PLY_property<T>("green"), CGAL::IO::PLY_property<T>("blue"));
}

template <class... Extra>
bool read_ply_records(std::istream &in, std::vector<Record> &out, bool normals, Extra &&...extra) {
    auto sink = std::back_inserter(out);
    if (normals)
        return CGAL::IO::read_PLY_with_properties(in, sink, CGAL::IO::make_ply_point_reader(PointMap()),
                                                  CGAL::IO::make_ply_normal_reader(NormalMap()),
                                                  std::forward<Extra>(extra)...);
    return CGAL::IO::read_PLY_with_properties(in, sink, CGAL::IO::make_ply_point_reader(PointMap()),
                                              std::forward<Extra>(extra)...);
}

bool read_records(std::istream &in, Format f, const Scan &s, std::vector<Record> &out) {
    if (f == Format::xyz && s.normals)
        return CGAL::IO::read_XYZ(in, std::back_inserter(out),
                                  CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()));
    if (f == Format::xyz) return CGAL::IO::read_XYZ(in, std::back_inserter(out), CGAL::parameters::point_map(PointMap()));
    if (!s.colors) return read_ply_records(in, out, s.normals);
    if (s.colors_float) return read_ply_records(in, out, s.normals, color_reader<float>());
    return read_ply_records(in, out, s.normals, color_reader<std::uint8_t>());
}

Model read_points(const std::string &path, const std::string &file, Format f, const Scan &s) {
    std::vector<Record> records;
    bool ok = false;
    std::string said;
    {
        std::ifstream in(file, std::ios::binary);
        Capture capture;
        ok = in && guarded(path, "CGAL", [&] { return read_records(in, f, s, records); });
        said = capture.said();
    }
    if (!ok) fail(path, "CGAL could not read the file although it passed validation" + said);
    if (records.size() != s.points)
        fail(path, "CGAL read " + std::to_string(records.size()) + " points but the file has " +
                       std::to_string(s.points) + said);
    Model m;
    m.is_mesh = false;
    for (const Record &r : records) {
        const auto &p = std::get<0>(r);
        m.points.push_back({p.x(), p.y(), p.z()});
        if (s.normals) {
            const auto &n = std::get<1>(r);
            m.normals.push_back({n.x(), n.y(), n.z()});
        }
        if (s.colors) {
            const auto &c = std::get<2>(r);
            auto channel = [&](double v) { return static_cast<uint8_t>(s.colors_float ? std::lround(v * 255) : v); };
            m.colors.push_back({channel(c[0]), channel(c[1]), channel(c[2])});
        }
    }
    return m;
}

// ------------------------------------------------------------------------- checks on the result

// The library's coordinates must match the scan's bounding box up to float rounding: OpenMesh
// reads through floats, and a misread (wrong offset, wrong column) moves the box.
void check_box(const std::string &path, const Model &m, const Scan &s, const char *library) {
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const auto &p : m.points)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    double scale = 0;
    for (int k = 0; k < 3; ++k) scale = std::max({scale, std::fabs(s.lo[k]), std::fabs(s.hi[k])});
    const double tolerance = 1e-6 * scale;
    for (int k = 0; k < 3; ++k)
        if (!(std::fabs(lo[k] - s.lo[k]) <= tolerance && std::fabs(hi[k] - s.hi[k]) <= tolerance))
            fail(path, std::string(library) + " read coordinates that differ from the file");
}

// Zero area, relative to the triangle's own size: the coordinates went through float, so a
// triangle whose corners lie on a line rarely gives an exact zero.
bool zero_area(const Model &m, const std::array<uint32_t, 3> &t) {
    const auto &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    auto len2 = [](const double *e) { return e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; };
    const double longest2 = std::max({len2(u), len2(v), len2(w)});
    return std::sqrt(x * x + y * y + z * z) <= 1e-6 * longest2;  // |u x v| is twice the area
}

// Whole-model problems (Where::none): nothing to draw.
void check_usable(const std::string &path, const Model &m) {
    if (m.points.empty()) fail(path, m.is_mesh ? "model has no vertices" : "point set has no points");
    if (!m.is_mesh) {
        if (std::all_of(m.points.begin(), m.points.end(), [&m](const auto &p) { return p == m.points[0]; }))
            fail(path, "all " + std::to_string(m.points.size()) + " points are identical (zero extent)");
        return;
    }
    if (m.tris.empty()) fail(path, "mesh has no usable faces (every face repeats a vertex)");
    for (const auto &t : m.tris)
        if (!zero_area(m, t)) return;
    fail(path, "all " + std::to_string(m.tris.size()) + " triangles have zero area");
}

}  // namespace

Model load_model(const std::string &path) {
    check_readable(path);
    const Format f = format_of(path);
    const Scan s = scan_file(path, f);
    Model m;
    if (s.rewrite) {
        CleanCopy copy(path, f);
        m = s.is_mesh ? read_mesh(path, copy.path(), f, s) : read_points(path, copy.path(), f, s);
    } else {
        m = s.is_mesh ? read_mesh(path, path, f, s) : read_points(path, path, f, s);
    }
    check_box(path, m, s, s.is_mesh ? "OpenMesh" : "CGAL");
    check_usable(path, m);
    return m;
}

}  // namespace mc
