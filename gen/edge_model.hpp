// The edge-model part: what a tracker draws to score a camera pose (runtime/include/modelc/edges.h):
// the lines to match against image edges and the triangles that hide them, in the model's own
// metric frame (micrometres), not in the unit cube the renderers draw.
//
// Promise: build_edge_model keeps the file's frame (no --up turn, no centring: a pose a user gives
// is in the file's coordinates) and scales it by opt.unit to micrometres, rounded. Its faces are the
// model's triangles with three distinct, non-collinear corners, made consistently oriented by CGAL
// (orient_polygon_soup, which copies a vertex where a non-manifold fan forbids one orientation); a
// closed result is turned to face outwards, component by component, so that a tracker may cull faces
// seen from behind. Its lines are the file's own (a .cao model's lines and polygon sides) when it has
// any, else the mesh's feature edges: borders and creases whose faces' normals differ by more than
// opt.crease_angle (CGAL detect_sharp_edges). A closed model is also marked convex when no vertex
// lies more than a micrometre in front of any face's plane (tested when vertices x faces is at most
// 10^8) and each line is the edge of exactly two faces, which it then records (line_faces): a
// tracker then shows exactly the lines with a face towards the camera, with no face pass (track.h).
// With opt.hide_faces > 0 and more faces than that, the faces (not the lines, still the full mesh's
// feature edges) are instead the mesh OpenMesh's Decimater leaves at about hide_faces / 2 vertices
// (pmesh.hpp decimated_faces: half-edge collapses, so original points), oriented and closed as above.
// A model too large for int32 micrometres (beyond
// +-2^28 um, 268 m, per axis) or with no line is an InputError without a place.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model.hpp"

namespace mc {

struct EdgeModelOptions {
    double unit = 1.0;            // metres per file unit (--unit)
    double crease_angle = 60.0;   // degrees between face normals above which an edge is a line
    size_t hide_faces = 0;        // 0: every face hides; else the mesh decimated to about this many
};

struct EdgeModel {
    std::vector<std::array<int32_t, 3>> positions;   // um, |coordinate| < 2^28
    std::vector<std::array<uint32_t, 2>> lines;      // smaller index first
    std::vector<std::array<uint32_t, 3>> faces;      // counter-clockwise seen from outside when closed
    bool closed = false;
    bool convex = false;                              // closed, convex, every line between two faces
    std::vector<std::array<uint32_t, 2>> line_faces;  // when convex: the two faces of each line
    bool file_lines = false;      // the lines are the file's own, not feature edges
    // what happened to the input (budget.json)
    size_t dropped_faces = 0;     // a repeated corner or no area: hides nothing
    size_t copied_vertices = 0;   // vertices copied to orient non-manifold faces
    size_t border_lines = 0, crease_lines = 0;
};

// The part from a mesh model (m.is_mesh). path names the file in errors.
EdgeModel build_edge_model(const Model &m, const std::string &path, const EdgeModelOptions &opt);

}  // namespace mc
