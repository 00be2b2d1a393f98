// The octree the runtime decodes: child masks and palette indices, level by level.
#pragma once
#include <array>
#include <cstdint>
#include <vector>
#include "voxel.hpp"

namespace mc {

struct Octree {
    int depth = 0;
    // masks[l]: one child-mask byte per node at level l (l = 0..depth-1), depth-first order.
    std::vector<std::vector<uint8_t>> masks;
    // colors[l]: palette index per node at level l (l = 0..depth; level 0 is left empty).
    std::vector<std::vector<uint8_t>> colors;
    // Runs of consecutive entries the renderer reads from one chunk, so chunk boundaries must fall
    // between them. siblings[l] (l >= 1): the number of children of each node at level l-1 (the
    // masks a node at level l-1 reads at once). cousins[l] (l >= 1): the number of grandchildren of
    // each node at level l-2, or the whole of level 1 (the colours a node two levels up reads).
    std::vector<std::vector<uint8_t>> siblings, cousins;
    std::vector<std::array<uint8_t, 3>> palette;
    // cones[l]: normal cones of the nodes at level l (cones.hpp, octree.h), 7 bytes each; empty
    // where the bake has none
    std::vector<std::vector<uint8_t>> cones;
    size_t nodes(int level) const { return level == 0 ? 1 : colors[level].size(); }
};

// The palette-independent part of an octree of depth D, from which the octree of any depth d <= D
// is cut without sampling again: the masks, sibling and cousin groups of levels above d are the
// same whatever d, and a node's colour is the mean of the leaves under it (for a mesh baked deeper than
// kSampledLevel: levels from kSampledLevel down have their own colours, Voxels::level_rgb, and the
// levels above are the means of kSampledLevel's).
struct OctreeLevels {
    int depth = 0;
    std::vector<std::vector<uint8_t>> masks, siblings, cousins;   // as in Octree, for depth D
    std::vector<std::vector<std::array<double, 3>>> mean;         // mean[l][i]: colour of node i at level l
    size_t nodes(int level) const { return level == 0 ? 1 : mean[level].size(); }
};

OctreeLevels build_levels(const Voxels &v);

// The octree of depth d (1..levels.depth): the levels 0..d of `levels`, with one palette of at most
// max_palette entries over their colours (exact when few enough colours occur), each colour weighted
// by the level-d leaves under its node. Palette entries no node uses are dropped.
Octree cut_octree(const OctreeLevels &levels, int d, int max_palette);

// build_levels then cut_octree at the voxels' depth.
Octree build_octree(const Voxels &v, int max_palette);

// The octree of the kept leaves (keep: one flag per cell of vox, as visibility.hpp's visible_cells
// makes it). Nodes keep the colours they have in full (so coarse levels are the unpruned model's
// colours and the palette is unchanged); nodes with no kept leaf disappear. full may be cut at a
// depth d below the voxels' (its leaves are then the level-d nodes): a leaf stays when any cell
// under it is kept.
Octree prune_octree(const Octree &full, const Voxels &vox, const std::vector<uint8_t> &keep);

// Median-cut quantization: at most max_entries colours; exact (deduplicated, sorted) when the input
// has no more distinct colours than that. index[i] is the entry for colours[i]. Deterministic.
std::vector<std::array<uint8_t, 3>> make_palette(const std::vector<std::array<uint8_t, 3>> &colours,
                                                 const std::vector<double> &weights, int max_entries,
                                                 std::vector<uint8_t> &index);

}  // namespace mc
