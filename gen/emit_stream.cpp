// --emit stream: the bake as one binary stream, coarse first: the octree's levels, then a mesh part's
// base, splits and adjacency (the format is runtime/include/modelc/stream.h's, read by
// runtime/src/stream.c and stream_mesh.c).
#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "emit.hpp"
#include "pmesh.hpp"

namespace mc {
namespace {

constexpr int kKindPalette = 1, kKindLevel = 2, kKindEnd = 3, kKindMesh = 4, kKindBase = 5, kKindSplits = 6,
              kKindAdjacency = 7;
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

// Splits per record: the batches double the vertex count until they hold 4096 splits, so that the
// first pictures come soon and a receiver still checks a bounded record at a time.
constexpr size_t kFirstBatch = 64, kLargestBatch = 4096;

// The mesh part's records, payloads in order: mesh header, base, split batches, adjacency.
struct MeshRecord {
    int kind;
    std::string payload;
    size_t level;   // the mesh level drawable once it is in (0: the adjacency)
};
std::vector<MeshRecord> mesh_records(const PMesh &pm) {
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
    for (size_t first = 0; first < S;) {
        const size_t k = std::min(S - first, std::clamp<size_t>(V0 + first, kFirstBatch, kLargestBatch));
        std::string p;
        put32(p, static_cast<uint32_t>(first));
        put32(p, static_cast<uint32_t>(k));
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

Stream bake_stream(const Octree &t, const PMesh *pm) {
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
    const std::vector<MeshRecord> mesh = pm ? mesh_records(*pm) : std::vector<MeshRecord>{};
    for (const auto &r : mesh) total += kRecordBytes + r.payload.size();
    if (total > 0xFFFFFFFFu) throw std::runtime_error("--emit stream: the stream would exceed 4 GiB");
    s.append("mcs\x1A", 4);
    put16(s, pm ? 2 : 1);                                 // version: 2 with a mesh part
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
        if (r.kind == kKindAdjacency) out.lines_at = s.size();
        else if (r.level) out.mesh_levels.push_back({s.size(), r.level});
    };
    size_t m = 0, octree_bytes = 0, mesh_bytes = 0;
    for (; m < mesh.size() && mesh[m].kind != kKindSplits && mesh[m].kind != kKindAdjacency; m++) put_mesh(mesh[m]);
    for (int l = 0; l <= t.depth; l++) {
        for (; m < mesh.size() && mesh[m].kind == kKindSplits && mesh_bytes < octree_bytes; m++) {
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
        const uint64_t b = (s.size() + 3) / 4 * 4 + pm_draw_bytes(pm->vertices(), pm->base_vertices, pm->faces.size());
        if (b > 0xFFFFFFFFu) throw std::runtime_error("--emit stream: the stream and its mesh would exceed 4 GiB");
        out.buffer = b;
    }
    return out;
}

}  // namespace mc
