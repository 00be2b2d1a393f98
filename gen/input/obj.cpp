// OBJ reader: 'v x y z [w]' or 'v x y z r g b' (colours 0..1) and 'f' lines with corners v, v/t,
// v/t/n or v//n; positive indices count from 1 and may name any vertex of the file, negative ones
// count back from the last vertex read so far. Every other statement (vt, vn, g, o, s, usemtl,
// mtllib, ...) is skipped unread: the model has no use for it. '#' starts a comment.
//
// Promise: reads the file once into a mesh (see readers.hpp). A face that names a vertex twice
// keeps the first mention of each vertex (the usual reading of OBJ exports that close a polygon by
// repeating its first corner), and is dropped only when fewer than 3 vertices remain. Colours are
// all or nothing and become bytes as float v * 255 + 0.5, truncated. Forward references are
// checked after the last vertex, reported at the line of the face that made them.
#include <algorithm>

#include "input/faces.hpp"
#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc::input {
namespace {

class ObjReader {
public:
    ObjReader(ByteReader &in, const std::string &path) : path_(path), r_(in, path, true) {}

    Model run() {
        m_.is_mesh = true;
        while (r_.next_content()) {
            const std::string_view k = r_.tok()[0];
            if (k == "v") vertex();
            else if (k == "f") face();
        }
        if (m_.points.empty()) fail_none(path_, "model has no vertices");
        if (face_line_.empty()) fail_none(path_, "mesh has no faces");
        build();
        return std::move(m_);
    }

private:
    void vertex() {
        const Tokens &t = r_.tok();
        const size_t n = t.size() - 1;
        if (n != 3 && n != 4 && n != 6)
            r_.fail("expected 3, 4 or 6 numbers after 'v' (x y z [w] or x y z r g b), found " + num(n));
        std::array<double, 3> p;
        for (int k = 0; k < 3; ++k) p[k] = r_.coordinate_f(t[k + 1]);
        std::array<uint8_t, 3> c{};
        for (size_t k = 4; k < t.size(); ++k) {
            const double v = r_.number(t[k]);  // w is checked and ignored
            if (n != 6) continue;
            if (v < 0 || v > 1) r_.fail("colour value " + quote(t[k]) + " out of range (0..1)");
            float f = 0;
            parse_float(t[k], f);
            c[k - 4] = static_cast<uint8_t>(f * 255.0f + 0.5f);
        }
        const bool color = n == 6;
        if (!m_.points.empty() && color != !m_.colors.empty())
            r_.fail(color ? "vertex has a colour but earlier vertices have none"
                          : "vertex has no colour but earlier vertices have one");
        if (m_.points.size() >= kMaxElements) r_.fail("more than " + kLimit + " vertices");
        m_.points.push_back(p);
        if (color) m_.colors.push_back(c);
    }

    void face() {
        const Tokens &t = r_.tok();
        if (t.size() < 4) r_.fail("face has " + num(t.size() - 1) + " vertices (at least 3 needed)");
        if (face_line_.size() >= kMaxElements) r_.fail("more than " + kLimit + " faces");
        face_start_.push_back(corners_.size());
        face_line_.push_back(r_.line());
        for (size_t k = 1; k < t.size(); ++k) corners_.push_back(corner(t[k]));
    }

    // One face corner: v, v/t, v/t/n or v//n. Returns the 0-based vertex index; one past the
    // vertices read so far may still be valid (checked in build()).
    uint32_t corner(std::string_view tok) {
        std::string_view part[3];
        size_t parts = 0, start = 0;
        for (;;) {
            size_t slash = tok.find('/', start);
            if (parts == 3) r_.fail("bad face vertex " + quote(tok));
            part[parts++] = tok.substr(start, slash == std::string_view::npos ? slash : slash - start);
            if (slash == std::string_view::npos) break;
            start = slash + 1;
        }
        long long v = 0, unused = 0;
        const Num n = parse_int(part[0], v);
        if (n == Num::bad) r_.fail("bad face vertex " + quote(tok));
        for (size_t k = 1; k < parts; ++k)
            if (!part[k].empty() && parse_int(part[k], unused) == Num::bad) r_.fail("bad face vertex " + quote(tok));
        const std::string shown(part[0]);
        const uint64_t nv = m_.points.size();
        if (n == Num::ok && v == 0) r_.fail("vertex index 0 is invalid (OBJ indices start at 1)");
        if (n == Num::ok && v > 0 && static_cast<uint64_t>(v) <= kMaxElements) return static_cast<uint32_t>(v - 1);
        if (n == Num::ok && v < 0 && v >= -static_cast<long long>(nv)) return static_cast<uint32_t>(static_cast<int64_t>(nv) + v);
        if (part[0][0] != '-') r_.fail("vertex index " + shown + " exceeds the limit of " + kLimit);
        if (nv == 0) r_.fail("vertex index " + shown + " but no vertex precedes this face");
        r_.fail("vertex index " + shown + " out of range (-" + num(nv) + "..-1)");
    }

    void build() {
        const uint64_t nv = m_.points.size();
        Faces faces(m_.tris);
        std::vector<uint32_t> idx;
        face_start_.push_back(corners_.size());
        for (size_t f = 0; f + 1 < face_start_.size(); ++f) {
            idx.clear();
            for (size_t k = face_start_[f]; k < face_start_[f + 1]; ++k) {
                const uint32_t v = corners_[k];
                if (v >= nv) fail_line(path_, face_line_[f], "vertex index " + num(uint64_t(v) + 1) + " out of range (1.." + num(nv) + ")");
                idx.push_back(v);
            }
            first_mentions(idx);
            faces.add(idx);
        }
    }

    // Keeps the first mention of each vertex, in order.
    void first_mentions(std::vector<uint32_t> &idx) {
        if (idx.size() <= 16) {  // faces are short: pairwise is cheapest
            size_t n = 0;
            for (size_t i = 0; i < idx.size(); ++i)
                if (std::find(idx.begin(), idx.begin() + n, idx[i]) == idx.begin() + n) idx[n++] = idx[i];
            idx.resize(n);
            return;
        }
        order_.clear();  // (vertex, position), sorted: a long face costs n log n, not n^2
        for (size_t i = 0; i < idx.size(); ++i) order_.push_back({idx[i], i});
        std::sort(order_.begin(), order_.end());
        std::vector<bool> keep(idx.size(), false);
        for (size_t i = 0; i < order_.size(); ++i)
            if (i == 0 || order_[i].first != order_[i - 1].first) keep[order_[i].second] = true;
        size_t n = 0;
        for (size_t i = 0; i < idx.size(); ++i)
            if (keep[i]) idx[n++] = idx[i];
        idx.resize(n);
    }

    std::string path_;
    TextReader r_;
    std::vector<std::pair<uint32_t, size_t>> order_;
    Model m_;
    std::vector<uint32_t> corners_;    // every face's corners, 0-based (at most kMaxElements - 1)
    std::vector<size_t> face_start_;   // where each face's corners begin in corners_
    std::vector<long long> face_line_;
};

}  // namespace

Model read_obj(const std::string &path, uint64_t) {
    ByteReader in(path);
    return ObjReader(in, path).run();
}

}  // namespace mc::input
