// Validating scan of an input file, run before the mesh / point-set libraries read it.
// OpenMesh and CGAL only say "failed" (or silently misread), so every problem they could trip over
// is found here first and reported with its exact place: a 1-based line for text, a byte offset
// for binary data. The scan keeps no per-vertex data; it only counts and measures.
#pragma once
#include <array>
#include <cstdint>
#include <ostream>
#include <string>

#include "model.hpp"

namespace mc {

enum class Format { off, obj, ply, stl, xyz };

// Most vertices, points or faces a file may declare or contain.
constexpr uint64_t kMaxElements = 50'000'000;

// Format from the extension (case-insensitive); InputError for anything else.
Format format_of(const std::string &path);
const char *extension_of(Format f);  // ".off", ...

// What the scan found; load.cpp checks the library's result against it.
struct Scan {
    bool is_mesh = true;
    bool binary = false;       // binary STL / PLY
    uint64_t points = 0;       // vertices or points in the file
    uint64_t faces = 0;        // faces the library will build (it drops faces that repeat a vertex);
                               // for STL a lower bound, see stl_triangle_kept()
    uint64_t faces_in_file = 0;
    bool colors = false;       // RGB per vertex / point
    bool colors_float = false; // PLY colours stored as float (0..1) rather than uchar
    bool normals = false;      // normals per point (point sets)
    bool rewrite = false;      // the library misreads this file as it is: load a clean copy instead
    std::array<double, 3> lo{}, hi{};  // bounding box of all coordinates
};

// Scans PATH (already known to be a readable regular file) and throws InputError at the first
// problem. With CLEAN set, also writes a copy of the file in the form the library reads correctly
// (comments dropped, canonical header...); only meaningful when a first scan returned rewrite.
Scan scan_file(const std::string &path, Format f, std::ostream *clean = nullptr);

}  // namespace mc
