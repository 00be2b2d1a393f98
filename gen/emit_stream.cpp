// --emit stream: the bake as one binary stream, coarse first: the octree's levels, then a mesh part's
// base, splits and adjacency (the format is runtime/include/modelc/stream.h's, read by
// runtime/src/stream.c and stream_mesh.c).
#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "emit.hpp"
#include "pmesh.hpp"

namespace mc {
namespace {

constexpr int kKindPalette = 1, kKindLevel = 2, kKindEnd = 3, kKindMesh = 4, kKindBase = 5, kKindSplits = 6,
              kKindAdjacency = 7, kKindPacked = 8, kKindPackedAdjacency = 9;
constexpr size_t kHeaderBytes = 20, kRecordBytes = 12;

uint32_t crc32(const std::string &s, size_t from, size_t n) {
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = from; i < from + n; i++) {
        crc ^= static_cast<uint8_t>(s[i]);
        for (int k = 0; k < 8; k++) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void put16(std::string &s, uint32_t v) {
    s.push_back(static_cast<char>(v & 0xFF));
    s.push_back(static_cast<char>(v >> 8 & 0xFF));
}
void put32(std::string &s, uint32_t v) {
    put16(s, v & 0xFFFF);
    put16(s, v >> 16);
}
void put(std::string &s, const std::vector<uint8_t> &v) { s.append(v.begin(), v.end()); }
void put_n(std::string &s, uint32_t v, unsigned bytes) {
    for (unsigned i = 0; i < bytes; i++) s.push_back(static_cast<char>(v >> (8 * i) & 0xFF));
}
void put_position(std::string &s, const std::array<uint16_t, 3> &q) {
    for (uint16_t c : q) put16(s, c);
}

// The index of w's highest set bit (w >= 1).
unsigned top_bit(uint64_t w) {
    unsigned n = 0;
    while (w >> (n + 1)) n++;
    return n;
}

// Bits, most significant first within each byte (stream.h, kind 8).
struct BitWriter {
    std::string bytes;
    unsigned used = 8;   // bits used in the last byte
    void bit(unsigned b) {
        if (used == 8) bytes.push_back(0), used = 0;
        if (b) bytes.back() = static_cast<char>(static_cast<uint8_t>(bytes.back()) | 0x80u >> used);
        used++;
    }
    void bits(uint32_t v, unsigned n) {
        while (n--) bit(v >> n & 1u);
    }
    // Exp-Golomb of order k: u + 2^k has n + 1 bits; n - k zeros, then those n + 1 bits.
    void exp_golomb(uint32_t u, unsigned k) {
        const uint64_t w = static_cast<uint64_t>(u) + (uint64_t{1} << k);
        const unsigned n = top_bit(w);
        for (unsigned i = k; i < n; i++) bit(0);
        for (unsigned i = n + 1; i-- > 0;) bit(static_cast<unsigned>(w >> i & 1u));
    }
};

unsigned exp_golomb_bits(uint32_t u, unsigned k) { return 2 * top_bit(static_cast<uint64_t>(u) + (uint64_t{1} << k)) + 1 - k; }

// Bits of an offset below n (0 for n <= 1): stream.h's width(n).
unsigned width(uint32_t n) {
    unsigned b = 0;
    while (b < 32 && (uint64_t{1} << b) < n) b++;
    return b;
}

uint32_t zigzag(int32_t r) { return r >= 0 ? 2u * static_cast<uint32_t>(r) : 2u * static_cast<uint32_t>(-r) - 1u; }

// The packed splits (stream.h, kind 8): what a decoder that keeps the level's mesh can infer is left
// out. This coder keeps that mesh its own way (sets of corners per vertex, walked ancestors) and
// shares nothing with the runtime's decoder but the format.
class SplitPacker {
    struct Face {
        std::array<uint32_t, 3> at;   // its corners' vertices at the split's level: v, p, x or p, v, x
        uint32_t rank, ring;          // x's rank among p's neighbours, and their number
    };
    struct Split {
        uint32_t p, size;
        size_t first_face;
        std::vector<Face> faces;
        std::array<uint32_t, 3> residual;   // the position's, zigzagged
    };

  public:
    explicit SplitPacker(const PMesh &pm)
        : pm_(pm), V_(static_cast<uint32_t>(pm.vertices())), since_(V_, 0), slot_(V_), corners_of_(V_),
          level_(3 * pm.faces.size()) {
        const size_t S = pm.split_vertex.size();
        for (size_t s = 0; s < S; s++) since_[pm.split_vertex[s]] = static_cast<uint32_t>(s + 1);
        for (uint32_t v = 0; v < V_; v++) slot_[v] = v + 1;
        for (size_t f = 0; f < pm.base_faces; f++) add_face(f, 0);
        faces_ = pm.base_faces;
    }

    // Splits first .. first + k - 1 into one record's payload (after its first and count).
    std::string pack(size_t first, size_t k) {
        std::vector<Split> out;
        for (size_t s = first; s < first + k; s++) out.push_back(split(s));
        // positions: the Exp-Golomb order that codes this record's residuals in the fewest bits
        unsigned best = 0;
        uint64_t best_bits = UINT64_MAX;
        for (unsigned order = 0; order <= 15; order++) {
            uint64_t b = 0;
            for (const Split &x : out)
                for (uint32_t r : x.residual) b += exp_golomb_bits(r, order);
            if (b < best_bits) best_bits = b, best = order;
        }
        BitWriter w;
        for (const Split &x : out) {
            w.bits(x.p, width(V_));
            w.exp_golomb(x.size - 1, 0);
            w.bit(static_cast<unsigned>(x.faces.size() - 1));
            size_t face = x.first_face;
            for (const Face &g : x.faces) {
                w.bit(g.at[0] == x.p);
                w.bits(g.rank, width(g.ring));
                // each full-mesh corner as its offset in the subtree of the vertex it is at this level
                for (unsigned c = 0; c < 3; c++) w.bits(pm_.faces[face][c] - g.at[c], width(pm_.size[g.at[c]]));
                face++;
            }
            for (uint32_t r : x.residual) w.exp_golomb(r, best);
        }
        std::string p;
        p.push_back(static_cast<char>(best));
        p += w.bytes;
        return p;
    }

  private:
    const PMesh &pm_;
    uint32_t V_;
    std::vector<uint32_t> since_, slot_;
    std::vector<std::set<uint32_t>> corners_of_;   // corner ids 3 f + c at each vertex, this level
    std::vector<uint32_t> level_;                  // each placed corner's vertex at this level
    size_t splits_ = 0, faces_ = 0;                // done, and the faces they and the base have

    // c's nearest ancestor present after `splits` splits
    uint32_t at(uint32_t c, size_t splits) const {
        while (since_[c] > splits) c = pm_.parent[c];
        return c;
    }
    void add_face(size_t f, size_t splits) {
        for (unsigned c = 0; c < 3; c++) {
            const uint32_t a = at(pm_.faces[f][c], splits);
            level_[3 * f + c] = a;
            corners_of_[a].insert(static_cast<uint32_t>(3 * f + c));
        }
    }
    // the distinct vertices sharing a face with u at this level
    std::set<uint32_t> ring(uint32_t u) const {
        std::set<uint32_t> r;
        for (uint32_t c : corners_of_[u]) {
            const uint32_t f = c / 3;
            for (unsigned k = 0; k < 3; k++)
                if (level_[3 * f + k] != u) r.insert(level_[3 * f + k]);
        }
        return r;
    }

    Split split(size_t s) {
        const uint32_t v = pm_.split_vertex[s], p = pm_.parent[v], size = pm_.size[v];
        if (slot_[p] != v)
            throw std::runtime_error("--stream-splits packed: split " + std::to_string(s) +
                                     " does not bring back its parent's next child in depth-first order");
        slot_[p] += size;
        if (s != splits_++) throw std::logic_error("SplitPacker: splits out of order");
        Split x{p, size, faces_, {}, {}};
        const std::set<uint32_t> rp = ring(p);
        for (unsigned j = 0; j < pm_.split_faces[s]; j++) {
            const auto &fc = pm_.faces[faces_ + j];
            std::array<uint32_t, 3> a;
            for (unsigned c = 0; c < 3; c++) a[c] = fc[c] >= v && fc[c] - v < size ? v : at(fc[c], s);
            if (!((a[0] == v && a[1] == p) || (a[0] == p && a[1] == v)) || a[2] == v || a[2] == p || !rp.count(a[2]))
                throw std::runtime_error("--stream-splits packed: split " + std::to_string(s) +
                                         ": a new face is not its vertex, its parent and a neighbour of the parent");
            x.faces.push_back({a, static_cast<uint32_t>(std::distance(rp.begin(), rp.find(a[2]))),
                               static_cast<uint32_t>(rp.size())});
        }
        // the split: the parent's corners whose full-mesh vertex lies in v's subtree go to v
        for (auto it = corners_of_[p].begin(); it != corners_of_[p].end();) {
            const uint32_t c = *it, full = pm_.faces[c / 3][c % 3];
            if (full >= v && full - v < size) {
                level_[c] = v;
                corners_of_[v].insert(c);
                it = corners_of_[p].erase(it);
            } else {
                ++it;
            }
        }
        for (size_t f = faces_; f < faces_ + x.faces.size(); f++) add_face(f, s + 1);
        faces_ += x.faces.size();
        // the position: its difference to the rounded mean of v's neighbours after the split
        const std::set<uint32_t> rv = ring(v);
        for (unsigned k = 0; k < 3; k++) {
            uint64_t sum = 0;
            for (uint32_t u : rv) sum += pm_.positions[u][k];
            const uint32_t n = static_cast<uint32_t>(rv.size()), mean = static_cast<uint32_t>((sum + n / 2) / n);
            x.residual[k] = zigzag(static_cast<int32_t>(pm_.positions[v][k]) - static_cast<int32_t>(mean));
        }
        return x;
    }
};

// A packed stream's reader finds each half-edge's opposite as the one half-edge that runs the other
// way between the same two vertices of the full mesh (stream.h, kind 9); the part's own must be that.
void check_opposites_derivable(const PMesh &pm) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> half;   // (from, to) -> half-edge
    for (size_t f = 0; f < pm.faces.size(); f++)
        for (unsigned k = 0; k < 3; k++)
            if (!half.emplace(std::make_pair(pm.faces[f][k], pm.faces[f][(k + 1) % 3]), 4 * f + k).second)
                throw std::runtime_error("--stream-splits packed: two faces run the same way along one edge");
    for (size_t f = 0; f < pm.faces.size(); f++)
        for (unsigned k = 0; k < 3; k++) {
            const auto it = half.find({pm.faces[f][(k + 1) % 3], pm.faces[f][k]});
            if ((it == half.end() ? kNoHalfEdge : it->second) != pm.opposite[f][k])
                throw std::runtime_error("--stream-splits packed: an edge's opposite is not the half-edge back along it");
        }
}

// Splits per record: the batches double the vertex count until they hold 4096 splits, so that the
// first pictures come soon and a receiver still checks a bounded record at a time.
constexpr size_t kFirstBatch = 64, kLargestBatch = 4096;

// The mesh part's records, payloads in order: mesh header, base, split batches, adjacency.
struct MeshRecord {
    int kind;
    std::string payload;
    size_t level;   // the mesh level drawable once it is in (0: the adjacency)
};
std::vector<MeshRecord> mesh_records(const PMesh &pm, bool packed) {
    const uint32_t V = static_cast<uint32_t>(pm.vertices()), V0 = pm.base_vertices;
    const uint32_t F = static_cast<uint32_t>(pm.faces.size()), F0 = pm.base_faces;
    const uint32_t E = static_cast<uint32_t>(pm.edge_order.size());
    const PmWidths wd = pm_widths(V, F);   // as the baked arrays
    const unsigned ib = wd.index_bytes, hb = wd.half_bytes;
    std::vector<MeshRecord> out;
    std::string h;
    for (uint32_t v : {V, V0, F, F0, E}) put32(h, v);
    h.push_back(static_cast<char>(ib));
    h.push_back(static_cast<char>(hb));
    h.push_back(static_cast<char>(pm.closed() ? 1 : 0));
    h.push_back(0);
    put16(h, static_cast<uint16_t>(pm.crease_cos));
    put16(h, static_cast<uint32_t>(pm.palette.size()));
    for (const auto &c : pm.palette) h.append(reinterpret_cast<const char *>(c.data()), 3);
    out.push_back({kKindMesh, h, 0});
    auto put_face = [&](std::string &s, size_t f) {
        for (uint32_t c : pm.faces[f]) put_n(s, c, ib);
    };
    std::string b;
    for (uint32_t v = 0; v < V; v += pm.size[v]) {   // the roots, whose subtrees tile 0 .. V-1
        put_n(b, v, ib);
        put_position(b, pm.positions[v]);
        put_n(b, pm.size[v], ib);
    }
    for (size_t f = 0; f < F0; f++) put_face(b, f);
    out.push_back({kKindBase, b, V0});
    size_t face = F0;
    const size_t S = pm.split_vertex.size();
    std::unique_ptr<SplitPacker> packer;
    if (packed) packer = std::make_unique<SplitPacker>(pm);
    for (size_t first = 0; first < S;) {
        const size_t k = std::min(S - first, std::clamp<size_t>(V0 + first, kFirstBatch, kLargestBatch));
        std::string p;
        put32(p, static_cast<uint32_t>(first));
        put32(p, static_cast<uint32_t>(k));
        if (packer) {
            p += packer->pack(first, k);
            first += k;
            out.push_back({kKindPacked, p, V0 + first});
            continue;
        }
        for (size_t i = first; i < first + k; i++) {
            const uint32_t v = pm.split_vertex[i];
            put_n(p, v, ib);
            p.push_back(static_cast<char>(pm.split_faces[i]));
            put_position(p, pm.positions[v]);
            put_n(p, pm.parent[v], ib);
            put_n(p, pm.size[v], ib);
            for (unsigned j = 0; j < pm.split_faces[i]; j++) put_face(p, face++);
        }
        first += k;
        out.push_back({kKindSplits, p, V0 + first});
    }
    if (packed) {   // the opposites are the reader's to find; the edge order, 3 f + k in width(3 F) bits
        check_opposites_derivable(pm);
        BitWriter w;
        for (uint32_t h : pm.edge_order) w.bits(3 * (h >> 2) + (h & 3), width(3 * F));
        out.push_back({kKindPackedAdjacency, w.bytes, 0});
        return out;
    }
    std::string a;
    for (const auto &o : pm.opposite)
        for (uint32_t x : o) put_n(a, x, hb);
    for (uint32_t x : pm.edge_order) put_n(a, x, hb);
    out.push_back({kKindAdjacency, a, 0});
    return out;
}

void record(std::string &s, int kind, int level, const std::string &payload) {
    const size_t at = s.size();
    s.push_back(static_cast<char>(kind));
    s.push_back(static_cast<char>(level));
    put16(s, 0);
    put32(s, static_cast<uint32_t>(payload.size()));
    s += payload;
    put32(s, crc32(s, at, 8 + payload.size()));
}

}  // namespace

Stream bake_stream(const Octree &t, const PMesh *pm, bool packed) {
    Stream out;
    std::string &s = out.bytes;
    const bool mono = t.palette.size() == 1;
    std::vector<std::string> levels;
    size_t total = kHeaderBytes + kRecordBytes + 3 * t.palette.size() + kRecordBytes;   // header, palette, end
    for (int l = 0; l <= t.depth; l++) {
        std::string p;
        put32(p, static_cast<uint32_t>(t.nodes(l)));
        if (l < t.depth) put(p, t.masks[l]);
        if (l >= 1 && !mono) put(p, t.colors[l]);
        // a level's cones come with the level three below it, the first depth that culls with them
        const int k = l - 3;
        if (k >= 1 && k < static_cast<int>(t.cones.size()) && !t.cones[k].empty()) put(p, t.cones[k]);
        total += kRecordBytes + p.size();
        levels.push_back(std::move(p));
    }
    const std::vector<MeshRecord> mesh = pm ? mesh_records(*pm, packed) : std::vector<MeshRecord>{};
    for (const auto &r : mesh) total += kRecordBytes + r.payload.size();
    if (total > 0xFFFFFFFFu) throw std::runtime_error("--emit stream: the stream would exceed 4 GiB");
    s.append("mcs\x1A", 4);
    put16(s, pm ? (packed ? 3 : 2) : 1);                  // version: 2 with a mesh part, 3 with packed splits
    s.push_back(static_cast<char>(t.depth));
    s.push_back(pm ? 1 : 0);                              // flags: a mesh part follows
    put16(s, static_cast<uint32_t>(t.palette.size()));
    put16(s, 0);
    put32(s, static_cast<uint32_t>(total));
    put32(s, crc32(s, 0, 16));
    std::string pal;
    for (const auto &c : t.palette) pal.append(reinterpret_cast<const char *>(c.data()), 3);
    record(s, kKindPalette, 0, pal);
    // the mesh header and base first, then levels and batches of splits merged by the bytes each part
    // has had, then the adjacency (stream.h)
    auto put_mesh = [&](const MeshRecord &r) {
        record(s, r.kind, 0, r.payload);
        if (r.kind == kKindAdjacency || r.kind == kKindPackedAdjacency) out.lines_at = s.size();
        else if (r.level) out.mesh_levels.push_back({s.size(), r.level});
    };
    size_t m = 0, octree_bytes = 0, mesh_bytes = 0;
    auto splits = [&](size_t i) { return i < mesh.size() && (mesh[i].kind == kKindSplits || mesh[i].kind == kKindPacked); };
    auto adjacency = [&](size_t i) { return mesh[i].kind == kKindAdjacency || mesh[i].kind == kKindPackedAdjacency; };
    for (; m < mesh.size() && !splits(m) && !adjacency(m); m++) put_mesh(mesh[m]);
    for (int l = 0; l <= t.depth; l++) {
        for (; splits(m) && mesh_bytes < octree_bytes; m++) {
            mesh_bytes += mesh[m].payload.size();
            put_mesh(mesh[m]);
        }
        record(s, kKindLevel, l, levels[l]);
        octree_bytes += levels[l].size();
        if (l >= 1) out.drawable_at.push_back(s.size());
    }
    for (; m < mesh.size(); m++) put_mesh(mesh[m]);
    record(s, kKindEnd, 0, "");
    out.buffer = s.size();
    if (pm) {   // MC_STREAM_MESH_BYTES after the stream, from a multiple of 4
        const uint64_t b = (s.size() + 3) / 4 * 4 + pm_draw_bytes(pm->vertices(), pm->base_vertices, pm->faces.size()) +
                           (packed ? pm_packed_bytes(pm->vertices(), pm->faces.size()) : 0);
        if (b > 0xFFFFFFFFu) throw std::runtime_error("--emit stream: the stream and its mesh would exceed 4 GiB");
        out.buffer = b;
    }
    return out;
}

}  // namespace mc
