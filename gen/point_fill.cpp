// Filling sparse point sets: see point_fill.hpp.
#include "point_fill.hpp"

#include "cgal_mesh.hpp"
#include "voxel.hpp"

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/pca_estimate_normals.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace mc {
namespace {

std::vector<Point> cgal_points(const Model &m) {
    std::vector<Point> pts;
    pts.reserve(m.points.size());
    for (const auto &p : m.points) pts.emplace_back(p[0], p[1], p[2]);
    return pts;
}

// Each point's distance to its k-th nearest other point (a duplicate counts, at distance 0), model
// units; 0 for a set of at most k points.
std::vector<double> kth_neighbour(const Model &m, unsigned k) {
    using Search = CGAL::Orthogonal_k_neighbor_search<CGAL::Search_traits_3<K>>;
    const std::vector<Point> pts = cgal_points(m);
    Search::Tree tree(pts.begin(), pts.end());
    std::vector<double> out(pts.size(), 0);
    if (pts.size() <= k) return out;
    for (size_t i = 0; i < pts.size(); i++) {
        Search search(tree, pts[i], k + 1);   // the point itself among them
        double far = 0;
        for (auto it = search.begin(); it != search.end(); ++it) far = std::max(far, it->second);
        out[i] = std::sqrt(far);
    }
    return out;
}

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3f", v);
    return b;
}

// The points in buckets of side `side` cells: every point whose ball (radius at most side) reaches
// a cell lies in the cell's bucket or one of the 26 around it. Each bucket lists its points in file
// order.
class Buckets {
public:
    Buckets(const std::vector<std::array<double, 3>> &p, const std::vector<double> &r, double side) : side_(side) {
        for (size_t i = 0; i < p.size(); i++)
            if (r[i] > 0) map_[key(at(p[i][0]), at(p[i][1]), at(p[i][2]))].push_back(static_cast<uint32_t>(i));
    }
    // f(j) for every point j of the 27 buckets around cell centre c (cell units)
    template <class F>
    void around(const double c[3], F f) const {
        const int64_t b[3] = {at(c[0]), at(c[1]), at(c[2])};
        for (int dz = -1; dz <= 1; dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    auto it = map_.find(key(b[0] + dx, b[1] + dy, b[2] + dz));
                    if (it != map_.end())
                        for (uint32_t j : it->second) f(j);
                }
    }

private:
    int64_t at(double v) const { return static_cast<int64_t>(std::floor(v / side_)) + 1; }   // >= 0 in the grid
    static uint64_t key(int64_t x, int64_t y, int64_t z) {
        return (uint64_t(x) << 42) | (uint64_t(y) << 21) | uint64_t(z);
    }
    double side_;
    std::unordered_map<uint64_t, std::vector<uint32_t>> map_;
};

}  // namespace

double average_spacing(const Model &m) {
    if (m.points.size() < 2) return 0;
    const unsigned k = static_cast<unsigned>(std::min<size_t>(6, m.points.size()));
    return CGAL::compute_average_spacing<CGAL::Sequential_tag>(cgal_points(m), k);
}

std::string PointFill::json() const {
    std::string s = "{\"spacing_cells\": " + number(spacing) + ", \"radius_cells\": " + number(radius) +
                    ", \"cells_added\": " + std::to_string(cells_added);
    if (!why.empty()) s += ", \"why_not\": \"" + why + "\"";
    return s + "}";
}

std::vector<FilledCell> fill_points(const Model &m, const std::vector<std::array<double, 3>> &colors,
                                    const std::vector<std::array<double, 3>> &normals_in, const GridCube &cube,
                                    int depth, const std::vector<uint64_t> &occupied, PointFill &st,
                                    Progress &progress) {
    std::vector<FilledCell> out;
    st.radius = 0;
    st.cells_added = 0;
    st.why.clear();
    if (!st.enabled) {
        st.why = "--point-fill off";
        return out;
    }
    const double cell = cube.cell(depth);
    st.spacing = average_spacing(m) / cell;
    if (!(st.spacing >= kFillFrom)) {
        st.why = "dense: under " + number(kFillFrom) + " cells apart";
        return out;
    }
    // the file's normals where they are usable, else PCA estimates
    auto usable = [](const std::array<double, 3> &n) {
        const double len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        return len2 > 0 && std::isfinite(len2);
    };
    std::vector<std::array<double, 3>> normals = normals_in;
    if (normals.size() != m.points.size() || !std::all_of(normals.begin(), normals.end(), usable)) {
        const std::vector<std::array<double, 3>> pca = pca_normals(m);
        normals.resize(m.points.size(), {0, 0, 0});
        for (size_t i = 0; i < normals.size(); i++)
            if (!usable(normals[i])) normals[i] = pca[i];
    }
    const size_t np = m.points.size();
    // the points in cell units (cell centres at integers + 1/2), unit normals and ball radii in cells
    std::vector<std::array<double, 3>> p(np), nv(np);
    std::vector<double> r = kth_neighbour(m, 6);
    {
        std::vector<double> sorted = r;
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(np / 2), sorted.end());
        const double most = kFillClamp * kFillRadius * sorted[np / 2] / cell;
        for (size_t i = 0; i < np; i++) {
            for (int a = 0; a < 3; a++) p[i][a] = (m.points[i][a] - cube.origin[a]) / cell;
            const auto &n = normals[i];
            const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(len > 0) || !std::isfinite(len)) { r[i] = 0; continue; }   // no normal (a degenerate PCA): no ball
            for (int a = 0; a < 3; a++) nv[i][a] = n[a] / len;
            r[i] = std::max(1.0, std::min(kFillRadius * r[i] / cell, most));
        }
        std::vector<double> used;
        for (double x : r)
            if (x > 0) used.push_back(x);
        if (used.empty()) {
            st.why = "no point has a normal";
            return out;
        }
        std::nth_element(used.begin(), used.begin() + static_cast<long>(used.size() / 2), used.end());
        st.radius = used[used.size() / 2];
    }
    const double rmax = *std::max_element(r.begin(), r.end());
    const Buckets buckets(p, r, rmax);
    const int64_t n = int64_t(1) << depth;
    // Blocks of the grid, 2^B cells a side, aligned: a block's cells are one run of Morton codes, so
    // blocks taken in order and each block's cells sorted give every cell in order, and the
    // candidates never outgrow one block. Each point goes to the blocks its ball's box meets.
    const int B = std::min(depth, 5);
    std::unordered_map<uint64_t, std::vector<uint32_t>> blocks;
    for (size_t i = 0; i < np; i++) {
        if (!(r[i] > 0)) continue;
        int64_t lo[3], hi[3];
        for (int a = 0; a < 3; a++) {
            lo[a] = std::max<int64_t>(0, static_cast<int64_t>(std::floor(p[i][a] - r[i] - 1))) >> B;
            hi[a] = std::min<int64_t>(n - 1, static_cast<int64_t>(std::floor(p[i][a] + r[i] + 1))) >> B;
        }
        for (int64_t z = lo[2]; z <= hi[2]; z++)
            for (int64_t y = lo[1]; y <= hi[1]; y++)
                for (int64_t x = lo[0]; x <= hi[0]; x++)
                    blocks[morton_encode(uint32_t(x), uint32_t(y), uint32_t(z), depth - B)].push_back(uint32_t(i));
    }
    std::vector<uint64_t> order;
    order.reserve(blocks.size());
    for (const auto &kv : blocks) order.push_back(kv.first);
    std::sort(order.begin(), order.end());
    std::vector<uint64_t> cand;
    for (size_t done = 0; done < order.size(); done++) {
        const uint64_t blk = order[done];
        progress.update(static_cast<double>(done), static_cast<double>(order.size()));
        // candidates: the cells of this block within a ball whose point's plane, widened by a cell
        // each way, passes through them (the moving plane bends between the points)
        const auto b0 = morton_decode(blk, depth - B);
        const int64_t lo[3] = {int64_t(b0[0]) << B, int64_t(b0[1]) << B, int64_t(b0[2]) << B};
        const int64_t side = int64_t(1) << B;
        cand.clear();
        for (uint32_t i : blocks[blk]) {
            const auto &q0 = p[i];
            const auto &v = nv[i];
            int a = 0;   // the disc's columns run along its normal's largest axis a
            for (int k = 1; k < 3; k++)
                if (std::fabs(v[k]) > std::fabs(v[a])) a = k;
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            const double h = 0.5 * (std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2])) + 1.0;   // the slab
            const double reach = h / std::fabs(v[a]);                                             // along a
            const double eb = r[i] * std::sqrt(std::max(0.0, 1 - v[b] * v[b])) + 1;
            const double ec = r[i] * std::sqrt(std::max(0.0, 1 - v[c] * v[c])) + 1;
            const int64_t ib0 = std::max(lo[b], int64_t(std::floor(q0[b] - eb)));
            const int64_t ib1 = std::min(lo[b] + side - 1, int64_t(std::floor(q0[b] + eb)));
            const int64_t ic0 = std::max(lo[c], int64_t(std::floor(q0[c] - ec)));
            const int64_t ic1 = std::min(lo[c] + side - 1, int64_t(std::floor(q0[c] + ec)));
            for (int64_t ib = ib0; ib <= ib1; ib++)
                for (int64_t ic = ic0; ic <= ic1; ic++) {
                    const double qb = ib + 0.5 - q0[b], qc = ic + 0.5 - q0[c];
                    const double t = -(v[b] * qb + v[c] * qc) / v[a];   // the plane over this column, along a
                    const int64_t ia0 = std::max(lo[a], int64_t(std::ceil(q0[a] + t - reach - 0.5)));
                    const int64_t ia1 = std::min(lo[a] + side - 1, int64_t(std::floor(q0[a] + t + reach - 0.5)));
                    for (int64_t ia = ia0; ia <= ia1; ia++) {
                        const double qa = ia + 0.5 - q0[a];
                        if (qa * qa + qb * qb + qc * qc > r[i] * r[i]) continue;
                        uint32_t idx[3];
                        idx[a] = uint32_t(ia), idx[b] = uint32_t(ib), idx[c] = uint32_t(ic);
                        cand.push_back(morton_encode(idx[0], idx[1], idx[2], depth));
                    }
                }
        }
        std::sort(cand.begin(), cand.end());
        cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
        // each candidate against the points' moving plane there (point_fill.hpp)
        for (uint64_t code : cand) {
            if (std::binary_search(occupied.begin(), occupied.end(), code)) continue;
            const auto ijk = morton_decode(code, depth);
            const double cc[3] = {ijk[0] + 0.5, ijk[1] + 0.5, ijk[2] + 0.5};
            auto dist2 = [&](uint32_t j) {
                const double ex = cc[0] - p[j][0], ey = cc[1] - p[j][1], ez = cc[2] - p[j][2];
                return ex * ex + ey * ey + ez * ez;
            };
            double best = INFINITY;
            int64_t ref = -1;   // the nearest point whose ball reaches the cell: it orients the normals
            buckets.around(cc, [&](uint32_t j) {
                const double d2 = dist2(j);
                if (d2 < r[j] * r[j] && d2 < best) best = d2, ref = j;
            });
            if (ref < 0) continue;
            double W = 0, P[3] = {0, 0, 0}, N[3] = {0, 0, 0}, C[3] = {0, 0, 0};
            buckets.around(cc, [&](uint32_t j) {
                const double d2 = dist2(j);
                if (!(d2 < r[j] * r[j])) return;
                const double u = 1 - d2 / (r[j] * r[j]), w = u * u;
                const double s = nv[j][0] * nv[ref][0] + nv[j][1] * nv[ref][1] + nv[j][2] * nv[ref][2] < 0 ? -w : w;
                W += w;
                for (int k = 0; k < 3; k++) P[k] += w * p[j][k], N[k] += s * nv[j][k], C[k] += w * colors[j][k];
            });
            const double len = std::sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
            if (!(W > 0) || !(len > 0)) continue;
            double along = 0, extent = 0;   // the cell centre off the plane, and the cell's half-width along N
            for (int k = 0; k < 3; k++) along += (cc[k] - P[k] / W) * N[k], extent += 0.5 * std::fabs(N[k]);
            if (!(along > -extent && along <= extent)) continue;   // a plane on cell faces: one layer
            out.push_back({code, {C[0] / W, C[1] / W, C[2] / W}});
        }
    }
    st.cells_added = out.size();
    return out;
}

}  // namespace mc
