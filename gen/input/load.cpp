// load_model(): the one entry point (model.hpp). Checks that PATH is a readable regular file,
// picks the reader by extension (readers.hpp), and refuses a model there is nothing to draw of.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc {
namespace {

using input::fail_none;

// Only regular files: a directory, FIFO or device (/dev/zero) would block or never end.
uint64_t check_readable(const std::string &path) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) fail_none(path, std::string("cannot open: ") + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) fail_none(path, "cannot open: Is a directory");
    if (!S_ISREG(st.st_mode)) fail_none(path, "cannot open: not a regular file");
    return static_cast<uint64_t>(st.st_size);
}

}  // namespace

bool zero_area(const Model &m, const std::array<uint32_t, 3> &t) {
    const auto &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    auto len2 = [](const double *e) { return e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; };
    const double longest2 = std::max({len2(u), len2(v), len2(w)});
    return std::sqrt(x * x + y * y + z * z) <= 1e-6 * longest2;  // |u x v| is twice the area
}

namespace {

// Whole-model problems (no place): nothing to draw.
void check_usable(const std::string &path, const Model &m) {
    if (m.points.empty()) fail_none(path, m.is_mesh ? "model has no vertices" : "point set has no points");
    if (!m.is_mesh) {
        if (std::all_of(m.points.begin(), m.points.end(), [&m](const auto &p) { return p == m.points[0]; }))
            fail_none(path, "all " + std::to_string(m.points.size()) + " points are identical (zero extent)");
        return;
    }
    if (m.tris.empty()) fail_none(path, "mesh has no usable faces (every face repeats a vertex)");
    for (const auto &t : m.tris)
        if (!zero_area(m, t)) return;
    fail_none(path, "all " + std::to_string(m.tris.size()) + " triangles have zero area");
}

}  // namespace

namespace input {

Format format_of(const std::string &path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    const std::string ext =
        dot == std::string::npos || (slash != std::string::npos && dot < slash) ? std::string() : lower(path.substr(dot));
    if (ext == ".off") return Format::off;
    if (ext == ".obj") return Format::obj;
    if (ext == ".ply") return Format::ply;
    if (ext == ".stl") return Format::stl;
    if (ext == ".xyz") return Format::xyz;
    if (ext == ".cao") return Format::cao;
    if (ext == ".gltf" || ext == ".glb") return Format::gltf;
    fail_none(path, "unknown format '" + ext + "' (expected .off .obj .ply .stl .xyz .cao .gltf .glb)");
}

}  // namespace input

Model load_model(const std::string &path) {
    const uint64_t size = check_readable(path);
    const input::Format f = input::format_of(path);
    if (size == 0) fail_none(path, "file is empty");
    Model m;
    switch (f) {
    case input::Format::off: m = input::read_off(path, size); break;
    case input::Format::obj: m = input::read_obj(path, size); break;
    case input::Format::ply: m = input::read_ply(path, size); break;
    case input::Format::stl: m = input::read_stl(path, size); break;
    case input::Format::xyz: m = input::read_xyz(path, size); break;
    case input::Format::cao: m = input::read_cao(path, size); break;
    case input::Format::gltf: m = input::read_gltf(path, size); break;
    }
    check_usable(path, m);
    return m;
}

}  // namespace mc
