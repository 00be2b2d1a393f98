// STL reader, binary and ascii. Binary: an 80-byte header, a little-endian triangle count and 50
// bytes per triangle (normal, three corners as float32, 2 attribute bytes). Ascii: solid /
// facet normal / outer loop / 3 x vertex / endloop / endfacet / endsolid, keywords in any case,
// several solids in a row. A file is binary when its size is exactly 84 + 50 x its count, else
// ascii when it starts with "solid" and its first KiB is text (binary headers often say "solid").
//
// Promise: reads the file once into a mesh (see readers.hpp). STL repeats every corner, so corners
// with equal float coordinates (0 and -0 alike) become one vertex, numbered in order of first use;
// a triangle two of whose corners are equal is dropped. Normals and attribute bytes are ignored.
// A binary count is checked against the file size before anything is reserved.
#include <cstring>
#include <unordered_map>

#include "input/faces.hpp"
#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc::input {
namespace {

uint32_t le32(const unsigned char *b) {
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

float le_float(const unsigned char *b) {
    const uint32_t u = le32(b);
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

// Corners to vertices: equal coordinates, one vertex.
class Corners {
public:
    explicit Corners(Model &m) : m_(m) {}
    uint32_t vertex(const float c[3]) {
        Key k{bits(c[0]), bits(c[1]), bits(c[2])};
        auto [it, added] = at_.emplace(k, static_cast<uint32_t>(m_.points.size()));
        if (added) m_.points.push_back({c[0], c[1], c[2]});
        return it->second;
    }

private:
    using Key = std::array<uint32_t, 3>;
    static uint32_t bits(float f) {
        if (f == 0) f = 0;  // -0 is 0
        uint32_t u;
        std::memcpy(&u, &f, sizeof u);
        return u;
    }
    struct Hash {
        size_t operator()(const Key &k) const {
            uint64_t h = k[0];
            h = h * 0x9E3779B97F4A7C15ull ^ k[1];
            h = h * 0x9E3779B97F4A7C15ull ^ k[2];
            return static_cast<size_t>(h ^ (h >> 29));
        }
    };
    Model &m_;
    std::unordered_map<Key, uint32_t, Hash> at_;
};

bool stl_is_text(const std::string &path, uint64_t size) {
    ByteReader in(path);
    unsigned char head[1024];
    const size_t n = in.read(reinterpret_cast<char *>(head), sizeof head);
    if (n >= 84 && size == 84 + 50 * uint64_t(le32(head + 80))) return false;
    size_t i = 0;
    while (i < n && (is_space(char(head[i])) || head[i] == '\n')) ++i;
    if (n - i < 5 || lower(std::string_view(reinterpret_cast<char *>(head) + i, 5)) != "solid") return false;
    for (size_t k = 0; k < n; ++k)
        if ((head[k] < 32 || head[k] > 126) && !is_space(char(head[k])) && head[k] != '\n') return false;
    return true;
}

Model read_binary(const std::string &path, uint64_t size) {
    ByteReader in(path);
    unsigned char head[84];
    if (in.read(reinterpret_cast<char *>(head), 84) < 84) fail_byte(path, size, "file ends inside the 84-byte header of a binary STL");
    const uint64_t n = le32(head + 80);
    if (n > kMaxElements) fail_byte(path, 80, "triangle count " + num(n) + " exceeds the limit of " + kLimit);
    const uint64_t need = 84 + 50 * n;
    if (size < need)
        fail_byte(path, size, "file ends after " + num((size - 84) / 50) + " of " + num(n) + " triangles (needs " +
                                  num(need) + " bytes, has " + num(size) + ")");
    if (size > need)
        fail_byte(path, need, num(size - need) + " bytes of extra data after " + num(n) +
                                  " triangles (the count in the header does not match the file size)");
    if (n == 0) fail_none(path, "mesh has no faces");
    Model m;
    m.is_mesh = true;
    m.tris.reserve(n);  // the size check above proved the file holds N triangles
    Corners corners(m);
    Faces faces(m.tris);
    std::vector<uint32_t> idx(3);
    for (uint64_t i = 0; i < n; ++i) {
        unsigned char t[50];
        const uint64_t at = in.offset();
        in.read(reinterpret_cast<char *>(t), 50);
        float c[9];
        for (int k = 0; k < 9; ++k) {
            c[k] = le_float(t + 12 + 4 * k);  // the first 12 bytes are the normal
            if (const char *why = bad_coordinate(c[k]))
                fail_byte(path, at + 12 + 4 * k, std::string(why) + " (" + show(c[k]) + ") in triangle " + num(i));
        }
        for (int v = 0; v < 3; ++v) idx[v] = corners.vertex(c + 3 * v);
        faces.add(idx);
    }
    return m;
}

class TextStl {
public:
    TextStl(ByteReader &in, const std::string &path) : path_(path), r_(in, path, false), corners_(m_), faces_(m_.tris) {
        m_.is_mesh = true;
    }

    Model run() {
        r_.next_content();  // stl_is_text() saw "solid"
        solid();
        for (;;) {
            if (!r_.next_content()) r_.fail("file ends before 'endsolid' (after " + num(facets_) + " facets)");
            const std::string kw = lower(r_.tok()[0]);
            if (kw == "facet") {
                facet();
            } else if (kw == "endsolid") {
                if (!r_.next_content()) break;
                if (lower(r_.tok()[0]) != "solid") r_.fail("extra data after 'endsolid': " + quote(r_.tok()[0]));
                solid();  // several solids in one file
            } else {
                r_.fail("expected 'facet normal' or 'endsolid', found " + quote(r_.tok()[0]));
            }
        }
        if (facets_ == 0) fail_none(path_, "mesh has no faces");
        return std::move(m_);
    }

private:
    static std::string join(const Tokens &t) {
        std::string r;
        for (size_t i = 0; i < t.size(); ++i) r += (i ? " " : "") + std::string(t[i]);
        return r;
    }

    void solid() {
        if (lower(r_.tok()[0]) != "solid") r_.fail("expected 'solid', found " + quote(r_.tok()[0]));
    }

    void facet() {
        const Tokens &t = r_.tok();
        if (t.size() != 5 || lower(t[1]) != "normal") r_.fail("expected 'facet normal nx ny nz', found " + quote(join(t)));
        for (int k = 2; k < 5; ++k)
            if (double v; parse_double(t[k], v) == Num::bad) r_.fail("not a number: " + quote(t[k]));
        if (++facets_ > kMaxElements) r_.fail("more than " + kLimit + " facets");
        expect("outer loop");
        std::vector<uint32_t> idx(3);
        for (int v = 0; v < 3; ++v) idx[v] = corner(v);
        expect("endloop");
        expect("endfacet");
        faces_.add(idx);
    }

    uint32_t corner(int v) {
        next_in_facet();
        const Tokens &t = r_.tok();
        const std::string kw = lower(t[0]);
        if (kw == "endloop") r_.fail("facet has " + std::to_string(v) + " vertices, expected 3");
        if (kw != "vertex" || t.size() != 4) r_.fail("expected 'vertex x y z', found " + quote(join(t)));
        float c[3];
        for (int k = 0; k < 3; ++k) c[k] = r_.coordinate_f(t[k + 1]);
        return corners_.vertex(c);
    }

    void expect(const std::string &words) {
        next_in_facet();
        const std::string got = lower(join(r_.tok()));
        if (words == "endloop" && lower(r_.tok()[0]) == "vertex") r_.fail("facet has more than 3 vertices");
        if (got != words) r_.fail("expected '" + words + "', found " + quote(join(r_.tok())));
    }

    void next_in_facet() {
        if (!r_.next_content()) r_.fail("file ends inside facet " + num(facets_));
    }

    std::string path_;
    TextReader r_;
    Model m_;
    Corners corners_;
    Faces faces_;
    uint64_t facets_ = 0;
};

}  // namespace

Model read_stl(const std::string &path, uint64_t size) {
    if (!stl_is_text(path, size)) return read_binary(path, size);
    ByteReader in(path);
    return TextStl(in, path).run();
}

}  // namespace mc::input
