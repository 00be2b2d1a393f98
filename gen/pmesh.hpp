// The progressive-mesh part: a triangle mesh decimated by half-edge collapses (OpenMesh's
// Decimater), recorded in the layout of runtime/include/modelc/pmesh.h.
//
// Promise: build_pmesh turns every face of the model that has three distinct corners into a face of
// the full level (faces OpenMesh cannot add because their edge or vertex is already used twice over
// get their own copies of their vertices, counted in split_vertices), then collapses half-edges in
// order of quadric error, refusing collapses that flip a face normal, until none is left; the
// record of those collapses, reversed, is the part. Level n of the result is exactly the mesh the Decimater had with n vertices. With
// max_faces, the finest collapses are applied for good until the full level has at most that many
// faces.
#pragma once
#include <array>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "model.hpp"
#include "normalize.hpp"

namespace mc {

struct PMeshOptions {
    size_t max_faces = 0;        // 0: no limit
    double crease_angle = 60.0;  // degrees between two faces' normals above which their edge is a crease
};

// A half-edge: edge k (corner k to corner k + 1 mod 3) of face f is 4 f + k; none (a border) is all ones.
constexpr uint32_t kNoHalfEdge = 0xFFFFFFFFu;

struct PMesh {
    // per vertex, in depth-first order of the collapse forest (pmesh.h)
    std::vector<std::array<uint16_t, 3>> positions;   // (q - 32768) / 65536: unit-cube coordinate
    std::vector<uint32_t> parent, size;
    uint32_t base_vertices = 0, base_faces = 0;
    // per split, in order: the vertex it brings back and the number of faces it adds (1 or 2)
    std::vector<uint32_t> split_vertex;
    std::vector<uint8_t> split_faces;
    // per face, in creation order: corners in the full level, counter-clockwise from outside; a
    // split's faces start at the split vertex or its parent, so that edge 0 is the collapsed edge
    std::vector<std::array<uint32_t, 3>> faces;
    // per face: the half-edge across each of its edges in the full level (kNoHalfEdge on a border)
    std::vector<std::array<uint32_t, 3>> opposite;
    // one half-edge per edge of the full level (the one of the face created first), borders first,
    // then by decreasing angle between the two faces' normals: where the silhouette search starts
    std::vector<uint32_t> edge_order;
    int16_t crease_cos = 0;      // cos(crease angle) in Q14 (mesh_lines.h)
    // the shades the runtime draws faces in (mesh_render.h): MC_MESH_SHADES greys of the frontal
    // light (light.hpp), 0.15 + 0.85 k / (MC_MESH_SHADES - 1); then the paper and the line colours
    // (mesh_lines.h)
    std::vector<std::array<uint8_t, 3>> palette;
    // what happened to the input
    size_t dropped_faces = 0;    // faces with a repeated corner (no area, nothing to draw)
    size_t split_vertices = 0;   // vertex copies made for faces OpenMesh could not add (non-manifold)
    size_t capped_collapses = 0; // collapses applied for good by max_faces
    size_t vertices() const { return positions.size(); }
    bool closed() const {
        for (const auto &o : opposite)
            for (uint32_t h : o)
                if (h == kNoHalfEdge) return false;
        return true;
    }
};

// Builds the part from a mesh model (m.is_mesh, at least one triangle) normalized into cube.
PMesh build_pmesh(const Model &m, const GridCube &cube, const PMeshOptions &opt);

// Writes the faces OpenMesh's Decimater leaves when it collapses the model's mesh, as build_pmesh
// does, down to `vertices` vertices: one line per face, its corners' quantized positions (x y z,
// three times, in the face's order). For tests: level `vertices` of the part must be the same faces.
void dump_decimated(const Model &m, const GridCube &cube, size_t vertices, std::ostream &out);

// The same faces (the Decimater's mesh at `vertices` vertices, isolated ones not counted) as corners
// in the model's point indices: half-edge collapses keep the original positions, so they index
// m.points. In OpenMesh's (consistent) orientation.
std::vector<std::array<size_t, 3>> decimated_faces(const Model &m, size_t vertices);

}  // namespace mc
