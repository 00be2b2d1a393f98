// Polygon faces to the model's triangles.
//
// Promise: add() takes one face's 0-based vertex indices (already range-checked) and appends its
// triangles: none when the face names a vertex twice (such a face has no consistent orientation;
// this is also what OpenMesh's importer does, so models read before keep their triangles), else
// the fan (c0 c1 c2) (c0 c2 c3) ... from its first corner.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace mc::input {

class Faces {
public:
    explicit Faces(std::vector<std::array<uint32_t, 3>> &tris) : tris_(tris) {}

    // Returns whether the face was kept.
    bool add(const std::vector<uint32_t> &c) {
        if (c.size() < 3 || repeats(c)) return false;
        for (size_t k = 1; k + 1 < c.size(); ++k) tris_.push_back({c[0], c[k], c[k + 1]});
        return true;
    }

private:
    bool repeats(const std::vector<uint32_t> &c) {
        if (c.size() <= 16) {  // faces are short: pairwise is cheapest
            for (size_t i = 1; i < c.size(); ++i)
                if (std::find(c.begin(), c.begin() + i, c[i]) != c.begin() + i) return true;
            return false;
        }
        sorted_ = c;
        std::sort(sorted_.begin(), sorted_.end());
        return std::adjacent_find(sorted_.begin(), sorted_.end()) != sorted_.end();
    }
    std::vector<std::array<uint32_t, 3>> &tris_;
    std::vector<uint32_t> sorted_;
};

}  // namespace mc::input
