// --fit: the largest bake within the budgets.
//
// Promise: fit() chooses, in this order of priority, the finest depth <= the voxels' depth, then the
// largest palette <= max_palette (halving, not below min_palette), and, under a RAM budget, the
// largest screen of the requested aspect (its shorter side not below kFitMinSide pixels, or below
// the requested screen's when that is smaller) whose bake meets every limit of opt.limits. RAM depends
// on the screen only, flash on depth and palette, stack on depth only, so each is searched on its
// own. The octree it returns is the one the bake writes (pruned to keep when keep is not empty).
// Nothing fits: throws BudgetError naming the last limit missed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include "budget.hpp"
#include "cones.hpp"
#include "emit.hpp"
#include "octree.hpp"
#include "voxel.hpp"

namespace mc {

// --fit never shrinks the screen below this many pixels on its shorter side (nor below --screen).
constexpr int kFitMinSide = 32;

struct FitRequest {
    int max_palette = 256;    // --palette
    int min_palette = 16;     // --min-palette
    std::string screen;       // --screen as given, for the messages
    const ConeSource *cones = nullptr;   // normal cones for each candidate (cones.hpp), or none
};

struct FitChoice {
    Octree tree;
    int screen_w = 0, screen_h = 0;
    Budget budget;
    std::string note;         // "fit: depth 7 (of 8), palette ...": what it chose, in one line
};

// opt: the bake's options (limits, screen, name, chunking: everything its budget depends on).
FitChoice fit(const Voxels &voxels, const std::vector<uint8_t> &keep, const EmitOptions &opt,
              const FitRequest &request);

}  // namespace mc
