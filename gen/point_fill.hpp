// Sparse point sets: the surface between the points, filled in the voxel grid (voxel.cpp calls it).
//
// Promise: a point set whose points lie 0.3 cells of the baked grid or more apart (CGAL's average
// spacing, 6 neighbours) gets, besides the cells its points land in, the cells that the surface the
// points stand for passes through, so that a scan sampled more coarsely than the grid bakes to a
// closed surface where it is closed, and the renderer still draws one leaf per cell. That surface is
// the points' moving least-squares plane: near a cell centre c, the plane through the weighted mean
// of the points whose balls reach c, normal to their weighted mean normal (each normal first turned
// to agree with the nearest point's, so unoriented normals do), with weights (1 - d^2 / r^2)^2 at
// distance d. A point's ball has radius kFillRadius times the distance to its 6th nearest neighbour
// (so it adapts to the local density; at least one cell, at most kFillClamp times the median), and
// its normal is the file's where it has a usable one, else CGAL's PCA estimate from 12 neighbours.
// A cell is added when that plane passes through it (|(c - mean).n| at most half the cell's extent
// along n, one side exclusive: a ray cannot slip between the added cells, and a plane lying on cell
// faces adds one layer), and takes the colours of the same points with the same weights. The cells
// the points themselves occupy keep their colours as before. Meshes, and point sets denser than
// that, are not touched. Deterministic: blocks of the grid in Morton order, the points in file
// order within each.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>
#include "model.hpp"
#include "normalize.hpp"
#include "progress.hpp"

namespace mc {

// A point's ball radius over the distance to its 6th nearest neighbour. Points of a random sample
// lie about as a Poisson process, whose 6th neighbour is 1.35 / sqrt(density) away on average: balls
// of that radius leave 0.3 % of the surface outside all of them; the moving plane needs several
// points in each. Measured (tests/points/suite.sh, the catalogue meshes' vertices subsampled):
// 1.25 turns more of the thin parts into bridges and background, 0.8 leaves holes.
inline constexpr double kFillRadius = 1.0;
// The largest ball over the median one: isolated points (a scan's stray returns) do not span the
// scene with one plane, while a scan's sparse parts (5 times the median spacing in the catalogue's
// man subsampled: its legs) are still closed.
inline constexpr double kFillClamp = 4.0;
// No fill below this average spacing, in cells. CGAL's average runs over the point itself and its 5
// nearest others, about 0.75 / sqrt(density) for a random sample: 0.3 cells is some 6 points per
// cell face, which leave about 0.2 % of the surface's cells empty (exp(-6)); regular scans none.
inline constexpr double kFillFrom = 0.3;

struct PointFill {
    bool enabled = true;       // --point-fill auto; false: off (each point its own cell only, as before)
    double spacing = 0;        // CGAL's average spacing, in cells of the grid (0: not measured)
    double radius = 0;         // the median ball radius in cells; 0 when nothing was filled
    uint64_t cells_added = 0;  // cells added to those the points occupy
    std::string why;           // why nothing was filled, when nothing was
    std::string json() const;  // budget.json's "point_fill"
};

struct FilledCell {
    uint64_t code;                 // Morton code (voxel.hpp morton_encode)
    std::array<double, 3> rgb;     // colour, 0..255
};

// CGAL's average spacing of m's points (compute_average_spacing, 6 neighbours), in model units.
double average_spacing(const Model &m);

// The cells the fill adds for point set m in the 2^depth grid of cube, ascending by code, none of
// `occupied` (the codes the points themselves hold, ascending). colors: each point's colour
// (0..255); normals: each point's normal, or empty (PCA estimates from 12 neighbours, which also
// stand in for any normal of zero length). Adds nothing when st.enabled is false or the points are
// denser than kFillFrom cells; fills st and reports progress.
std::vector<FilledCell> fill_points(const Model &m, const std::vector<std::array<double, 3>> &colors,
                                    const std::vector<std::array<double, 3>> &normals, const GridCube &cube,
                                    int depth, const std::vector<uint64_t> &occupied, PointFill &st,
                                    Progress &progress);

}  // namespace mc
