// The generator's in-memory model: what every loader produces and every later stage consumes.
#pragma once
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace mc {

// Bad input. Reported as one line "modelc: FILE:PLACE: MESSAGE" where PLACE is a 1-based line number
// for text files, "byte N" (0-based offset) for binary data, or empty when there is no place
// (missing file, unknown format, a property of the whole model).
struct InputError : std::runtime_error {
    enum class Where { none, line, byte };
    std::string file;
    Where where = Where::none;
    long long place = 0;
    InputError(std::string f, Where w, long long p, const std::string &msg)
        : std::runtime_error(msg), file(std::move(f)), where(w), place(p) {}
    std::string line() const {  // the whole error line, without "modelc: "
        std::string s = file + ":";
        if (where == Where::line) s += std::to_string(place) + ":";
        if (where == Where::byte) s += "byte " + std::to_string(place) + ":";
        return s + " " + what();
    }
};

struct Model {
    bool is_mesh = false;                          // triangle mesh, or a point set
    std::vector<std::array<double, 3>> points;     // mesh vertices or point-set points
    std::vector<std::array<uint32_t, 3>> tris;     // triangles (polygons are fan-triangulated)
    std::vector<std::array<uint8_t, 3>> colors;    // per point, RGB; empty when the file has none
    std::vector<std::array<double, 3>> normals;    // per point (point sets only); empty when none
    std::vector<std::array<uint32_t, 2>> lines;    // edges the file names for tracking (.cao: its 3D lines and every polygon's sides, each once, smaller index first, in order of first mention); empty for other formats
};

// Loads and validates FILE. Throws InputError for anything wrong with it.
Model load_model(const std::string &path);

// Whether triangle t of m has no area relative to its own size (|u x v| at most 1e-6 of its longest
// side squared): exact zeros are rare for corners on a line. The readers' rule, and the edge model's.
bool zero_area(const Model &m, const std::array<uint32_t, 3> &t);

}  // namespace mc
