#include <algorithm>

#include "input/numbers.hpp"
#include "input/ply.hpp"

namespace mc::input {
namespace {

bool ply_type(std::string_view name, PType &t) {
    static const struct {
        const char *name;
        PType type;
    } kTypes[] = {{"char", PType::i8},   {"int8", PType::i8},     {"uchar", PType::u8},   {"uint8", PType::u8},
                  {"short", PType::i16}, {"int16", PType::i16},   {"ushort", PType::u16}, {"uint16", PType::u16},
                  {"int", PType::i32},   {"int32", PType::i32},   {"uint", PType::u32},   {"uint32", PType::u32},
                  {"float", PType::f32}, {"float32", PType::f32}, {"double", PType::f64}, {"float64", PType::f64}};
    for (const auto &k : kTypes)
        if (name == k.name) {
            t = k.type;
            return true;
        }
    return false;
}

Role role_of(const std::string &element, const std::string &name) {
    if (element == "vertex") {
        static const struct {
            const char *name;
            Role role;
        } kRoles[] = {{"x", Role::x},         {"y", Role::y},         {"z", Role::z},          {"nx", Role::nx},
                      {"ny", Role::ny},       {"nz", Role::nz},       {"red", Role::red},      {"green", Role::green},
                      {"blue", Role::blue},   {"alpha", Role::color_other}, {"diffuse_red", Role::color_other},
                      {"diffuse_green", Role::color_other}, {"diffuse_blue", Role::color_other}};
        for (const auto &k : kRoles)
            if (name == k.name) return k.role;
    }
    if (element == "face" && (name == "vertex_indices" || name == "vertex_index")) return Role::index;
    return Role::other;
}

// Element and property names end up in messages, so they must be printable words.
void check_name(const TextReader &r, std::string_view name) {
    for (char c : name)
        if (c < 33 || c > 126) r.fail("bad name " + quote(name) + " in the header");
}

class HeaderReader {
public:
    explicit HeaderReader(TextReader &r) : r_(r) {}

    PlyHeader run() {
        if (!r_.next() || r_.tok().size() != 1 || r_.tok()[0] != "ply") r_.fail("expected 'ply' on the first line");
        if (!r_.next() || r_.tok().size() != 3 || r_.tok()[0] != "format")
            r_.fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
        const std::string_view f = r_.tok()[1];
        if (f == "ascii") h_.format = PlyHeader::ascii;
        else if (f == "binary_little_endian") h_.format = PlyHeader::little;
        else if (f == "binary_big_endian") h_.format = PlyHeader::big;
        else r_.fail("unknown PLY format " + quote(f));
        if (r_.tok()[2] != "1.0") r_.fail("unsupported PLY version " + quote(r_.tok()[2]));
        for (;;) {
            if (!r_.next()) r_.fail("file ends inside the header (no 'end_header')");
            const Tokens &t = r_.tok();
            if (t.empty()) r_.fail("empty line in the header");
            if (t[0] == "end_header" && t.size() == 1) break;
            if (t[0] == "element") element();
            else if (t[0] == "property") property();
            else if (t[0] != "comment" && t[0] != "obj_info") r_.fail("unknown header keyword " + quote(t[0]));
        }
        // An element without properties takes no room, so its count is not checked by the data;
        // refusing it keeps a tiny file from making the reader loop over 50 million empty items.
        for (const PlyElem &e : h_.elems)
            if (e.props.empty() && e.count > 0) fail_line(r_.path(), e.line, "element '" + e.name + "' has no properties");
        check();
        return std::move(h_);
    }

private:
    void element() {
        const Tokens &t = r_.tok();
        if (t.size() != 3) r_.fail("expected 'element NAME COUNT'");
        check_name(r_, t[1]);
        PlyElem e;
        e.name = std::string(t[1]);
        e.line = r_.line();
        long long n = 0;
        const Num ok = parse_int(t[2], n);
        if (ok == Num::bad || (ok == Num::ok && n < 0)) r_.fail("bad element count " + quote(t[2]));
        if (ok == Num::range || static_cast<uint64_t>(n) > kMaxElements)
            r_.fail("element '" + e.name + "' count " + std::string(t[2]) + " exceeds the limit of " + kLimit);
        e.count = static_cast<uint64_t>(n);
        if (find(e.name)) r_.fail("second element named '" + e.name + "'");
        h_.elems.push_back(e);
    }

    void property() {
        const Tokens &t = r_.tok();
        if (h_.elems.empty()) r_.fail("property before any element");
        PlyProp p;
        p.line = r_.line();
        if (t.size() == 5 && t[1] == "list") {
            p.list = true;
            if (!ply_type(t[2], p.count_type) || is_float(p.count_type)) r_.fail("bad list count type " + quote(t[2]));
            p.type_name = std::string(t[3]);
            p.name = std::string(t[4]);
        } else if (t.size() == 3) {
            p.type_name = std::string(t[1]);
            p.name = std::string(t[2]);
        } else {
            r_.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
        }
        if (!ply_type(p.type_name, p.type)) r_.fail("unknown property type " + quote(p.type_name));
        check_name(r_, p.name);
        PlyElem &e = h_.elems.back();
        for (const PlyProp &q : e.props)
            if (q.name == p.name) r_.fail("second property '" + p.name + "' in element '" + e.name + "'");
        p.role = role_of(e.name, p.name);
        const bool ascii = h_.format == PlyHeader::ascii;
        e.min_bytes += ascii ? 2 : p.list ? type_size(p.count_type) : type_size(p.type);
        e.props.push_back(p);
    }

    const PlyElem *find(const std::string &name) const {
        for (const PlyElem &e : h_.elems)
            if (e.name == name) return &e;
        return nullptr;
    }

    static const PlyProp *prop(const PlyElem &e, Role role) {
        for (const PlyProp &p : e.props)
            if (p.role == role) return &p;
        return nullptr;
    }

    void fail_at(long long line, const std::string &msg) const { fail_line(r_.path(), line, msg); }

    void check() {
        const PlyElem *v = find("vertex");
        if (!v) r_.fail("no 'element vertex' in the header");
        h_.vertex = static_cast<size_t>(v - h_.elems.data());
        for (Role axis : {Role::x, Role::y, Role::z})
            if (!prop(*v, axis))
                fail_at(v->line, std::string("vertex element has no '") + "xyz"[static_cast<int>(axis) - 1] + "' property");
        for (const PlyProp &p : v->props) check_vertex_prop(p);
        const PlyProp *red = prop(*v, Role::red), *green = prop(*v, Role::green), *blue = prop(*v, Role::blue);
        h_.normals = prop(*v, Role::nx) && prop(*v, Role::ny) && prop(*v, Role::nz);
        if (red && green && blue) {
            for (const PlyProp *c : {green, blue})
                if (c->type != red->type) fail_at(c->line, "colour properties red, green and blue have different types");
            h_.colors = true;
            h_.colors_float = red->type == PType::f32;
        }
        PlyElem *f = nullptr;
        for (PlyElem &e : h_.elems)
            if (e.name == "face") f = &e;
        h_.is_mesh = f && f->count > 0;
        if (h_.is_mesh) check_faces(*f);
        else if (f)  // an empty face element: a point set; its lists are not indices
            for (PlyProp &p : f->props) p.role = Role::other;
    }

    void check_vertex_prop(const PlyProp &p) {
        const bool coordinate = p.role == Role::x || p.role == Role::y || p.role == Role::z;
        const bool normal = p.role == Role::nx || p.role == Role::ny || p.role == Role::nz;
        const bool color = p.role == Role::red || p.role == Role::green || p.role == Role::blue || p.role == Role::color_other;
        if ((coordinate || normal || color) && p.list) fail_at(p.line, "property '" + p.name + "' must not be a list");
        if ((coordinate || normal) && !is_float(p.type))
            fail_at(p.line, "property '" + p.name + "' has type " + p.type_name + " (must be float or double)");
        if (color && p.type != PType::u8 && p.type != PType::f32)
            fail_at(p.line, "colour '" + p.name + "' has type " + p.type_name + " (must be uchar or float)");
    }

    // Picks the face's index list: the first vertex_indices / vertex_index list.
    void check_faces(PlyElem &f) {
        if (&f < &h_.elems[h_.vertex]) fail_at(f.line, "the 'face' element must come after 'vertex'");
        PlyProp *idx = nullptr;
        for (PlyProp &p : f.props) {
            if (p.role != Role::index) continue;
            if (idx || !p.list) p.role = Role::other;
            else idx = &p;
        }
        if (!idx) fail_at(f.line, "face element has no 'vertex_indices' list");
        if (is_float(idx->type)) fail_at(idx->line, "vertex indices must have an integer type, not " + idx->type_name);
    }

    TextReader &r_;
    PlyHeader h_;
};

}  // namespace

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

PlyHeader read_ply_header(TextReader &r) { return HeaderReader(r).run(); }

}  // namespace mc::input
