// --fit: see fit.hpp.
#include "fit.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace mc {
namespace {

// The largest screen of the requested aspect (w shrinks one pixel at a time, h = w * H / W
// rounded down) whose buffers fit the RAM budget; {0, 0} if none down to kFitMinSide does.
std::pair<int, int> fit_screen(int W, int H, size_t ram) {
    const int min_side = std::min(kFitMinSide, std::min(W, H));
    for (int w = W; w >= 1; w--) {
        int h = static_cast<int>(static_cast<long long>(w) * H / W);
        if (std::min(w, h) < min_side) break;
        if (ram_bytes(w, h) <= ram) return {w, h};
    }
    return {0, 0};
}

// The palettes to try, largest first: max, max/2, ... down to min (itself tried last).
std::vector<int> palettes_to_try(int palette, int min_palette) {
    std::vector<int> palettes;
    for (int p = palette; p >= std::min(min_palette, palette); p /= 2) {
        palettes.push_back(std::max(p, std::min(min_palette, palette)));
        if (p <= 1 || p == std::min(min_palette, palette)) break;
    }
    palettes.erase(std::unique(palettes.begin(), palettes.end()), palettes.end());
    return palettes;
}

}  // namespace

FitChoice fit(const Voxels &voxels, const std::vector<uint8_t> &keep, const EmitOptions &opt,
              const FitRequest &request) {
    const Limits &limits = opt.limits;
    EmitOptions emit = opt;
    if (limits.ram) {
        auto [w, h] = fit_screen(emit.screen_w, emit.screen_h, limits.ram);
        if (!w) {
            int ms = std::min(kFitMinSide, std::min(emit.screen_w, emit.screen_h));
            throw BudgetError("over budget: ram: no screen of " + request.screen + "'s aspect with a side of at least " +
                              std::to_string(ms) + " pixels fits " + std::to_string(limits.ram) + " bytes");
        }
        emit.screen_w = w, emit.screen_h = h;
    }
    const std::vector<int> palettes = palettes_to_try(request.max_palette, request.min_palette);
    const OctreeLevels levels = build_levels(voxels);
    std::string last;
    const size_t code = runtime_code_bytes(emit.leaf_switch);
    for (int d = levels.depth; d >= 1; d--) {
        for (int p : palettes) {
            // a lower bound first (no palette, no descriptors), to skip depths far over;
            // pruning (--views) removes nodes, so then every candidate is built
            size_t bound = keep.empty() ? code : 0;
            for (int l = 0; l < d && keep.empty(); l++) bound += levels.nodes(l);
            if (p > 1 && keep.empty())
                for (int l = 1; l <= d; l++) bound += levels.nodes(l);
            if (limits.flash && bound > limits.flash && p == palettes.back()) {
                last = "flash at least " + std::to_string(bound) + " bytes > " + std::to_string(limits.flash) +
                       " (by " + std::to_string(bound - limits.flash) + ") at depth " + std::to_string(d);
                break;
            }
            if (limits.flash && bound > limits.flash) continue;
            if (limits.stack && stack_bytes(d) > limits.stack) {
                last = "stack " + std::to_string(stack_bytes(d)) + " bytes > " + std::to_string(limits.stack) +
                       " at depth " + std::to_string(d);
                break;
            }
            Octree t = cut_octree(levels, d, p);
            if (!keep.empty()) t = prune_octree(t, voxels, keep);
            if (request.cones) add_cones(t, *request.cones);
            Budget b = budget_of(t, emit);
            std::string over = over_budget(b, limits);
            if (!over.empty()) {
                last = over + " at depth " + std::to_string(d) + ", palette " + std::to_string(p);
                continue;
            }
            FitChoice c;
            c.tree = std::move(t);
            c.screen_w = emit.screen_w, c.screen_h = emit.screen_h;
            c.budget = b;
            char line[400];
            std::snprintf(line, sizeof line,
                          "fit: depth %d (of %d), palette %zu entries (of at most %d), screen %dx%d (of %s): "
                          "flash %zu bytes, ram %zu, stack %zu",
                          d, levels.depth, c.tree.palette.size(), request.max_palette, c.screen_w, c.screen_h,
                          request.screen.c_str(), b.flash(), b.ram(), b.stack);
            c.note = line;
            return c;
        }
    }
    throw BudgetError("over budget at every depth, palette and screen --fit may choose: " + last);
}

}  // namespace mc
