// The readers, one per format, and the choice between them.
//
// Promise: each read_FORMAT parses the file at PATH (a readable regular file of SIZE > 0 bytes)
// once, front to back, into a Model, and throws InputError at the first problem with its exact
// place: the 1-based line for text, the byte offset for binary data. A reader checks what the
// format itself requires (counts, indices, numbers, structure); whole-model checks (no usable
// face, zero extent) are load_model's (load.cpp). What each reader stores:
//   meshes (OFF, OBJ, PLY with faces, STL): coordinates rounded to float, vertices in file order
//     (STL: equal corners merged, in order of first use), faces in file order with any face that
//     names a vertex twice dropped (OBJ first keeps each vertex's first mention, see obj.cpp),
//     polygons fan-triangulated from their first corner
//     (faces.hpp), RGB vertex colours when the file has them;
//   CAO (ViSP's tracker models) is a mesh as above whose polygons are its faces from points and
//     its faces from lines (each as the vertex loop its lines chain into), and the only format
//     that fills Model::lines: its 3D lines, then the sides of every polygon kept, each edge once;
//   glTF (.gltf, .glb) is a mesh as above made of the triangle primitives of the default scene's
//     nodes, each vertex transformed by its node's world matrix in double before the rounding to
//     float, colours from the base colour (factor, texture, COLOR_0) as sRGB bytes (gltf.cpp);
//     the one reader built on a library (tinygltf) and one that reads its file whole, checked
//     before and after the library;
//   point sets (XYZ, PLY without faces): coordinates and normals as double, RGB colours.
#pragma once
#include <cstdint>
#include <string>

#include "model.hpp"

namespace mc::input {

enum class Format { off, obj, ply, stl, xyz, cao, gltf };

// Format from the extension (case-insensitive); InputError for anything else.
Format format_of(const std::string &path);

Model read_off(const std::string &path, uint64_t size);
Model read_obj(const std::string &path, uint64_t size);
Model read_ply(const std::string &path, uint64_t size);
Model read_stl(const std::string &path, uint64_t size);
Model read_xyz(const std::string &path, uint64_t size);
Model read_cao(const std::string &path, uint64_t size);
Model read_gltf(const std::string &path, uint64_t size);  // .gltf and .glb

}  // namespace mc::input
