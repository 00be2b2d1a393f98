// CAO reader: ViSP's model-based tracker format (vpMbTracker::loadCAOModel). In order: the
// header V1 (or V2, whose point lines add two integer image coordinates), then five sections,
// each a count followed by one record per line:
//   points            x y z
//   3D lines          i j [key=value...]                 (point indices)
//   faces from lines  n l1 .. ln [key=value...]          (3D line indices)
//   faces from points n p1 .. pn [key=value...]          (point indices)
//   cylinders, circles: counts only; both may be missing at the end of older files.
// Indices count from 0. '#' starts a comment; blank lines are skipped. Attributes (name=...,
// name="with spaces", useLod=..., minLineLengthThreshold=...) are checked for form and ignored.
//
// Promise: reads the file once into a mesh (see readers.hpp). A face from lines becomes the vertex
// loop its lines chain into, running from its first line's first point to that line's second;
// lines that do not chain into exactly one closed loop are an error, as are includes
// (load(...)), cylinders and circles (modelc tracks lines and polygons) and anything after a
// record but attributes. Model::lines holds the 3D lines, then each kept polygon's sides, every
// edge once (smaller index first) in order of first mention; a face that names a point twice is
// dropped (faces.hpp) and adds no sides.
#include <algorithm>

#include "input/faces.hpp"
#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc::input {
namespace {

class CaoReader {
public:
    CaoReader(ByteReader &in, const std::string &path, uint64_t size) : in_(in), path_(path), size_(size), r_(in, path, true) {}

    Model run() {
        m_.is_mesh = true;
        header();
        points();
        lines();
        Faces faces(m_.tris);
        faces_from_lines(faces);
        faces_from_points(faces);
        if (unsupported("cylinders")) unsupported("circles");
        if (r_.next_content()) r_.fail("extra data after the circles: " + quote(r_.tok()[0]));
        if (nfaces_ == 0) fail_none(path_, "mesh has no faces");
        dedup_edges();
        return std::move(m_);
    }

private:
    // Comments, then V1 or V2 alone on its line.
    void header() {
        if (!r_.next_content()) r_.fail("no V1 header (only comments or blank lines)");
        include();
        const Tokens &t = r_.tok();
        long long v = 0;
        if (t[0].size() < 2 || t[0][0] != 'V' || parse_int(t[0].substr(1), v) != Num::ok)
            r_.fail("expected the version header V1, found " + quote(t[0]));
        if (v != 1 && v != 2) r_.fail("version " + quote(t[0]) + " is not supported (V1 or V2)");
        v2_ = v == 2;
        alone(1, "the header");
    }

    // ViSP merges the files that load("other.cao") names; modelc reads one file.
    void include() {
        if (r_.tok()[0].substr(0, 4) == "load") r_.fail("includes (load(...)) are not supported");
    }

    void alone(size_t n, const std::string &what) {
        if (r_.tok().size() > n) r_.fail("unexpected " + quote(r_.tok()[n]) + " after " + what);
    }

    // A section's count alone on the next line.
    uint64_t count(const std::string &what) {
        if (!r_.next_content()) r_.fail("file ends before the number of " + what);
        return count_here(what);
    }

    uint64_t count_here(const std::string &what) {
        include();
        const std::string_view t = r_.tok()[0];
        long long v = 0;
        const Num n = parse_int(t, v);
        if (n == Num::bad) r_.fail("expected the number of " + what + ", found " + quote(t));
        if (n == Num::ok && v < 0) r_.fail("negative number of " + what + ": " + std::string(t));
        if (n == Num::range || static_cast<uint64_t>(v) > kMaxElements)
            r_.fail(std::string(t) + " " + what + " exceed the limit of " + kLimit);
        alone(1, "the number of " + what);
        return static_cast<uint64_t>(v);
    }

    uint64_t left() const { return size_ - std::min(size_, in_.offset()); }

    void record(uint64_t i, uint64_t n, const std::string &what) {
        if (!r_.next_content()) r_.fail("file ends after " + num(i) + " of " + num(n) + " " + what);
    }

    void points() {
        const uint64_t n = count("points");
        if (n == 0) r_.fail("number of points is 0 (the model needs points)");
        m_.points.reserve(reserve_for(n, 6, left()));  // "0 0 0\n"
        const size_t want = v2_ ? 5 : 3;
        for (uint64_t i = 0; i < n; ++i) {
            record(i, n, "points");
            const Tokens &t = r_.tok();
            if (t.size() != want)
                r_.fail("expected " + std::string(v2_ ? "5 values per point (x y z i j)" : "3 numbers per point (x y z)") +
                        ", found " + num(t.size()));
            std::array<double, 3> p;
            for (int k = 0; k < 3; ++k) p[k] = r_.coordinate_f(t[k]);
            long long unused = 0;
            for (size_t k = 3; k < want; ++k)  // V2's image coordinates: checked, not kept
                if (parse_int(t[k], unused) != Num::ok) r_.fail("image coordinate is not an integer: " + quote(t[k]));
            m_.points.push_back(p);
        }
    }

    void lines() {
        const uint64_t n = count("3D lines");
        file_lines_.reserve(reserve_for(n, 4, left()));  // "0 1\n"
        for (uint64_t i = 0; i < n; ++i) {
            record(i, n, "3D lines");
            const Tokens &t = r_.tok();
            const size_t have = leading_integers(t, 0);
            if (have != 2) {
                if (have < 2 && have < t.size() && !is_attribute(t[have])) index(t[have], "point", 0);  // its message
                r_.fail("3D line has " + num(have) + (have == 1 ? " point index" : " point indices") + " (expected 2)");
            }
            const uint32_t a = index(t[0], "point", m_.points.size()), b = index(t[1], "point", m_.points.size());
            if (a == b) r_.fail("3D line names point " + num(a) + " twice");
            attributes(t, 2, "the 3D line");
            file_lines_.push_back({a, b});
            edge(a, b);
        }
    }

    void faces_from_lines(Faces &faces) {
        const uint64_t n = count("faces from lines");
        m_.tris.reserve(reserve_for(n, 8, left()));  // "3 0 1 2\n"
        std::vector<uint32_t> ls, loop;
        for (uint64_t i = 0; i < n; ++i) {
            record(i, n, "faces from lines");
            face_indices(ls, "line", file_lines_.size());
            chain(ls, loop);
            faces.add(loop);  // a loop never repeats a point: always kept
            for (uint32_t l : ls) edge(file_lines_[l][0], file_lines_[l][1]);
            ++nfaces_;
        }
    }

    void faces_from_points(Faces &faces) {
        const uint64_t n = count("faces from points");
        m_.tris.reserve(m_.tris.size() + reserve_for(n, 8, left()));
        std::vector<uint32_t> idx;
        for (uint64_t i = 0; i < n; ++i) {
            record(i, n, "faces from points");
            face_indices(idx, "point", m_.points.size());
            if (faces.add(idx))
                for (size_t k = 0; k < idx.size(); ++k) edge(idx[k], idx[(k + 1) % idx.size()]);
            ++nfaces_;
        }
    }

    // Cylinders and circles have no polygon to bake; their counts may be missing at the end of
    // older files (ViSP reads them as 0). Returns whether the file goes on.
    bool unsupported(const std::string &what) {
        if (!r_.next_content()) return false;
        if (count_here(what) > 0) r_.fail(what + " are not supported: modelc tracks lines and polygons");
        return true;
    }

    // "n i1 .. in [key=value...]" on the current line into IDX: n >= 3 indices of WHAT below N.
    void face_indices(std::vector<uint32_t> &idx, const std::string &what, uint64_t n) {
        const Tokens &t = r_.tok();
        long long c = 0;
        const Num cn = parse_int(t[0], c);
        if (cn == Num::bad) r_.fail("expected a face (number of " + what + "s, then " + what + " indices), found " + quote(t[0]));
        if (cn == Num::ok && c < 3) r_.fail("face has " + std::string(t[0]) + " " + what + "s (at least 3 needed)");
        const size_t have = leading_integers(t, 1);
        if (cn == Num::range || static_cast<uint64_t>(c) > have) {
            if (1 + have < t.size() && !is_attribute(t[1 + have])) index(t[1 + have], what, 0);  // its message
            r_.fail("face has " + num(have) + " " + what + " indices but its count says " + std::string(t[0]));
        }
        const size_t want = static_cast<size_t>(c);
        if (have > want) r_.fail("face count says " + num(want) + " but " + num(have) + " " + what + " indices follow");
        idx.clear();
        for (size_t j = 1; j <= want; ++j) idx.push_back(index(t[j], what, n));
        attributes(t, 1 + want, "the face");
    }

    // How many tokens from FROM on read as integers (in range or not).
    static size_t leading_integers(const Tokens &t, size_t from) {
        long long v = 0;
        size_t k = from;
        while (k < t.size() && parse_int(t[k], v) != Num::bad) ++k;
        return k - from;
    }

    uint32_t index(std::string_view t, const std::string &what, uint64_t n) {
        long long v = 0;
        const Num k = parse_int(t, v);
        if (k == Num::bad) r_.fail(what + " index is not an integer: " + quote(t));
        if (k == Num::range || v < 0 || static_cast<uint64_t>(v) >= n)
            r_.fail(what + " index " + std::string(t) + " out of range " +
                    (n ? "(0.." + num(n - 1) + ")" : "(the file has no " + std::string(what == "line" ? "3D line" : what) + "s)"));
        return static_cast<uint32_t>(v);
    }

    // key=value, the key a name, the value anything (an empty one too) up to a space.
    static bool is_attribute(std::string_view t) {
        const size_t eq = t.find('=');
        if (eq == 0 || eq == std::string_view::npos) return false;
        for (size_t k = 0; k < eq; ++k) {
            const char c = t[k];
            const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
            if (!letter && !(k > 0 && c >= '0' && c <= '9')) return false;
        }
        return true;
    }

    // Tokens FROM on: attributes only; a value in double quotes may hold spaces (name="face 1").
    void attributes(const Tokens &t, size_t from, const std::string &what) {
        for (size_t k = from; k < t.size(); ++k) {
            if (!is_attribute(t[k])) r_.fail("expected key=value attributes after " + what + ", found " + quote(t[k]));
            std::string_view v = t[k].substr(t[k].find('=') + 1);
            if (v.empty() || v[0] != '"') continue;
            v.remove_prefix(1);
            for (size_t j = k;; v = t[++j]) {  // on to the token that closes the quote
                const size_t q = v.find('"');
                if (q != std::string_view::npos) {
                    if (q + 1 != v.size()) r_.fail("unexpected " + quote(v.substr(q + 1)) + " after a quoted value");
                    k = j;
                    break;
                }
                if (j + 1 == t.size()) r_.fail("quoted value of " + quote(t[k]) + " has no closing quote");
            }
        }
    }

    // The face's lines LS as one closed loop of points: each point ends exactly two of them, and
    // walking from the first line's first point comes back after all of them.
    void chain(const std::vector<uint32_t> &ls, std::vector<uint32_t> &loop) {
        ends_.clear();  // (point, 2 * line position + end), sorted: each point's two ends side by side
        for (size_t k = 0; k < ls.size(); ++k)
            for (uint32_t e = 0; e < 2; ++e) ends_.push_back({file_lines_[ls[k]][e], 2 * k + e});
        std::sort(ends_.begin(), ends_.end());
        for (size_t s = 0; s < ends_.size();) {
            size_t e = s;
            while (e < ends_.size() && ends_[e].first == ends_[s].first) ++e;
            if (e - s != 2)
                r_.fail("the face's lines do not form one closed loop (point " + num(ends_[s].first) + " ends " +
                        num(e - s) + " of them, not 2)");
            s = e;
        }
        slot_.assign(ends_.size(), 0);  // where each line end sits in ends_
        for (size_t s = 0; s < ends_.size(); ++s) slot_[ends_[s].second] = s;
        loop.clear();
        loop.push_back(file_lines_[ls[0]][0]);
        size_t end = 1;  // the line end we stand on: 2 * line position + which end
        for (size_t steps = 1;; ++steps) {
            const size_t other = ends_[slot_[end] ^ 1].second;  // the other line end at this point
            if (other / 2 == 0) {  // back at the first line's first point
                if (steps != ls.size()) r_.fail("the face's lines do not form one closed loop (they form more than one)");
                return;
            }
            loop.push_back(ends_[slot_[end]].first);
            end = other ^ 1;  // that line's far end
        }
    }

    void edge(uint32_t a, uint32_t b) { mentions_.push_back({std::min(a, b), std::max(a, b)}); }

    // Model::lines: every edge mentioned, once, in order of first mention.
    void dedup_edges() {
        std::vector<std::pair<uint64_t, size_t>> order(mentions_.size());
        for (size_t k = 0; k < mentions_.size(); ++k) order[k] = {uint64_t(mentions_[k][0]) << 32 | mentions_[k][1], k};
        std::sort(order.begin(), order.end());
        std::vector<bool> first(mentions_.size(), false);
        for (size_t k = 0; k < order.size(); ++k)
            if (k == 0 || order[k].first != order[k - 1].first) first[order[k].second] = true;
        for (size_t k = 0; k < mentions_.size(); ++k)
            if (first[k]) m_.lines.push_back(mentions_[k]);
    }

    ByteReader &in_;
    std::string path_;
    uint64_t size_;
    TextReader r_;
    Model m_;
    bool v2_ = false;
    uint64_t nfaces_ = 0;
    std::vector<std::array<uint32_t, 2>> file_lines_;  // the 3D lines as the file writes them
    std::vector<std::array<uint32_t, 2>> mentions_;    // every edge each time it is named
    std::vector<std::pair<uint32_t, size_t>> ends_;
    std::vector<size_t> slot_;
};

}  // namespace

Model read_cao(const std::string &path, uint64_t size) {
    ByteReader in(path);
    return CaoReader(in, path, size).run();
}

}  // namespace mc::input
