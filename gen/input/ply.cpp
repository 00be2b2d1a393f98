// PLY reader: ascii, binary_little_endian and binary_big_endian bodies after the header that
// ply_header.cpp reads. Elements are read in header order; properties the model has no use for
// (other elements, texture coordinates, alpha, extra lists) are read past and checked only for
// being there and being numbers of their type.
//
// Promise: reads the file once into a mesh when the header has faces, else into a point set (see
// readers.hpp). Values are taken with their declared type: a float stays the float the file holds;
// mesh coordinates are then rounded to float, point-set coordinates and normals kept as double.
// Colours: uchar as is; float (0..1) as float v * 255 truncated for meshes (what the PLY mesh
// reader always did), round(255 v) for point sets. Nothing is reserved beyond what the bytes left can hold (PlyElem::min_bytes).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include "input/faces.hpp"
#include "input/numbers.hpp"
#include "input/ply.hpp"
#include "input/readers.hpp"

namespace mc::input {
namespace {

std::string ends_after(const PlyElem &e, uint64_t i) {
    return "file ends after " + num(i) + " of " + num(e.count) + " " + plural(e.name);
}

// Values of an ascii body: one element per line, whitespace-separated.
class TextSource {
public:
    explicit TextSource(TextReader &r) : r_(r) {}
    void begin_item(const PlyElem &e, uint64_t i) {
        k_ = 0;
        if (!r_.next_content()) r_.fail(ends_after(e, i));
    }
    // False when the line has no more values.
    bool value(PType t, double &v) {
        if (k_ >= r_.tok().size()) return false;
        tok_ = r_.tok()[k_++];
        if (t == PType::f32) {
            float f = 0;
            const Num n = parse_float(tok_, f);
            if (n == Num::bad) fail("not a number: " + quote(tok_));
            v = n == Num::range ? HUGE_VAL : f;
            return true;
        }
        if (t == PType::f64) {
            const Num n = parse_double(tok_, v);
            if (n == Num::bad) fail("not a number: " + quote(tok_));
            if (n == Num::range) v = HUGE_VAL;
            return true;
        }
        long long i = 0;
        if (parse_int(tok_, i) != Num::ok || !fits(t, i)) fail(std::string("not a valid ") + type_name(t) + " value: " + quote(tok_));
        v = static_cast<double>(i);
        return true;
    }
    std::string shown() const { return std::string(tok_); }
    std::string quoted() const { return ": " + quote(tok_); }
    void end_item(const PlyElem &e) {
        if (k_ < r_.tok().size())
            fail("too many values for a " + e.name + ": expected " + num(k_) + ", found " + num(r_.tok().size()));
    }
    std::string item_size() const { return num(r_.tok().size()); }
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
    BinarySource(ByteReader &in, const std::string &path, uint64_t size, bool big) : in_(in), path_(path), size_(size), big_(big) {}
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
        type_ = t;
        value_ = v;
        return true;
    }
    // The last value as a message shows it (formatted only on failure: this is the hot path).
    std::string shown() const { return is_float(type_) ? show(value_) : std::to_string(static_cast<long long>(value_)); }
    std::string quoted() const { return " (" + shown() + ")"; }
    void end_item(const PlyElem &) {}
    std::string item_size() const { return "?"; }
    [[noreturn]] void fail(const std::string &msg) const { fail_byte(path_, at_, msg); }
    void finish() {
        if (!in_.at_end()) fail_byte(path_, in_.offset(), num(size_ - in_.offset()) + " bytes of extra data after the last element");
    }

private:
    static double decode(PType t, const unsigned char *b) {
        uint64_t u = 0;  // bytes are little-endian here; assembled explicitly to stay host-independent
        for (size_t k = type_size(t); k-- > 0;) u = u << 8 | b[k];
        switch (t) {
        case PType::i8: return static_cast<int8_t>(u);
        case PType::u8: return static_cast<uint8_t>(u);
        case PType::i16: return static_cast<int16_t>(u);
        case PType::u16: return static_cast<uint16_t>(u);
        case PType::i32: return static_cast<int32_t>(u);
        case PType::u32: return static_cast<uint32_t>(u);
        case PType::f32: {
            const uint32_t w = static_cast<uint32_t>(u);
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
    PType type_ = PType::u8;
    double value_ = 0;
    const PlyElem *e_ = nullptr;
    uint64_t i_ = 0;
};

class Body {
public:
    Body(const PlyHeader &h, Model &m) : h_(h), m_(m), faces_(m.tris) {}

    template <class Src>
    void read(Src &src, const ByteReader &in, uint64_t size) {
        const uint64_t nv = h_.elems[h_.vertex].count;
        for (const PlyElem &e : h_.elems) {
            reserve(e, size - std::min(size, in.offset()));
            for (uint64_t i = 0; i < e.count; ++i) {
                src.begin_item(e, i);
                item(src, e, nv);
            }
        }
        src.finish();
    }

private:
    void reserve(const PlyElem &e, uint64_t left) {
        const uint64_t n = reserve_for(e.count, e.min_bytes, left);
        if (&e == &h_.elems[h_.vertex]) {
            m_.points.reserve(n);
            if (h_.colors) m_.colors.reserve(n);
            if (h_.normals && !h_.is_mesh) m_.normals.reserve(n);
        } else if (e.name == "face" && h_.is_mesh) {
            m_.tris.reserve(n);
        }
    }

    template <class Src>
    void item(Src &src, const PlyElem &e, uint64_t nv) {
        std::array<double, 3> p{}, n{}, c{};
        idx_.clear();
        for (const PlyProp &pr : e.props) {
            double v = 0;
            if (!pr.list) {
                if (!src.value(pr.type, v)) too_few(src, e);
                check(src, pr, v, nv, p, n, c);
                continue;
            }
            if (!src.value(pr.count_type, v)) too_few(src, e);
            if (v < 0) src.fail("negative list length " + src.shown());
            const uint64_t len = static_cast<uint64_t>(v);
            if (pr.role == Role::index && len < 3) src.fail("face has " + num(len) + " vertices (at least 3 needed)");
            for (uint64_t j = 0; j < len; ++j) {
                if (!src.value(pr.type, v)) {
                    if (pr.role == Role::index) src.fail("face has " + num(j) + " vertex indices but its count says " + num(len));
                    src.fail("list '" + pr.name + "' has " + num(j) + " values but its count says " + num(len));
                }
                check(src, pr, v, nv, p, n, c);
            }
        }
        src.end_item(e);
        if (&e == &h_.elems[h_.vertex]) vertex(p, n, c);
        else if (e.name == "face" && h_.is_mesh) faces_.add(idx_);
    }

    void vertex(const std::array<double, 3> &p, const std::array<double, 3> &n, const std::array<double, 3> &c) {
        if (h_.is_mesh) {
            m_.points.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
        } else {
            m_.points.push_back(p);
            if (h_.normals) m_.normals.push_back(n);
        }
        if (!h_.colors) return;
        std::array<uint8_t, 3> rgb;
        for (int k = 0; k < 3; ++k) {
            if (!h_.colors_float) rgb[k] = static_cast<uint8_t>(c[k]);
            else if (h_.is_mesh) rgb[k] = static_cast<uint8_t>(static_cast<float>(c[k]) * 255.0f);
            else rgb[k] = static_cast<uint8_t>(std::lround(c[k] * 255));
        }
        m_.colors.push_back(rgb);
    }

    template <class Src>
    [[noreturn]] void too_few(Src &src, const PlyElem &e) {
        const bool lists = std::any_of(e.props.begin(), e.props.end(), [](const PlyProp &p) { return p.list; });
        if (lists) src.fail("too few values for a " + e.name);
        src.fail("expected " + num(e.props.size()) + " values for a " + e.name + ", found " + src.item_size());
    }

    template <class Src>
    void check(Src &src, const PlyProp &pr, double v, uint64_t nv, std::array<double, 3> &p, std::array<double, 3> &n,
               std::array<double, 3> &c) {
        switch (pr.role) {
        case Role::x: case Role::y: case Role::z:
            if (const char *why = bad_coordinate(v)) src.fail(why + src.quoted());
            p[static_cast<int>(pr.role) - static_cast<int>(Role::x)] = v;
            return;
        case Role::nx: case Role::ny: case Role::nz:
            if (!(std::fabs(v) <= FLT_MAX)) src.fail("normal is not finite or beyond float" + src.quoted());
            n[static_cast<int>(pr.role) - static_cast<int>(Role::nx)] = v;
            return;
        case Role::red: case Role::green: case Role::blue: case Role::color_other:
            if (is_float(pr.type) && !(v >= 0 && v <= 1)) src.fail("colour value out of range (0..1)" + src.quoted());
            if (pr.role != Role::color_other) c[static_cast<int>(pr.role) - static_cast<int>(Role::red)] = v;
            return;
        case Role::index:
            if (v < 0 || v >= static_cast<double>(nv))
                src.fail("vertex index " + src.shown() + " out of range " +
                         (nv ? "(0.." + num(nv - 1) + ")" : "(the file has no vertices)"));
            idx_.push_back(static_cast<uint32_t>(v));
            return;
        case Role::other:
            return;
        }
    }

    const PlyHeader &h_;
    Model &m_;
    Faces faces_;
    std::vector<uint32_t> idx_;
};

}  // namespace

Model read_ply(const std::string &path, uint64_t size) {
    ByteReader in(path);
    TextReader r(in, path, false);
    const PlyHeader h = read_ply_header(r);
    Model m;
    m.is_mesh = h.is_mesh;
    Body body(h, m);
    if (h.format == PlyHeader::ascii) {
        TextSource src(r);
        body.read(src, in, size);
    } else {
        BinarySource src(in, path, size, h.format == PlyHeader::big);
        body.read(src, in, size);
    }
    if (m.points.empty()) fail_none(path, m.is_mesh ? "model has no vertices" : "point set has no points");
    return m;
}

}  // namespace mc::input
