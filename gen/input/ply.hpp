// PLY headers: what ply_header.cpp reads and ply.cpp's body reader consumes.
//
// Promise: read_ply_header() reads "ply", the format line and the element/property lines up to
// end_header, and checks what the body reader relies on: a 'vertex' element with float or double
// x, y, z; normals float or double; colours uchar or float with red, green and blue of one type;
// when 'face' has items, it comes after 'vertex' and has an integer vertex_indices (or
// vertex_index) list. Counts beyond kMaxElements and elements without properties are refused.
// Errors are at the header line they concern.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "input/source.hpp"

namespace mc::input {

enum class PType { i8, u8, i16, u16, i32, u32, f32, f64 };

size_t type_size(PType t);
bool is_float(PType t);
const char *type_name(PType t);

// What a property means to the reader.
enum class Role { other, x, y, z, nx, ny, nz, red, green, blue, color_other, index };

struct PlyProp {
    std::string name, type_name;
    PType type = PType::u8, count_type = PType::u8;
    bool list = false;
    Role role = Role::other;
    long long line = 0;
};

struct PlyElem {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProp> props;
    long long line = 0;
    uint64_t min_bytes = 0;  // smallest an item can be in the body (ascii: 2 bytes per value)
};

struct PlyHeader {
    enum { ascii, little, big } format = ascii;
    std::vector<PlyElem> elems;
    size_t vertex = 0;        // index of the vertex element
    bool is_mesh = false;     // a face element with items
    bool colors = false;      // red, green and blue
    bool colors_float = false;
    bool normals = false;     // nx, ny and nz
};

PlyHeader read_ply_header(TextReader &r);

}  // namespace mc::input
