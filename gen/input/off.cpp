// OFF reader: [ST][C][N]OFF header (optionally with the counts on the same line), the vertex, face
// and edge counts, one vertex per line (x y z [nx ny nz] [r g b [a]] [s t]) and one face per line
// (n i1 .. in [r g b [a]]). '#' starts a comment anywhere; blank lines are skipped.
//
// Promise: reads the file once into a mesh (see readers.hpp); colours of a C...OFF header are
// integers 0..255, or decimals 0..1 when any value of the vertex has a '.', turned into bytes as
// round(255 v) computed in float (v * 255 + 0.5, truncated); face colours are checked and ignored.
// Counts are checked against the bytes left before anything is reserved.
#include <algorithm>

#include "input/faces.hpp"
#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc::input {
namespace {

class OffReader {
public:
    OffReader(ByteReader &in, const std::string &path, uint64_t size) : in_(in), path_(path), size_(size), r_(in, path, true) {}

    Model run() {
        m_.is_mesh = true;
        header();
        vertices();
        faces();
        if (r_.next_content())
            r_.fail("extra data after the last " + std::string(nf_ ? "face" : "vertex") + " (the header says " +
                    num(nv_) + " vertices, " + num(nf_) + " faces)");
        if (nv_ == 0) fail_none(path_, "model has no vertices");
        if (nf_ == 0) fail_none(path_, "mesh has no faces");
        return std::move(m_);
    }

private:
    void header() {
        if (!r_.next_content()) r_.fail("no OFF header (only comments or blank lines)");
        const Tokens &t = r_.tok();
        keyword(t[0]);
        if (t.size() > 1 && t[1] == "BINARY") r_.fail("binary OFF is not supported");
        if (t.size() > 1) {
            counts(t, 1);
        } else {
            if (!r_.next_content()) r_.fail("file ends before the vertex, face and edge counts");
            counts(r_.tok(), 0);
        }
    }

    void keyword(std::string_view h) {
        std::string_view s = h;
        auto eat = [&s](std::string_view p) {
            if (s.substr(0, p.size()) != p) return false;
            s.remove_prefix(p.size());
            return true;
        };
        st_ = eat("ST");
        color_ = eat("C");
        normal_ = eat("N");
        bool not_3d = eat("4");
        not_3d = eat("n") || not_3d;
        if (s != "OFF") r_.fail("expected an OFF header (OFF, COFF, NOFF, CNOFF, STOFF...), found " + quote(h));
        if (not_3d) r_.fail(quote(h) + " (not 3D) is not supported");
    }

    void counts(const Tokens &t, size_t i) {
        if (t.size() - i != 3)
            r_.fail("expected 3 counts (vertices faces edges), found " + num(t.size() - i) + " values");
        nv_ = count(t[i], "vertices");
        nf_ = count(t[i + 1], "faces");
        long long ne = 0;
        if (parse_int(t[i + 2], ne) != Num::ok || ne < 0) r_.fail("bad edge count: " + quote(t[i + 2]));
        // A vertex line has at least 6 bytes ("0 0 0\n"), a face line at least 8 ("3 0 1 2\n").
        const uint64_t left = size_ - std::min(size_, in_.offset());
        m_.points.reserve(reserve_for(nv_, 6, left));
        if (color_) m_.colors.reserve(reserve_for(nv_, 12, left));
        m_.tris.reserve(reserve_for(nf_, 8, left));
    }

    uint64_t count(std::string_view t, const std::string &what) {
        long long v = 0;
        Num n = parse_int(t, v);
        if (n == Num::bad) r_.fail("expected the number of " + what + ", found " + quote(t));
        if (n == Num::ok && v < 0) r_.fail("negative number of " + what + ": " + std::string(t));
        if (n == Num::range || static_cast<uint64_t>(v) > kMaxElements)
            r_.fail(std::string(t) + " " + what + " exceed the limit of " + kLimit);
        return static_cast<uint64_t>(v);
    }

    void vertices() {
        const size_t base = 3 + (normal_ ? 3 : 0) + (st_ ? 2 : 0);
        for (uint64_t i = 0; i < nv_; ++i) {
            if (!r_.next_content()) r_.fail("file ends after " + num(i) + " of " + num(nv_) + " vertices");
            const Tokens &t = r_.tok();
            const bool ok = color_ ? t.size() == base + 3 || t.size() == base + 4 : t.size() == base;
            if (!ok) {
                std::string want = color_ ? num(base + 3) + " or " + num(base + 4) : num(base);
                r_.fail("expected " + want + " numbers per vertex, found " + num(t.size()));
            }
            std::array<double, 3> p;
            for (int k = 0; k < 3; ++k) p[k] = r_.coordinate_f(t[k]);
            m_.points.push_back(p);
            const size_t k = normal_ ? 6 : 3;
            for (size_t j = 3; j < k; ++j) r_.number(t[j]);  // normals: checked, not kept for meshes
            const size_t colors = t.size() - base;
            if (color_) m_.colors.push_back(color(t, k, colors));
            for (size_t j = k + colors; j < t.size(); ++j) r_.number(t[j]);  // texture coordinates
        }
    }

    // Integers 0..255 or, when any value is written with a '.', decimals 0..1.
    std::array<uint8_t, 3> color(const Tokens &t, size_t from, size_t n) {
        bool decimal = false;
        for (size_t j = from; j < from + n; ++j) decimal = decimal || t[j].find('.') != std::string_view::npos;
        std::array<uint8_t, 3> c{};
        for (size_t j = from; j < from + n; ++j) {
            uint8_t byte = 0;
            if (decimal) {
                double v = r_.number(t[j]);
                if (v < 0 || v > 1) r_.fail("colour value " + quote(t[j]) + " out of range (0..1)");
                float f = 0;
                parse_float(t[j], f);
                byte = static_cast<uint8_t>(f * 255.0f + 0.5f);
            } else {
                long long v = 0;
                if (parse_int(t[j], v) != Num::ok) r_.fail("colour value is not an integer 0..255: " + quote(t[j]));
                if (v < 0 || v > 255) r_.fail("colour value " + quote(t[j]) + " out of range (0..255)");
                byte = static_cast<uint8_t>(v);
            }
            if (j - from < 3) c[j - from] = byte;  // an alpha value is checked, not kept
        }
        return c;
    }

    void faces() {
        Faces faces(m_.tris);
        std::vector<uint32_t> idx;
        for (uint64_t i = 0; i < nf_; ++i) {
            if (!r_.next_content()) r_.fail("file ends after " + num(i) + " of " + num(nf_) + " faces");
            const Tokens &t = r_.tok();
            long long n = 0;
            if (parse_int(t[0], n) != Num::ok) r_.fail("expected a face (vertex count, then indices), found " + quote(t[0]));
            if (n < 3) r_.fail("face has " + std::to_string(n) + " vertices (at least 3 needed)");
            const uint64_t have = t.size() - 1, want = static_cast<uint64_t>(n);
            if (have < want) r_.fail("face has " + num(have) + " vertex indices but its count says " + num(want));
            const uint64_t extra = have - want;
            if (extra != 0 && extra != 3 && extra != 4)
                r_.fail("face count says " + num(want) + " but " + num(have) +
                        " values follow (expected the indices, optionally then an RGB or RGBA colour)");
            idx.clear();
            for (uint64_t j = 1; j <= want; ++j) idx.push_back(index(t[j]));
            for (size_t j = want + 1; j < t.size(); ++j) r_.number(t[j]);  // face colour: checked, not kept
            faces.add(idx);
        }
    }

    uint32_t index(std::string_view t) {
        long long v = 0;
        Num n = parse_int(t, v);
        if (n == Num::bad) r_.fail("vertex index is not an integer: " + quote(t));
        if (n == Num::range || v < 0 || static_cast<uint64_t>(v) >= nv_)
            r_.fail("vertex index " + std::string(t) + " out of range " +
                    (nv_ ? "(0.." + num(nv_ - 1) + ")" : "(the file has no vertices)"));
        return static_cast<uint32_t>(v);
    }

    ByteReader &in_;
    std::string path_;
    uint64_t size_;
    TextReader r_;
    Model m_;
    bool st_ = false, color_ = false, normal_ = false;
    uint64_t nv_ = 0, nf_ = 0;
};

}  // namespace

Model read_off(const std::string &path, uint64_t size) {
    ByteReader in(path);
    return OffReader(in, path, size).run();
}

}  // namespace mc::input
