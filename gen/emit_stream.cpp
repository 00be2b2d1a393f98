// --emit stream: the octree as one binary stream, coarse levels first (the format is
// runtime/include/modelc/stream.h's, read by runtime/src/stream.c).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "emit.hpp"

namespace mc {
namespace {

constexpr int kKindPalette = 1, kKindLevel = 2, kKindEnd = 3;
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

Stream octree_stream(const Octree &t) {
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
    if (total > 0xFFFFFFFFu) throw std::runtime_error("--emit stream: the stream would exceed 4 GiB");
    s.append("mcs\x1A", 4);
    put16(s, 1);                                          // version
    s.push_back(static_cast<char>(t.depth));
    s.push_back(0);                                       // flags
    put16(s, static_cast<uint32_t>(t.palette.size()));
    put16(s, 0);
    put32(s, static_cast<uint32_t>(total));
    put32(s, crc32(s, 0, 16));
    std::string pal;
    for (const auto &c : t.palette) pal.append(reinterpret_cast<const char *>(c.data()), 3);
    record(s, kKindPalette, 0, pal);
    for (int l = 0; l <= t.depth; l++) {
        record(s, kKindLevel, l, levels[l]);
        if (l >= 1) out.drawable_at.push_back(s.size());
    }
    record(s, kKindEnd, 0, "");
    return out;
}

}  // namespace mc
