// Octree levels from sorted Morton codes, the palette, and pruning to kept cells.
#include "octree.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace mc {
namespace {

std::array<uint8_t, 3> to_byte(const std::array<double, 3> &c) {
    std::array<uint8_t, 3> b;
    for (int a = 0; a < 3; a++) b[a] = static_cast<uint8_t>(std::lround(std::clamp(c[a], 0.0, 255.0)));
    return b;
}

struct Box {
    std::vector<size_t> items;  // indices into the distinct colours
    double weight = 0;
};

// Cousin groups from sibling groups: a node at level l-2 has as many grandchildren as its children
// have children; level 1 is one group, the root's children.
std::vector<std::vector<uint8_t>> cousin_groups(const std::vector<std::vector<uint8_t>> &siblings) {
    const int D = static_cast<int>(siblings.size()) - 1;
    std::vector<std::vector<uint8_t>> cousins(siblings.size());
    for (int l = 1; l <= D; l++) {
        if (l == 1) { cousins[1] = {static_cast<uint8_t>(siblings[1].size() ? siblings[1][0] : 0)}; continue; }
        size_t child = 0;  // index into siblings[l], one entry per node at level l-1
        for (uint8_t n_children : siblings[l - 1]) {
            unsigned sum = 0;
            for (unsigned i = 0; i < n_children; i++) sum += siblings[l][child++];
            cousins[l].push_back(static_cast<uint8_t>(sum));
        }
    }
    return cousins;
}

}  // namespace

std::vector<std::array<uint8_t, 3>> make_palette(const std::vector<std::array<uint8_t, 3>> &colours,
                                                 const std::vector<double> &weights, int max_entries,
                                                 std::vector<uint8_t> &index) {
    std::map<std::array<uint8_t, 3>, double> distinct;  // ordered: deterministic
    for (size_t i = 0; i < colours.size(); i++) distinct[colours[i]] += weights[i];
    std::vector<std::array<uint8_t, 3>> dc;
    std::vector<double> dw;
    for (const auto &kv : distinct) dc.push_back(kv.first), dw.push_back(kv.second);

    std::vector<std::array<uint8_t, 3>> palette;
    if (static_cast<int>(dc.size()) <= max_entries) {
        palette = dc;
    } else {
        // Split the box with the largest weighted range along its longest axis at the weighted median.
        std::vector<Box> boxes(1);
        for (size_t i = 0; i < dc.size(); i++) boxes[0].items.push_back(i), boxes[0].weight += dw[i];
        while (static_cast<int>(boxes.size()) < max_entries) {
            int best = -1, best_axis = 0;
            double best_score = 0;
            for (size_t b = 0; b < boxes.size(); b++) {
                if (boxes[b].items.size() < 2) continue;
                for (int a = 0; a < 3; a++) {
                    int lo = 255, hi = 0;
                    for (size_t i : boxes[b].items) lo = std::min<int>(lo, dc[i][a]), hi = std::max<int>(hi, dc[i][a]);
                    double score = (hi - lo) * std::sqrt(boxes[b].weight);
                    if (score > best_score) best_score = score, best = static_cast<int>(b), best_axis = a;
                }
            }
            if (best < 0) break;
            Box &box = boxes[best];
            std::stable_sort(box.items.begin(), box.items.end(),
                             [&](size_t x, size_t y) { return dc[x][best_axis] < dc[y][best_axis]; });
            double half = box.weight / 2, acc = 0;
            size_t cut = 1;
            for (; cut < box.items.size() - 1; cut++) {
                acc += dw[box.items[cut - 1]];
                if (acc >= half) break;
            }
            Box upper;
            upper.items.assign(box.items.begin() + static_cast<long>(cut), box.items.end());
            box.items.resize(cut);
            box.weight = 0;
            for (size_t i : box.items) box.weight += dw[i];
            for (size_t i : upper.items) upper.weight += dw[i];
            boxes.push_back(std::move(upper));
        }
        for (const Box &b : boxes) {
            std::array<double, 3> mean{0, 0, 0};
            for (size_t i : b.items)
                for (int a = 0; a < 3; a++) mean[a] += dc[i][a] * dw[i] / b.weight;
            palette.push_back(to_byte(mean));
        }
        std::sort(palette.begin(), palette.end());
        palette.erase(std::unique(palette.begin(), palette.end()), palette.end());
    }
    // Nearest entry for each distinct colour, then for each input.
    std::map<std::array<uint8_t, 3>, uint8_t> lookup;
    for (const auto &c : dc) {
        int best = 0;
        long best_d = -1;
        for (size_t p = 0; p < palette.size(); p++) {
            long d = 0;
            for (int a = 0; a < 3; a++) d += (long)(c[a] - palette[p][a]) * (c[a] - palette[p][a]);
            if (best_d < 0 || d < best_d) best_d = d, best = static_cast<int>(p);
        }
        lookup[c] = static_cast<uint8_t>(best);
    }
    index.resize(colours.size());
    for (size_t i = 0; i < colours.size(); i++) index[i] = lookup[colours[i]];
    return palette;
}

OctreeLevels build_levels(const Voxels &v) {
    const int D = v.depth;
    OctreeLevels t;
    t.depth = D;
    t.masks.assign(D, {});
    t.siblings.assign(D + 1, {});
    t.mean.assign(D + 1, {});

    // Level by level from the leaves up: a node's key is its leaves' code >> 3 per level climbed.
    std::vector<uint64_t> keys = v.codes;
    std::vector<std::array<double, 3>> sum(v.rgb);    // colour sums of the leaves under each node
    std::vector<double> count(v.codes.size(), 1.0);
    for (int l = D; l >= 1; l--) {
        if (l < static_cast<int>(v.level_rgb.size()) && !v.level_rgb[l].empty()) {
            // a mesh's level sampled on its own (voxel.hpp, kSampledLevel): its colours are its own
            // samples', as a bake of depth l has them, and the levels above are their means
            if (v.level_rgb[l].size() != keys.size()) throw std::logic_error("build_levels: level colours and cells disagree");
            sum = v.level_rgb[l];
            count.assign(keys.size(), 1.0);
        }
        t.mean[l].resize(keys.size());
        for (size_t i = 0; i < keys.size(); i++)
            for (int a = 0; a < 3; a++) t.mean[l][i][a] = sum[i][a] / count[i];
        std::vector<uint64_t> pkeys;
        std::vector<std::array<double, 3>> psum;
        std::vector<double> pcount;
        std::vector<uint8_t> pmask, groups;
        for (size_t i = 0; i < keys.size(); i++) {
            uint64_t parent = keys[i] >> 3;
            if (pkeys.empty() || pkeys.back() != parent) {
                pkeys.push_back(parent), psum.push_back({0, 0, 0}), pcount.push_back(0), pmask.push_back(0);
                groups.push_back(0);
            }
            pmask.back() |= static_cast<uint8_t>(1u << (keys[i] & 7u));
            groups.back()++;
            for (int a = 0; a < 3; a++) psum.back()[a] += sum[i][a];
            pcount.back() += count[i];
        }
        t.masks[l - 1] = std::move(pmask);
        t.siblings[l] = std::move(groups);
        keys = std::move(pkeys), sum = std::move(psum), count = std::move(pcount);
    }

    t.cousins = cousin_groups(t.siblings);
    return t;
}

Octree cut_octree(const OctreeLevels &v, int d, int max_palette) {
    Octree t;
    t.depth = d;
    t.masks.assign(v.masks.begin(), v.masks.begin() + d);
    t.siblings.assign(v.siblings.begin(), v.siblings.begin() + d + 1);
    t.cousins.assign(v.cousins.begin(), v.cousins.begin() + d + 1);
    t.colors.assign(d + 1, {});

    // weight[l][i]: the level-d leaves under node i of level l, summed up the sibling groups
    std::vector<std::vector<double>> weight(d + 1);
    weight[d].assign(v.nodes(d), 1.0);
    for (int l = d - 1; l >= 1; l--) {
        weight[l].resize(v.nodes(l));
        size_t child = 0;
        for (size_t i = 0; i < weight[l].size(); i++) {
            double s = 0;
            for (unsigned k = 0; k < v.siblings[l + 1][i]; k++) s += weight[l + 1][child++];
            weight[l][i] = s;
        }
    }

    // One palette over every level's colours, each weighted by the leaves it stands for: a level
    // weighs as much as the leaves, so the fine image keeps its colours and coarse levels still count.
    std::vector<std::array<uint8_t, 3>> all;
    std::vector<double> w;
    for (int l = 1; l <= d; l++)
        for (size_t i = 0; i < v.mean[l].size(); i++) all.push_back(to_byte(v.mean[l][i])), w.push_back(weight[l][i]);
    std::vector<uint8_t> index;
    std::vector<std::array<uint8_t, 3>> palette = make_palette(all, w, max_palette, index);

    // Drop entries no node uses (median cut can leave an entry nearest to none of its colours);
    // the rest keep their order.
    std::vector<int> remap(palette.size(), -1);
    for (uint8_t i : index) remap[i] = 0;
    for (size_t p = 0; p < palette.size(); p++)
        if (remap[p] == 0) remap[p] = static_cast<int>(t.palette.size()), t.palette.push_back(palette[p]);
    for (uint8_t &i : index) i = static_cast<uint8_t>(remap[i]);

    size_t k = 0;
    for (int l = 1; l <= d; l++) {
        t.colors[l].assign(index.begin() + static_cast<long>(k), index.begin() + static_cast<long>(k + v.mean[l].size()));
        k += v.mean[l].size();
    }
    return t;
}

Octree build_octree(const Voxels &v, int max_palette) { return cut_octree(build_levels(v), v.depth, max_palette); }

Octree prune_octree(const Octree &full, const Voxels &vox, const std::vector<uint8_t> &keep) {
    const int D = full.depth;
    if (D > vox.depth || D < 1) throw std::logic_error("prune_octree: octree deeper than its voxels");
    Octree t;
    t.depth = D;
    t.palette = full.palette;
    t.masks.assign(D, {});
    t.colors.assign(D + 1, {});
    t.siblings.assign(D + 1, {});
    // the leaves of full: the voxels' codes climbed to level D
    const int up = 3 * (vox.depth - D);
    std::vector<uint64_t> all, kept;
    for (size_t i = 0; i < vox.codes.size(); i++) {
        const uint64_t key = vox.codes[i] >> up;
        if (all.empty() || all.back() != key) all.push_back(key);
        if (keep[i] && (kept.empty() || kept.back() != key)) kept.push_back(key);
    }
    for (int l = D; l >= 1; l--) {
        if (full.colors[l].size() != all.size()) throw std::logic_error("prune_octree: octree and voxels disagree");
        // both ascending: each kept node takes its colour from the full level
        size_t j = 0;
        for (uint64_t key : kept) {
            while (all[j] != key) j++;
            t.colors[l].push_back(full.colors[l][j]);
        }
        std::vector<uint64_t> parents, all_parents;
        std::vector<uint8_t> mask, groups;
        for (uint64_t key : kept) {
            if (parents.empty() || parents.back() != key >> 3) parents.push_back(key >> 3), mask.push_back(0), groups.push_back(0);
            mask.back() |= static_cast<uint8_t>(1u << (key & 7u));
            groups.back()++;
        }
        for (uint64_t key : all)
            if (all_parents.empty() || all_parents.back() != key >> 3) all_parents.push_back(key >> 3);
        t.masks[l - 1] = std::move(mask);
        t.siblings[l] = std::move(groups);
        kept = std::move(parents);
        all = std::move(all_parents);
    }
    t.cousins = cousin_groups(t.siblings);
    return t;
}

}  // namespace mc
