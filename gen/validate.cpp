// Validating scanners for OFF, OBJ, STL, PLY and XYZ (see validate.hpp).
//
// Each scanner accepts a subset of what the matching library reader (OpenMesh for meshes, CGAL for
// point sets) reads correctly, so a file that passes is read the same way by the library. Where a
// valid file trips a library limitation (comments in OFF, extra properties in a PLY mesh, blank
// "\r" lines in XYZ, ...) the scan sets Scan::rewrite and can write a clean copy for the library.
#include "validate.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string_view>
#include <vector>

namespace mc {
namespace {

using Where = InputError::Where;
using Tokens = std::vector<std::string_view>;

constexpr size_t kMaxLine = size_t(1) << 24;  // no sane model file has a longer text line
const std::string kLimit = std::to_string(kMaxElements);

// ------------------------------------------------------------------------- small helpers

[[noreturn]] void fail_none(const std::string &path, const std::string &msg) {
    throw InputError(path, Where::none, 0, msg);
}

[[noreturn]] void fail_byte(const std::string &path, uint64_t at, const std::string &msg) {
    throw InputError(path, Where::byte, static_cast<long long>(at), msg);
}

std::string num(uint64_t n) { return std::to_string(n); }

// A file token for an error message: quoted, control bytes escaped, cut short when long.
std::string quote(std::string_view s) {
    std::string r = "'";
    for (size_t i = 0; i < s.size() && i < 40; ++i) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        if (c >= 32 && c < 127 && c != '\\') {
            r += static_cast<char>(c);
        } else {
            char b[8];
            std::snprintf(b, sizeof b, "\\x%02x", c);
            r += b;
        }
    }
    return r + (s.size() > 40 ? "...'" : "'");
}

std::string lower(std::string_view s) {
    std::string r(s);
    for (char &c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

std::string plural(const std::string &element) {
    return element == "vertex" ? "vertices" : element + "s";
}

std::string join(const Tokens &t, size_t n) {
    std::string r;
    for (size_t i = 0; i < n && i < t.size(); ++i) {
        if (i) r += ' ';
        r += t[i];
    }
    return r;
}

// Number of different values in a face's vertex indices (pairwise: faces are short, and this
// runs once per face).
size_t distinct_count(const std::vector<long long> &v) {
    if (v.size() > 16) {
        std::vector<long long> c(v);
        std::sort(c.begin(), c.end());
        return static_cast<size_t>(std::unique(c.begin(), c.end()) - c.begin());
    }
    size_t n = 0;
    for (size_t i = 0; i < v.size(); ++i) n += std::find(v.begin(), v.begin() + i, v[i]) == v.begin() + i;
    return n;
}

bool distinct(const std::vector<long long> &v) { return distinct_count(v) == v.size(); }

enum class Num { ok, bad, range };

// iostreams (which the libraries use) accept a leading '+'; std::from_chars does not.
std::string_view skip_plus(std::string_view s) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
    return s;
}

// Whole-token, locale-independent number parsing.
Num parse_int(std::string_view s, long long &v) {
    s = skip_plus(s);
    const char *end = s.data() + s.size();
    auto [p, ec] = std::from_chars(s.data(), end, v);
    if (ec == std::errc::invalid_argument || p != end) return Num::bad;
    return ec == std::errc::result_out_of_range ? Num::range : Num::ok;
}

Num parse_double(std::string_view s, double &v) {
    s = skip_plus(s);
    const char *end = s.data() + s.size();
    auto [p, ec] = std::from_chars(s.data(), end, v);
    if (ec == std::errc::invalid_argument || p != end) return Num::bad;
    if (ec == std::errc::result_out_of_range) {
        // from_chars also reports underflow (1e-400), which is harmless: only overflow is an error.
        v = std::strtod(std::string(s).c_str(), nullptr);
        if (std::isinf(v)) return Num::range;
    }
    return Num::ok;
}

// Why a coordinate value is unusable, or nullptr. Later stages store floats, hence the float range.
const char *bad_coordinate(double v) {
    if (!std::isfinite(v)) return "coordinate is not finite";
    if (std::fabs(v) > FLT_MAX) return "coordinate is out of range (beyond float)";
    return nullptr;
}

std::string show(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

struct Box {
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    void add(const double p[3]) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    void store(Scan &s) const {
        s.lo = lo;
        s.hi = hi;
    }
};

// ------------------------------------------------------------------------- readers

// Buffered binary reader that knows its byte offset; also splits lines for the text formats.
class ByteReader {
public:
    explicit ByteReader(const std::string &path) : path_(path), in_(path, std::ios::binary) {
        if (!in_) fail_none(path, std::string("cannot open: ") + std::strerror(errno));
    }
    uint64_t offset() const { return offset_; }
    bool at_end() { return !fill(); }

    // Copies up to N bytes to DST; returns how many (fewer only at the end of the file).
    size_t read(char *dst, size_t n) {
        size_t done = 0;
        while (done < n && fill()) {
            size_t k = std::min(n - done, end_ - pos_);
            std::memcpy(dst + done, buf_.data() + pos_, k);
            pos_ += k;
            offset_ += k;
            done += k;
        }
        return done;
    }

    // Next line without its '\n' ('\r' is kept); false at the end of the file. Sets TOO_LONG
    // rather than reading more than kMaxLine bytes (a binary file given a text extension).
    bool line(std::string &out, bool &too_long) {
        out.clear();
        too_long = false;
        if (!fill()) return false;
        while (fill()) {
            const char *b = buf_.data() + pos_;
            const char *nl = static_cast<const char *>(std::memchr(b, '\n', end_ - pos_));
            size_t k = nl ? static_cast<size_t>(nl - b) : end_ - pos_;
            if (out.size() + k > kMaxLine) {
                too_long = true;
                return true;
            }
            out.append(b, k);
            pos_ += k + (nl ? 1 : 0);
            offset_ += k + (nl ? 1 : 0);
            if (nl) break;
        }
        return true;
    }

private:
    bool fill() {
        if (pos_ < end_) return true;
        in_.read(buf_.data(), static_cast<std::streamsize>(buf_.size()));
        pos_ = 0;
        end_ = static_cast<size_t>(in_.gcount());
        if (in_.bad()) fail_none(path_, std::string("cannot read: ") + std::strerror(errno));
        return end_ > 0;
    }

    std::string path_;
    std::ifstream in_;
    std::vector<char> buf_ = std::vector<char>(1 << 16);
    size_t pos_ = 0, end_ = 0;
    uint64_t offset_ = 0;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Line reader for the text formats: 1-based line numbers, whitespace-separated tokens and, if
// enabled, '#' comments. At the end of the file line() stays on the last line, which is where a
// truncated file is reported.
class TextReader {
public:
    TextReader(ByteReader &in, const std::string &path, bool comments, long long line = 0)
        : in_(in), path_(path), comments_(comments), line_(line) {}

    // Reads the next physical line; false at the end of the file.
    bool next() {
        bool too_long = false;
        if (!in_.line(raw_, too_long)) return false;
        ++line_;
        if (too_long) fail("line is longer than " + num(kMaxLine) + " bytes (not a text file?)");
        split();
        return true;
    }
    // Reads on to the next line that has tokens; false at the end of the file.
    bool next_content() {
        while (next())
            if (!tok_.empty()) return true;
        return false;
    }

    const Tokens &tok() const { return tok_; }
    const std::string &raw() const { return raw_; }
    long long line() const { return line_; }
    bool seen_comment() const { return seen_comment_; }

    [[noreturn]] void fail(const std::string &msg) const {
        throw InputError(path_, Where::line, line_, msg);
    }

    // Token checks that fail at the current line.
    double coordinate(std::string_view t) const {
        double v = 0;
        Num n = parse_double(t, v);
        if (n == Num::bad) fail("not a number: " + quote(t));
        if (n == Num::range) v = HUGE_VAL;
        if (const char *why = bad_coordinate(v)) fail(std::string(why) + ": " + quote(t));
        return v;
    }
    // Any other number (normal, colour, texture coordinate). OpenMesh reads these as float and
    // its stream stops at a value beyond float range, so they are held to it too.
    double number(std::string_view t) const {
        double v = 0;
        Num n = parse_double(t, v);
        if (n == Num::bad) fail("not a number: " + quote(t));
        if (n == Num::range || !std::isfinite(v)) fail("value is not finite: " + quote(t));
        if (std::fabs(v) > FLT_MAX) fail("value is out of range (beyond float): " + quote(t));
        return v;
    }

private:
    void split() {
        tok_.clear();
        std::string_view s(raw_);
        if (comments_) {
            size_t hash = s.find('#');
            if (hash != std::string_view::npos) {
                s = s.substr(0, hash);
                seen_comment_ = true;
            }
        }
        size_t i = 0;
        for (;;) {
            while (i < s.size() && is_space(s[i])) ++i;
            if (i == s.size()) break;
            size_t j = i;
            while (j < s.size() && !is_space(s[j])) ++j;
            tok_.push_back(s.substr(i, j - i));
            i = j;
        }
    }

    ByteReader &in_;
    std::string path_;
    bool comments_;
    long long line_;
    std::string raw_;
    Tokens tok_;
    bool seen_comment_ = false;
};

// ------------------------------------------------------------------------- OFF

// Reads OFF the way OpenMesh does: header keyword [ST][C][N]OFF alone on the first line, then the
// counts, one vertex per line (x y z [normal] [colour] [texcoord]) and one face per line
// (n i1 .. in [colour]). OpenMesh does not skip comments, so files with them are rewritten.
class OffScanner {
public:
    OffScanner(ByteReader &in, const std::string &path, std::ostream *clean)
        : path_(path), r_(in, path, true), clean_(clean) {}

    Scan run() {
        header();
        vertices();
        faces();
        if (r_.next_content())
            r_.fail("extra data after the last " + std::string(nf_ ? "face" : "vertex") +
                    " (the header says " + num(nv_) + " vertices, " + num(nf_) + " faces)");
        if (nv_ == 0) fail_none(path_, "model has no vertices");
        if (nf_ == 0) fail_none(path_, "mesh has no faces");
        s_.points = nv_;
        s_.faces_in_file = nf_;
        s_.faces = faces_ok_;
        s_.colors = color_;
        s_.rewrite = s_.rewrite || r_.seen_comment();
        box_.store(s_);
        return s_;
    }

private:
    void header() {
        if (!r_.next_content()) r_.fail("no OFF header (only comments or blank lines)");
        const Tokens &t = r_.tok();
        keyword(t[0]);
        // OpenMesh only recognises the keyword at the very start of the file, alone on its line.
        if (r_.line() != 1 || r_.raw().compare(0, t[0].size(), t[0]) != 0) s_.rewrite = true;
        if (t.size() > 1 && t[1] == "BINARY") r_.fail("binary OFF is not supported");
        emit(t, 1);
        if (t.size() > 1) {
            s_.rewrite = true;
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
        if (s != "OFF")
            r_.fail("expected an OFF header (OFF, COFF, NOFF, CNOFF, STOFF...), found " + quote(h));
        if (not_3d) r_.fail(quote(h) + " (not 3D) is not supported");
    }

    void counts(const Tokens &t, size_t i) {
        if (t.size() - i != 3)
            r_.fail("expected 3 counts (vertices faces edges), found " + num(t.size() - i) + " values");
        nv_ = count(t[i], "vertices");
        nf_ = count(t[i + 1], "faces");
        long long ne = 0;
        // OpenMesh reads the (unused) edge count into an unsigned int.
        if (parse_int(t[i + 2], ne) != Num::ok || ne < 0 || ne > 0xffffffffLL)
            r_.fail("bad edge count: " + quote(t[i + 2]));
        if (clean_) *clean_ << nv_ << ' ' << nf_ << ' ' << ne << '\n';
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
            if (!r_.next_content())
                r_.fail("file ends after " + num(i) + " of " + num(nv_) + " vertices");
            const Tokens &t = r_.tok();
            bool ok = color_ ? t.size() == base + 3 || t.size() == base + 4 : t.size() == base;
            if (!ok) {
                std::string want = color_ ? num(base + 3) + " or " + num(base + 4) : num(base);
                r_.fail("expected " + want + " numbers per vertex, found " + num(t.size()));
            }
            double p[3];
            for (int k = 0; k < 3; ++k) p[k] = r_.coordinate(t[k]);
            box_.add(p);
            size_t k = normal_ ? 6 : 3;
            for (size_t j = 3; j < k; ++j) r_.number(t[j]);
            size_t colors = t.size() - base;
            bool decimal = color_ && check_color(t, k, colors);
            for (size_t j = k + colors; j < t.size(); ++j) r_.number(t[j]);  // texture coordinates
            if (decimal && t[k].find('.') == std::string_view::npos) s_.rewrite = true;
            emit_vertex(t, k, colors, decimal);
        }
    }

    // Colours are integers 0..255 or, when any value is written with a '.', decimals 0..1.
    // Returns whether they are decimal.
    bool check_color(const Tokens &t, size_t from, size_t n) {
        bool decimal = false;
        for (size_t j = from; j < from + n; ++j) decimal = decimal || t[j].find('.') != std::string_view::npos;
        for (size_t j = from; j < from + n; ++j) {
            if (decimal) {
                double v = r_.number(t[j]);
                if (v < 0 || v > 1) r_.fail("colour value " + quote(t[j]) + " out of range (0..1)");
            } else {
                long long v = 0;
                if (parse_int(t[j], v) != Num::ok)
                    r_.fail("colour value is not an integer 0..255: " + quote(t[j]));
                if (v < 0 || v > 255) r_.fail("colour value " + quote(t[j]) + " out of range (0..255)");
            }
        }
        return decimal;
    }

    // OpenMesh takes colours as decimal only when the first value has a '.' ("0 0 0.9" would be
    // read as integers), so the clean copy writes decimal colours with a '.' in every value.
    void emit_vertex(const Tokens &t, size_t from, size_t n, bool decimal) {
        if (!clean_) return;
        for (size_t j = 0; j < t.size(); ++j) {
            if (j) *clean_ << ' ';
            if (decimal && j >= from && j < from + n) {
                char b[32];
                std::snprintf(b, sizeof b, "%.6f", r_.number(t[j]));
                *clean_ << b;
            } else {
                *clean_ << t[j];
            }
        }
        *clean_ << '\n';
    }

    void faces() {
        std::vector<long long> idx;
        for (uint64_t i = 0; i < nf_; ++i) {
            if (!r_.next_content()) r_.fail("file ends after " + num(i) + " of " + num(nf_) + " faces");
            const Tokens &t = r_.tok();
            long long n = 0;
            if (parse_int(t[0], n) != Num::ok)
                r_.fail("expected a face (vertex count, then indices), found " + quote(t[0]));
            if (n < 3) r_.fail("face has " + std::to_string(n) + " vertices (at least 3 needed)");
            const uint64_t have = t.size() - 1, want = static_cast<uint64_t>(n);
            if (have < want)
                r_.fail("face has " + num(have) + " vertex indices but its count says " + num(want));
            const uint64_t extra = have - want;
            if (extra != 0 && extra != 3 && extra != 4)
                r_.fail("face count says " + num(want) + " but " + num(have) +
                        " values follow (expected the indices, optionally then an RGB or RGBA colour)");
            idx.clear();
            for (uint64_t j = 1; j <= want; ++j) idx.push_back(index(t[j]));
            for (size_t j = want + 1; j < t.size(); ++j) r_.number(t[j]);
            if (extra && !color_) s_.rewrite = true;  // OpenMesh reads face colours only after COFF
            if (distinct(idx)) ++faces_ok_;  // OpenMesh drops faces that repeat a vertex
            emit(t, color_ ? t.size() : want + 1);
        }
    }

    long long index(std::string_view t) {
        long long v = 0;
        Num n = parse_int(t, v);
        if (n == Num::bad) r_.fail("vertex index is not an integer: " + quote(t));
        if (n == Num::range || v < 0 || static_cast<uint64_t>(v) >= nv_)
            r_.fail("vertex index " + std::string(t) + " out of range " +
                    (nv_ ? "(0.." + num(nv_ - 1) + ")" : "(the file has no vertices)"));
        return v;
    }

    void emit(const Tokens &t, size_t n) {
        if (clean_) *clean_ << join(t, n) << '\n';
    }

    std::string path_;
    TextReader r_;
    std::ostream *clean_;
    Scan s_;
    Box box_;
    bool st_ = false, color_ = false, normal_ = false;
    uint64_t nv_ = 0, nf_ = 0, faces_ok_ = 0;
};

// ------------------------------------------------------------------------- OBJ

// Reads 'v' and 'f' lines; everything else (vt, vn, g, usemtl, ...) is ignored, as OpenMesh does.
// Like OpenMesh, positive indices may refer to any vertex of the file, so a first pass counts them.
class ObjScanner {
public:
    explicit ObjScanner(const std::string &path) : path_(path) {}

    Scan run() {
        total_ = count_vertices();
        ByteReader in(path_);
        TextReader r(in, path_, true);
        while (r.next_content()) {
            if (r.tok()[0] == "v") vertex(r);
            else if (r.tok()[0] == "f") face(r);
            else if (r.tok()[0] == "vt") texture(r);
            else if (r.tok()[0] == "mtllib") material(r);
        }
        if (nv_ == 0) fail_none(path_, "model has no vertices");
        if (nf_ == 0) fail_none(path_, "mesh has no faces");
        s_.points = nv_;
        s_.faces_in_file = nf_;
        s_.faces = faces_ok_;
        s_.colors = colors_;
        box_.store(s_);
        return s_;
    }

private:
    uint64_t count_vertices() {
        ByteReader in(path_);
        TextReader r(in, path_, true);
        uint64_t n = 0;
        while (r.next_content()) n += r.tok()[0] == "v";
        return n;
    }

    void vertex(TextReader &r) {
        const Tokens &t = r.tok();
        const size_t n = t.size() - 1;
        if (n != 3 && n != 4 && n != 6)
            r.fail("expected 3, 4 or 6 numbers after 'v' (x y z [w] or x y z r g b), found " + num(n));
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = r.coordinate(t[k + 1]);
        box_.add(p);
        for (size_t k = 4; k < t.size(); ++k) {
            double v = r.number(t[k]);
            if (n == 6 && (v < 0 || v > 1)) r.fail("colour value " + quote(t[k]) + " out of range (0..1)");
        }
        const bool color = n == 6;
        // OpenMesh pairs the i-th colour with the i-th vertex, so colours must be all or nothing.
        if (nv_ > 0 && color != colors_)
            r.fail(color ? "vertex has a colour but earlier vertices have none"
                         : "vertex has no colour but earlier vertices have one");
        colors_ = color;
        if (++nv_ > kMaxElements) r.fail("more than " + kLimit + " vertices");
    }

    // OpenMesh gives up on the whole file when a 'vt' line does not start with two numbers.
    void texture(TextReader &r) {
        const Tokens &t = r.tok();
        if (t.size() != 3 && t.size() != 4)
            r.fail("expected 2 or 3 numbers after 'vt' (u v [w]), found " + num(t.size() - 1));
        for (size_t k = 1; k < t.size(); ++k) r.number(t[k]);
    }

    // OpenMesh reads the material file named here (relative to the OBJ's directory) line by line;
    // a device such as /dev/zero would keep it reading forever.
    void material(TextReader &r) {
        const std::string &raw = r.raw();
        const size_t from = raw.find("mtllib") + 6;
        const size_t first = raw.find_first_not_of(" \t\r", from), last = raw.find_last_not_of(" \t\r");
        if (first == std::string::npos) return;
        const std::string name = raw.substr(first, last - first + 1);
        const std::string file = path_.substr(0, path_.find_last_of('/') + 1) + name;
        struct stat st;
        if (stat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
            r.fail("material library " + quote(name) + " is not a regular file");
    }

    void face(TextReader &r) {
        const Tokens &t = r.tok();
        if (t.size() < 4) r.fail("face has " + num(t.size() - 1) + " vertices (at least 3 needed)");
        idx_.clear();
        for (size_t k = 1; k < t.size(); ++k) idx_.push_back(reference(r, t[k]));
        if (distinct_count(idx_) >= 3) ++faces_ok_;  // OpenMesh removes repeated vertices first
        if (++nf_ > kMaxElements) r.fail("more than " + kLimit + " faces");
    }

    // One face corner: v, v/t, v/t/n or v//n. Returns the 0-based vertex index.
    long long reference(TextReader &r, std::string_view tok) {
        std::string_view part[3];
        size_t parts = 0, start = 0;
        for (;;) {
            size_t slash = tok.find('/', start);
            if (parts == 3) r.fail("bad face vertex " + quote(tok));
            part[parts++] = tok.substr(start, slash == std::string_view::npos ? slash : slash - start);
            if (slash == std::string_view::npos) break;
            start = slash + 1;
        }
        long long v = 0, unused = 0;
        Num n = parse_int(part[0], v);
        if (n == Num::bad) r.fail("bad face vertex " + quote(tok));
        for (size_t k = 1; k < parts; ++k)
            if (!part[k].empty() && parse_int(part[k], unused) == Num::bad)
                r.fail("bad face vertex " + quote(tok));
        const std::string shown(part[0]);
        if (n == Num::ok && v == 0) r.fail("vertex index 0 is invalid (OBJ indices start at 1)");
        if (n == Num::ok && v > 0 && static_cast<uint64_t>(v) <= total_) return v - 1;
        if (n == Num::ok && v < 0 && static_cast<uint64_t>(-v) <= nv_)
            return static_cast<long long>(nv_) + v;  // relative to the vertices read so far
        bool negative = part[0][0] == '-';
        if (negative && nv_ == 0) r.fail("vertex index " + shown + " but no vertex precedes this face");
        if (negative) r.fail("vertex index " + shown + " out of range (-" + num(nv_) + "..-1)");
        if (total_ == 0) r.fail("vertex index " + shown + " but the file has no vertices");
        r.fail("vertex index " + shown + " out of range (1.." + num(total_) + ")");
    }

    std::string path_;
    Scan s_;
    Box box_;
    uint64_t total_ = 0, nv_ = 0, nf_ = 0, faces_ok_ = 0;
    bool colors_ = false;
    std::vector<long long> idx_;
};

// ------------------------------------------------------------------------- STL

uint32_t le32(const unsigned char *b) {
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

// Whether OpenMesh's STL reader certainly keeps a triangle with corners C[0..8]. It merges corners
// that differ by at most FLT_MIN in every coordinate (through a std::map whose comparison is then
// not transitive), so a triangle is certainly kept when each pair of its corners differs by more
// than twice that somewhere, and certainly dropped when two corners are equal. Between the two
// (denormal coordinates) the outcome depends on the map, see the check in load.cpp.
bool stl_triangle_kept(const float *c) {
    auto apart = [c](int a, int b) {
        for (int k = 0; k < 3; ++k)
            if (std::fabs(double(c[3 * a + k]) - double(c[3 * b + k])) > 2.0 * FLT_MIN) return true;
        return false;
    };
    return apart(0, 1) && apart(0, 2) && apart(1, 2);
}

float le_float(const unsigned char *b) {
    uint32_t u = le32(b);
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

// Binary when the size matches the triangle count exactly (what OpenMesh checks); otherwise text
// if it starts with "solid" and looks like text (binary headers often start with "solid" too).
bool stl_is_text(const std::string &path, uint64_t size) {
    ByteReader in(path);
    unsigned char head[1024];
    size_t n = in.read(reinterpret_cast<char *>(head), sizeof head);
    if (n >= 84 && size == 84 + 50 * uint64_t(le32(head + 80))) return false;
    size_t i = 0;
    while (i < n && (is_space(char(head[i])) || head[i] == '\n')) ++i;
    if (n - i < 5 || lower(std::string_view(reinterpret_cast<char *>(head) + i, 5)) != "solid") return false;
    for (size_t k = 0; k < n; ++k)
        if ((head[k] < 32 || head[k] > 126) && !is_space(char(head[k])) && head[k] != '\n') return false;
    return true;
}

class StlBinaryScanner {
public:
    StlBinaryScanner(ByteReader &in, const std::string &path, uint64_t size)
        : in_(in), path_(path), size_(size) {}

    Scan run() {
        unsigned char head[84];
        if (in_.read(reinterpret_cast<char *>(head), 84) < 84)
            fail_byte(path_, size_, "file ends inside the 84-byte header of a binary STL");
        const uint64_t n = le32(head + 80);
        if (n > kMaxElements)
            fail_byte(path_, 80, "triangle count " + num(n) + " exceeds the limit of " + kLimit);
        const uint64_t need = 84 + 50 * n;
        if (size_ < need)
            fail_byte(path_, size_, "file ends after " + num((size_ - 84) / 50) + " of " + num(n) +
                                        " triangles (needs " + num(need) + " bytes, has " + num(size_) + ")");
        if (size_ > need)
            fail_byte(path_, need, num(size_ - need) + " bytes of extra data after " + num(n) +
                                       " triangles (the count in the header does not match the file size)");
        if (n == 0) fail_none(path_, "mesh has no faces");
        for (uint64_t i = 0; i < n; ++i) triangle(i);
        Scan s;
        s.binary = true;
        s.points = 3 * n;  // before OpenMesh merges equal corners
        s.faces_in_file = n;
        s.faces = faces_ok_;
        box_.store(s);
        return s;
    }

private:
    void triangle(uint64_t i) {
        unsigned char t[50];
        const uint64_t at = in_.offset();
        in_.read(reinterpret_cast<char *>(t), 50);  // the size check above guarantees 50 bytes
        float c[9];
        for (int k = 0; k < 9; ++k) {
            c[k] = le_float(t + 12 + 4 * k);  // the first 12 bytes are the (unused) normal
            if (const char *why = bad_coordinate(c[k]))
                fail_byte(path_, at + 12 + 4 * k, std::string(why) + " (" + show(c[k]) + ") in triangle " + num(i));
        }
        for (int v = 0; v < 3; ++v) {
            double p[3] = {c[3 * v], c[3 * v + 1], c[3 * v + 2]};
            box_.add(p);
        }
        faces_ok_ += stl_triangle_kept(c);
    }

    ByteReader &in_;
    std::string path_;
    uint64_t size_;
    Box box_;
    uint64_t faces_ok_ = 0;
};

// Text STL: solid / facet normal / outer loop / 3 x vertex / endloop / endfacet / endsolid.
// OpenMesh finds loops by searching each line for "outer" or "OUTER" and then takes the next three
// lines as vertices, so odd spellings, blank lines inside a loop or a solid named "outer..." make
// the scan ask for a rewritten copy.
class StlTextScanner {
public:
    StlTextScanner(ByteReader &in, const std::string &path, std::ostream *clean)
        : path_(path), r_(in, path, false), clean_(clean) {}

    Scan run() {
        r_.next_content();  // stl_is_text() saw "solid"
        solid();
        for (;;) {
            if (!r_.next_content())
                r_.fail("file ends before 'endsolid' (after " + num(facets_) + " facets)");
            std::string kw = lower(r_.tok()[0]);
            if (kw == "facet") {
                facet();
            } else if (kw == "endsolid") {
                misleading_name();
                emit("endsolid");
                if (!r_.next_content()) break;
                if (lower(r_.tok()[0]) != "solid")
                    r_.fail("extra data after 'endsolid': " + quote(r_.tok()[0]));
                solid();  // several solids in one file
            } else {
                r_.fail("expected 'facet normal' or 'endsolid', found " + quote(r_.tok()[0]));
            }
        }
        if (facets_ == 0) fail_none(path_, "mesh has no faces");
        s_.points = 3 * facets_;
        s_.faces_in_file = facets_;
        s_.faces = faces_ok_;
        box_.store(s_);
        return s_;
    }

private:
    void solid() {
        if (lower(r_.tok()[0]) != "solid") r_.fail("expected 'solid', found " + quote(r_.tok()[0]));
        misleading_name();
        emit("solid");
    }

    void misleading_name() {
        const std::string &l = r_.raw();
        if (l.find("outer") != std::string::npos || l.find("OUTER") != std::string::npos) s_.rewrite = true;
    }

    void facet() {
        const Tokens &t = r_.tok();
        if (t.size() != 5 || lower(t[1]) != "normal")
            r_.fail("expected 'facet normal nx ny nz', found " + quote(join(t, t.size())));
        for (int k = 2; k < 5; ++k)
            if (double v; parse_double(t[k], v) == Num::bad) r_.fail("not a number: " + quote(t[k]));
        misleading_name();
        emit("facet normal " + join(Tokens(t.begin() + 2, t.end()), 3));
        if (++facets_ > kMaxElements) r_.fail("more than " + kLimit + " facets");
        expect("outer loop");
        const std::string &raw = r_.raw();
        if (raw.find("outer") == std::string::npos && raw.find("OUTER") == std::string::npos)
            s_.rewrite = true;
        emit("outer loop");
        float c[9];
        for (int v = 0; v < 3; ++v) corner(v, c + 3 * v);
        expect("endloop");
        emit("endloop");
        expect("endfacet");
        emit("endfacet");
        faces_ok_ += stl_triangle_kept(c);
    }

    // Reads one "vertex x y z" line into C, as float like OpenMesh.
    void corner(int v, float *c) {
        const long long before = r_.line();
        next_in_facet();
        if (r_.line() != before + 1) s_.rewrite = true;  // OpenMesh would read the blank line
        const Tokens &t = r_.tok();
        std::string kw = lower(t[0]);
        if (kw == "endloop") r_.fail("facet has " + std::to_string(v) + " vertices, expected 3");
        if (kw != "vertex" || t.size() != 4)
            r_.fail("expected 'vertex x y z', found " + quote(join(t, t.size())));
        misleading_name();
        double p[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = r_.coordinate(t[k + 1]);
            c[k] = static_cast<float>(p[k]);
        }
        box_.add(p);
        emit("vertex " + join(Tokens(t.begin() + 1, t.end()), 3));
    }

    void expect(const std::string &words) {
        next_in_facet();
        std::string got = lower(join(r_.tok(), r_.tok().size()));
        if (words == "endloop" && lower(r_.tok()[0]) == "vertex") r_.fail("facet has more than 3 vertices");
        if (got != words) r_.fail("expected '" + words + "', found " + quote(join(r_.tok(), r_.tok().size())));
        if (words != "outer loop") misleading_name();
    }

    void next_in_facet() {
        if (!r_.next_content()) r_.fail("file ends inside facet " + num(facets_));
    }

    void emit(const std::string &line) {
        if (clean_) *clean_ << line << '\n';
    }

    std::string path_;
    TextReader r_;
    std::ostream *clean_;
    Scan s_;
    Box box_;
    uint64_t facets_ = 0, faces_ok_ = 0;
};

// ------------------------------------------------------------------------- PLY

enum class PType { i8, u8, i16, u16, i32, u32, f32, f64 };

bool ply_type(std::string_view name, PType &t) {
    static const struct {
        const char *name;
        PType type;
    } kTypes[] = {{"char", PType::i8},   {"int8", PType::i8},    {"uchar", PType::u8},   {"uint8", PType::u8},
                  {"short", PType::i16}, {"int16", PType::i16},  {"ushort", PType::u16}, {"uint16", PType::u16},
                  {"int", PType::i32},   {"int32", PType::i32},  {"uint", PType::u32},   {"uint32", PType::u32},
                  {"float", PType::f32}, {"float32", PType::f32}, {"double", PType::f64}, {"float64", PType::f64}};
    for (const auto &k : kTypes)
        if (name == k.name) {
            t = k.type;
            return true;
        }
    return false;
}

size_t type_size(PType t) {
    switch (t) {
    case PType::i8: case PType::u8: return 1;
    case PType::i16: case PType::u16: return 2;
    case PType::i32: case PType::u32: case PType::f32: return 4;
    case PType::f64: return 8;
    }
    return 1;
}

bool is_float(PType t) { return t == PType::f32 || t == PType::f64; }

const char *type_name(PType t) {
    static const char *kNames[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
    return kNames[static_cast<int>(t)];
}

// What a property means to the scan.
enum class Role { other, x, y, z, normal, color, index };

struct PlyProp {
    std::string name, type_name, count_name;
    PType type = PType::u8, count_type = PType::u8;
    bool list = false;
    Role role = Role::other;
    long long line = 0;
};

struct PlyElem {
    std::string name;
    uint64_t count = 0;
    std::vector<PlyProp> props;
    long long line = 0;
};

std::string ends_after(const PlyElem &e, uint64_t i) {
    return "file ends after " + num(i) + " of " + num(e.count) + " " + plural(e.name);
}

struct PlyHeader {
    enum { ascii, little, big } format = ascii;
    std::vector<PlyElem> elems;
    long long lines = 0;        // header lines; the ascii body starts on the next one
    long long end_line = 0;     // line of end_header
    bool canonical = true;      // every line is its tokens joined by single spaces, '\n'-terminated
    bool comment_last = false;  // a comment right before end_header
    bool obj_info = false;
};

Role role_of(const std::string &element, const std::string &name) {
    if (element == "vertex") {
        if (name == "x") return Role::x;
        if (name == "y") return Role::y;
        if (name == "z") return Role::z;
        if (name == "nx" || name == "ny" || name == "nz") return Role::normal;
        if (name == "red" || name == "green" || name == "blue" || name == "alpha" || name == "diffuse_red" ||
            name == "diffuse_green" || name == "diffuse_blue")
            return Role::color;
    }
    if (element == "face" && (name == "vertex_indices" || name == "vertex_index")) return Role::index;
    return Role::other;
}

class PlyScanner {
public:
    PlyScanner(ByteReader &in, const std::string &path, uint64_t size, std::ostream *clean)
        : in_(in), path_(path), size_(size), clean_(clean) {}

    Scan run() {
        TextReader r(in_, path_, false);
        read_header(r);
        check_header(r);
        if (clean_) write_clean_header();
        if (h_.format == PlyHeader::ascii) {
            TextSource src(r);
            body(src);
        } else {
            BinarySource src(in_, path_, size_, h_.format == PlyHeader::big);
            body(src);
        }
        const PlyElem *v = find("vertex");
        if (v->count == 0) fail_none(path_, s_.is_mesh ? "model has no vertices" : "point set has no points");
        s_.points = v->count;
        s_.faces = faces_ok_;
        box_.store(s_);
        return s_;
    }

private:
    // ---- header

    void read_header(TextReader &r) {
        if (!r.next() || r.tok().size() != 1 || r.tok()[0] != "ply") r.fail("expected 'ply' on the first line");
        note_canonical(r);
        if (!r.next() || r.tok().size() != 3 || r.tok()[0] != "format")
            r.fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
        const std::string_view f = r.tok()[1];
        if (f == "ascii") h_.format = PlyHeader::ascii;
        else if (f == "binary_little_endian") h_.format = PlyHeader::little;
        else if (f == "binary_big_endian") h_.format = PlyHeader::big;
        else r.fail("unknown PLY format " + quote(f));
        if (r.tok()[2] != "1.0") r.fail("unsupported PLY version " + quote(r.tok()[2]));
        note_canonical(r);
        for (;;) {
            if (!r.next()) r.fail("file ends inside the header (no 'end_header')");
            note_canonical(r);
            const Tokens &t = r.tok();
            if (t.empty()) r.fail("empty line in the header");
            const bool comment = t[0] == "comment" || t[0] == "obj_info";
            if (t[0] == "end_header" && t.size() == 1) break;
            h_.comment_last = comment;
            h_.obj_info = h_.obj_info || t[0] == "obj_info";
            if (t[0] == "element") element(r);
            else if (t[0] == "property") property(r);
            else if (!comment) r.fail("unknown header keyword " + quote(t[0]));
        }
        h_.lines = h_.end_line = r.line();
        // An element without properties takes no room, so its count is not checked by the data;
        // refusing it keeps a tiny file from making the scan loop over 50 million empty items.
        for (const PlyElem &e : h_.elems)
            if (e.props.empty() && e.count > 0) fail_line(e.line, "element '" + e.name + "' has no properties");
    }

    void note_canonical(const TextReader &r) {
        if (r.raw() != join(r.tok(), r.tok().size())) h_.canonical = false;
    }

    // Element and property names end up in messages, so they must be printable words.
    static void check_name(const TextReader &r, std::string_view name) {
        for (char c : name)
            if (c < 33 || c > 126) r.fail("bad name " + quote(name) + " in the header");
    }

    void element(TextReader &r) {
        const Tokens &t = r.tok();
        if (t.size() != 3) r.fail("expected 'element NAME COUNT'");
        check_name(r, t[1]);
        PlyElem e;
        e.name = std::string(t[1]);
        e.line = r.line();
        long long n = 0;
        Num ok = parse_int(t[2], n);
        if (ok == Num::bad || (ok == Num::ok && n < 0)) r.fail("bad element count " + quote(t[2]));
        if (ok == Num::range || static_cast<uint64_t>(n) > kMaxElements)
            r.fail("element '" + e.name + "' count " + std::string(t[2]) + " exceeds the limit of " + kLimit);
        e.count = static_cast<uint64_t>(n);
        if (find(e.name)) r.fail("second element named '" + e.name + "'");
        h_.elems.push_back(e);
    }

    void property(TextReader &r) {
        const Tokens &t = r.tok();
        if (h_.elems.empty()) r.fail("property before any element");
        PlyProp p;
        p.line = r.line();
        if (t.size() == 5 && t[1] == "list") {
            p.list = true;
            p.count_name = std::string(t[2]);
            if (!ply_type(t[2], p.count_type) || is_float(p.count_type))
                r.fail("bad list count type " + quote(t[2]));
            p.type_name = std::string(t[3]);
            p.name = std::string(t[4]);
        } else if (t.size() == 3) {
            p.type_name = std::string(t[1]);
            p.name = std::string(t[2]);
        } else {
            r.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
        }
        if (!ply_type(p.type_name, p.type)) r.fail("unknown property type " + quote(p.type_name));
        check_name(r, p.name);
        PlyElem &e = h_.elems.back();
        for (const PlyProp &q : e.props)
            if (q.name == p.name) r.fail("second property '" + p.name + "' in element '" + e.name + "'");
        p.role = role_of(e.name, p.name);
        e.props.push_back(p);
    }

    const PlyElem *find(const std::string &name) const {
        for (const PlyElem &e : h_.elems)
            if (e.name == name) return &e;
        return nullptr;
    }
    PlyElem *find_mutable(const std::string &name) {
        return const_cast<PlyElem *>(find(name));
    }

    const PlyProp *prop(const PlyElem &e, const std::string &name) const {
        for (const PlyProp &p : e.props)
            if (p.name == name) return &p;
        return nullptr;
    }

    [[noreturn]] void fail_line(long long line, const std::string &msg) const {
        throw InputError(path_, Where::line, line, msg);
    }

    // Restrictions of the readers: CGAL asserts on coordinate and colour types it was not asked
    // for, OpenMesh converts colours only from uchar and float.
    void check_header(const TextReader &r) {
        const PlyElem *v = find("vertex");
        if (!v) r.fail("no 'element vertex' in the header");
        for (const char *axis : {"x", "y", "z"})
            if (!prop(*v, axis)) fail_line(v->line, std::string("vertex element has no '") + axis + "' property");
        for (const PlyProp &p : v->props) check_vertex_prop(p);
        check_colors(*v);
        PlyElem *f = find_mutable("face");
        s_.is_mesh = f && f->count > 0;
        s_.binary = h_.format != PlyHeader::ascii;
        s_.faces_in_file = f ? f->count : 0;
        if (s_.is_mesh) check_faces(*f);
        s_.rewrite = s_.is_mesh && !plain_for_openmesh();
    }

    void check_vertex_prop(const PlyProp &p) {
        bool coordinate = p.role == Role::x || p.role == Role::y || p.role == Role::z;
        if ((coordinate || p.role == Role::normal || p.role == Role::color) && p.list)
            fail_line(p.line, "property '" + p.name + "' must not be a list");
        if ((coordinate || p.role == Role::normal) && !is_float(p.type))
            fail_line(p.line, "property '" + p.name + "' has type " + p.type_name + " (must be float or double)");
        if (p.role == Role::color && p.type != PType::u8 && p.type != PType::f32)
            fail_line(p.line, "colour '" + p.name + "' has type " + p.type_name + " (must be uchar or float)");
    }

    void check_colors(const PlyElem &v) {
        const PlyProp *red = prop(v, "red"), *green = prop(v, "green"), *blue = prop(v, "blue");
        s_.normals = prop(v, "nx") && prop(v, "ny") && prop(v, "nz");
        if (!red || !green || !blue) return;
        for (const PlyProp *c : {green, blue})
            if (c->type != red->type) fail_line(c->line, "colour properties red, green and blue have different types");
        s_.colors = true;
        s_.colors_float = red->type == PType::f32;
    }

    // Picks the face's index list: the one property the scan treats as indices.
    void check_faces(PlyElem &f) {
        const PlyElem *v = find("vertex");
        if (v > &f) fail_line(f.line, "the 'face' element must come after 'vertex'");
        PlyProp *idx = nullptr;
        for (PlyProp &p : f.props) {
            if (p.role != Role::index) continue;
            if (idx || !p.list) p.role = Role::other;  // only the first index list counts
            else idx = &p;
        }
        if (!idx) fail_line(f.line, "face element has no 'vertex_indices' list");
        if (is_float(idx->type)) fail_line(idx->line, "vertex indices must have an integer type, not " + idx->type_name);
    }

    // Whether OpenMesh reads the file correctly as it is. Its PLY reader reads the elements in
    // order, reads the unknown properties of vertices and faces as single values (lists lose its
    // place), reads u, v, s, t and alpha as float and only a few list count types, and seeks to the
    // binary data assuming "\nend_header\n" right after the last property line. Anything else is
    // read from a clean copy with just the coordinates, colours and faces (write_clean_header()).
    bool plain_for_openmesh() const {
        if (h_.elems.size() < 2 || h_.elems[0].name != "vertex" || h_.elems[1].name != "face") return false;
        if (h_.obj_info || (s_.binary && (!h_.canonical || h_.comment_last))) return false;
        for (const PlyProp &p : h_.elems[0].props) {
            static const char *kSpecial[] = {"u", "v", "s", "t", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue"};
            if (p.list || std::any_of(std::begin(kSpecial), std::end(kSpecial), [&p](const char *n) { return p.name == n; }))
                return false;
        }
        const std::vector<PlyProp> &fp = h_.elems[1].props;
        if (fp.size() != 1 || fp[0].role != Role::index) return false;
        const std::string &c = fp[0].count_name;
        return c == "uchar" || c == "uint8" || c == "uint16" || c == "int";
    }

    // Is P one of the values the clean copy keeps?
    bool kept(const PlyElem &e, const PlyProp &p) const {
        if (e.name == "face") return p.role == Role::index;
        if (e.name != "vertex") return false;
        return p.role == Role::x || p.role == Role::y || p.role == Role::z ||
               (s_.colors && (p.name == "red" || p.name == "green" || p.name == "blue"));
    }

    // Header of the clean copy: the kept vertex properties with their types, and faces as
    // "list int int", little endian when binary.
    void write_clean_header() {
        *clean_ << "ply\nformat " << (s_.binary ? "binary_little_endian" : "ascii") << " 1.0\n";
        for (const PlyElem &e : h_.elems) {
            if (e.name != "vertex" && e.name != "face") continue;
            *clean_ << "element " << e.name << ' ' << e.count << '\n';
            for (const PlyProp &p : e.props) {
                if (!kept(e, p)) continue;
                if (p.list) *clean_ << "property list int int " << p.name << '\n';
                else *clean_ << "property " << p.type_name << ' ' << p.name << '\n';
            }
        }
        *clean_ << "end_header\n";
    }

    // ---- body

    // Values of an ascii body: one element per line, whitespace-separated.
    class TextSource {
    public:
        explicit TextSource(TextReader &r) : r_(r) {}
        static constexpr bool strict_floats = true;  // CGAL's stream reads fail on nan / inf
        void begin_item(const PlyElem &e, uint64_t i) {
            k_ = 0;
            if (!r_.next_content()) r_.fail(ends_after(e, i));
        }
        // False when the line has no more values.
        bool value(PType t, double &v) {
            if (k_ >= r_.tok().size()) return false;
            tok_ = r_.tok()[k_++];
            if (is_float(t)) {
                Num n = parse_double(tok_, v);
                if (n == Num::bad) fail("not a number: " + quote(tok_));
                if (n == Num::range) v = HUGE_VAL;
                return true;
            }
            long long i = 0;
            if (parse_int(tok_, i) != Num::ok || !fits(t, i))
                fail(std::string("not a valid ") + type_name(t) + " value: " + quote(tok_));
            v = static_cast<double>(i);
            return true;
        }
        std::string shown() const { return std::string(tok_); }  // an integer token
        std::string quoted() const { return ": " + quote(tok_); }
        // Clean copy: the value as written, one element per line.
        void copy_value(std::string &out, PType, double) const {
            out += tok_;
            out += ' ';
        }
        static void end_copy(std::string &out) { out.back() = '\n'; }
        std::string item_size() const { return num(r_.tok().size()); }
        void end_item(const PlyElem &e) {
            if (k_ < r_.tok().size())
                fail("too many values for a " + e.name + ": expected " + num(k_) + ", found " + item_size());
        }
        [[noreturn]] void fail(const std::string &msg) const { r_.fail(msg); }
        void finish() {
            if (r_.next_content()) r_.fail("extra data after the last element: " + quote(r_.tok()[0]));
        }

    private:
        static bool fits(PType t, long long i) {
            switch (t) {
            case PType::i8: return i >= -128 && i <= 127;
            case PType::u8: return i >= 0 && i <= 255;
            case PType::i16: return i >= -32768 && i <= 32767;
            case PType::u16: return i >= 0 && i <= 65535;
            case PType::i32: return i >= INT32_MIN && i <= INT32_MAX;
            default: return i >= 0 && i <= UINT32_MAX;
            }
        }
        TextReader &r_;
        size_t k_ = 0;
        std::string_view tok_;
    };

    // Values of a binary body, little or big endian.
    class BinarySource {
    public:
        BinarySource(ByteReader &in, const std::string &path, uint64_t size, bool big)
            : in_(in), path_(path), size_(size), big_(big) {}
        static constexpr bool strict_floats = false;
        // A missing item shows up as a short read in value(), reported at the end of the file.
        void begin_item(const PlyElem &e, uint64_t i) {
            e_ = &e;
            i_ = i;
        }
        bool value(PType t, double &v) {
            at_ = in_.offset();
            unsigned char b[8];
            const size_t n = type_size(t);
            if (in_.read(reinterpret_cast<char *>(b), n) < n) fail_byte(path_, size_, ends_after(*e_, i_));
            if (big_) std::reverse(b, b + n);
            v = decode(t, b);
            shown_ = is_float(t) ? show(v) : std::to_string(static_cast<long long>(v));
            return true;
        }
        std::string shown() const { return shown_; }
        std::string quoted() const { return " (" + shown_ + ")"; }
        // Clean copy: the value re-encoded as little-endian TYPE (exact: V came from the file).
        static void copy_value(std::string &out, PType type, double v) {
            uint64_t u = 0;
            if (type == PType::f32) {
                float f = static_cast<float>(v);
                uint32_t w;
                std::memcpy(&w, &f, sizeof w);
                u = w;
            } else if (type == PType::f64) {
                std::memcpy(&u, &v, sizeof u);
            } else {
                u = static_cast<uint64_t>(static_cast<int64_t>(v));  // two's complement, low bytes
            }
            for (size_t k = 0; k < type_size(type); ++k) out += static_cast<char>(u >> (8 * k));
        }
        static void end_copy(std::string &) {}
        std::string item_size() const { return "?"; }
        void end_item(const PlyElem &) {}
        [[noreturn]] void fail(const std::string &msg) const { fail_byte(path_, at_, msg); }
        void finish() {
            if (!in_.at_end())
                fail_byte(path_, in_.offset(), num(size_ - in_.offset()) + " bytes of extra data after the last element");
        }

    private:
        static double decode(PType t, const unsigned char *b) {
            // Bytes are in little-endian order here; assemble explicitly to stay host-independent.
            uint64_t u = 0;
            for (size_t k = type_size(t); k-- > 0;) u = u << 8 | b[k];
            switch (t) {
            case PType::i8: return static_cast<int8_t>(u);
            case PType::u8: return static_cast<uint8_t>(u);
            case PType::i16: return static_cast<int16_t>(u);
            case PType::u16: return static_cast<uint16_t>(u);
            case PType::i32: return static_cast<int32_t>(u);
            case PType::u32: return static_cast<uint32_t>(u);
            case PType::f32: {
                uint32_t w = static_cast<uint32_t>(u);
                float f;
                std::memcpy(&f, &w, sizeof f);
                return f;
            }
            case PType::f64: {
                double d;
                std::memcpy(&d, &u, sizeof d);
                return d;
            }
            }
            return 0;
        }
        ByteReader &in_;
        std::string path_;
        uint64_t size_, at_ = 0;
        bool big_;
        std::string shown_;
        const PlyElem *e_ = nullptr;
        uint64_t i_ = 0;
    };

    template <class Src>
    void body(Src &src) {
        const uint64_t nv = find("vertex")->count;
        for (const PlyElem &e : h_.elems) {
            for (uint64_t i = 0; i < e.count; ++i) {
                src.begin_item(e, i);
                item(src, e, nv);
            }
        }
        src.finish();
    }

    template <class Src>
    void item(Src &src, const PlyElem &e, uint64_t nv) {
        double p[3] = {0, 0, 0};
        idx_.clear();
        copy_.clear();
        for (const PlyProp &pr : e.props) {
            const bool copy = clean_ && kept(e, pr);
            double v = 0;
            if (!pr.list) {
                if (!src.value(pr.type, v)) too_few(src, e);
                check(src, pr, v, nv, p);
                if (copy) src.copy_value(copy_, pr.type, v);
                continue;
            }
            if (!src.value(pr.count_type, v)) too_few(src, e);
            if (copy) src.copy_value(copy_, PType::i32, v);
            if (v < 0) src.fail("negative list length " + src.shown());
            const uint64_t n = static_cast<uint64_t>(v);
            if (pr.role == Role::index && n < 3) src.fail("face has " + num(n) + " vertices (at least 3 needed)");
            for (uint64_t j = 0; j < n; ++j) {
                if (!src.value(pr.type, v)) {
                    if (pr.role == Role::index)
                        src.fail("face has " + num(j) + " vertex indices but its count says " + num(n));
                    src.fail("list '" + pr.name + "' has " + num(j) + " values but its count says " + num(n));
                }
                check(src, pr, v, nv, p);
                if (copy) src.copy_value(copy_, PType::i32, v);
            }
        }
        src.end_item(e);
        if (!copy_.empty()) {
            src.end_copy(copy_);
            *clean_ << copy_;
        }
        if (e.name == "vertex") box_.add(p);
        if (e.name != "face" || !s_.is_mesh) return;
        if (distinct(idx_)) ++faces_ok_;  // OpenMesh drops the others
    }

    template <class Src>
    [[noreturn]] void too_few(Src &src, const PlyElem &e) {
        bool lists = std::any_of(e.props.begin(), e.props.end(), [](const PlyProp &p) { return p.list; });
        if (lists) src.fail("too few values for a " + e.name);
        src.fail("expected " + num(e.props.size()) + " values for a " + e.name + ", found " + src.item_size());
    }

    template <class Src>
    void check(Src &src, const PlyProp &pr, double v, uint64_t nv, double *p) {
        switch (pr.role) {
        case Role::x: case Role::y: case Role::z:
            if (const char *why = bad_coordinate(v)) src.fail(why + src.quoted());
            p[static_cast<int>(pr.role) - static_cast<int>(Role::x)] = v;
            return;
        case Role::normal:
            if (!(std::fabs(v) <= FLT_MAX)) src.fail("normal is not finite or beyond float" + src.quoted());
            return;
        case Role::color:
            if (is_float(pr.type) && !(v >= 0 && v <= 1))
                src.fail("colour value out of range (0..1)" + src.quoted());
            return;
        case Role::index:
            if (v < 0 || v >= static_cast<double>(nv))
                src.fail("vertex index " + src.shown() + " out of range " +
                         (nv ? "(0.." + num(nv - 1) + ")" : "(the file has no vertices)"));
            idx_.push_back(static_cast<long long>(v));
            return;
        case Role::other: {
            // Text values are parsed by iostreams (CGAL as double, OpenMesh as the declared
            // type), which fail on nan, inf and values beyond the type.
            const double limit = pr.type == PType::f32 ? FLT_MAX : DBL_MAX;
            if (Src::strict_floats && is_float(pr.type) && !(std::fabs(v) <= limit))
                src.fail("value is not finite or beyond " + std::string(type_name(pr.type)) + src.quoted());
            return;
        }
        }
    }

    ByteReader &in_;
    std::string path_;
    uint64_t size_;
    std::ostream *clean_;
    PlyHeader h_;
    Scan s_;
    Box box_;
    uint64_t faces_ok_ = 0;
    std::vector<long long> idx_;
    std::string copy_;  // kept values of the current element, for the clean copy
};

// ------------------------------------------------------------------------- XYZ

// "x y z" or "x y z nx ny nz" per line, '#' comments, and (like CGAL) an optional point count alone
// on the first line, which is then checked against the points that follow. CGAL only skips lines
// that are empty or start with '#' once spaces are trimmed: a line holding just "\r" or a tab
// before '#' makes it fail, so such files are rewritten.
class XyzScanner {
public:
    XyzScanner(ByteReader &in, const std::string &path, std::ostream *clean)
        : path_(path), r_(in, path, true), clean_(clean) {}

    Scan run() {
        while (r_.next()) {
            if (r_.tok().empty()) {
                const std::string &l = r_.raw();
                const size_t first = l.find_first_not_of(' ');
                if (first != std::string::npos && l[first] != '#') s_.rewrite = true;
                continue;
            }
            if (r_.line() == 1 && r_.tok().size() == 1 && announce()) {
                emit();
                continue;
            }
            point();
            emit();
        }
        if (announced_ >= 0 && points_ < static_cast<uint64_t>(announced_))
            r_.fail("file ends after " + num(points_) + " of " + std::to_string(announced_) + " points");
        if (points_ == 0) fail_none(path_, "point set has no points");
        s_.is_mesh = false;
        s_.points = points_;
        s_.normals = columns_ == 6;
        box_.store(s_);
        return s_;
    }

private:
    bool announce() {
        long long n = 0;
        Num ok = parse_int(r_.tok()[0], n);
        if (ok == Num::bad) return false;
        if (ok == Num::range || n > static_cast<long long>(kMaxElements))
            r_.fail(std::string(r_.tok()[0]) + " points exceed the limit of " + kLimit);
        if (n < 0) r_.fail("negative point count " + std::string(r_.tok()[0]));
        announced_ = n;
        return true;
    }

    void point() {
        const Tokens &t = r_.tok();
        if (t.size() != 3 && t.size() != 6)
            r_.fail("expected 3 or 6 numbers (x y z [nx ny nz]), found " + num(t.size()));
        if (columns_ && t.size() != columns_)
            r_.fail("line has " + num(t.size()) + " numbers but earlier points have " + num(columns_));
        columns_ = t.size();
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = r_.coordinate(t[k]);
        for (size_t k = 3; k < t.size(); ++k) r_.number(t[k]);
        box_.add(p);
        ++points_;
        if (announced_ >= 0 && points_ > static_cast<uint64_t>(announced_))
            r_.fail("more points than the " + std::to_string(announced_) + " announced on line 1");
        if (points_ > kMaxElements) r_.fail("more than " + kLimit + " points");
    }

    void emit() {
        if (clean_) *clean_ << join(r_.tok(), r_.tok().size()) << '\n';
    }

    std::string path_;
    TextReader r_;
    std::ostream *clean_;
    Scan s_;
    Box box_;
    uint64_t points_ = 0;
    size_t columns_ = 0;
    long long announced_ = -1;
};

uint64_t file_size(const std::string &path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail_none(path, std::string("cannot open: ") + std::strerror(errno));
    return static_cast<uint64_t>(in.tellg());
}

}  // namespace

// ------------------------------------------------------------------------- entry points

Format format_of(const std::string &path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    const std::string ext = dot == std::string::npos || (slash != std::string::npos && dot < slash)
                                ? std::string()
                                : lower(path.substr(dot));
    if (ext == ".off") return Format::off;
    if (ext == ".obj") return Format::obj;
    if (ext == ".ply") return Format::ply;
    if (ext == ".stl") return Format::stl;
    if (ext == ".xyz") return Format::xyz;
    throw InputError(path, Where::none, 0,
                     "unknown format '" + ext + "' (expected .off .obj .ply .stl .xyz)");
}

const char *extension_of(Format f) {
    switch (f) {
    case Format::off: return ".off";
    case Format::obj: return ".obj";
    case Format::ply: return ".ply";
    case Format::stl: return ".stl";
    case Format::xyz: return ".xyz";
    }
    return "";
}

Scan scan_file(const std::string &path, Format f, std::ostream *clean) {
    const uint64_t size = file_size(path);
    if (size == 0) fail_none(path, "file is empty");
    switch (f) {
    case Format::off: {
        ByteReader in(path);
        return OffScanner(in, path, clean).run();
    }
    case Format::obj:
        return ObjScanner(path).run();
    case Format::ply: {
        ByteReader in(path);
        return PlyScanner(in, path, size, clean).run();
    }
    case Format::stl: {
        const bool text = stl_is_text(path, size);
        ByteReader in(path);
        if (text) return StlTextScanner(in, path, clean).run();
        return StlBinaryScanner(in, path, size).run();
    }
    case Format::xyz: {
        ByteReader in(path);
        return XyzScanner(in, path, clean).run();
    }
    }
    fail_none(path, "unknown format");
}

}  // namespace mc
