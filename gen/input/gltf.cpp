// Long because the three passes (the container and JSON before tinygltf, the indices and accessor
// bytes after it, the model built from them) share one set of limits, byte offsets and error
// messages keyed to the same glTF members; split, each file would restate them. The JSON pre-check
// (the SAX handler) is the piece that could stand alone if the file grows.
//
// glTF 2.0 reader: .gltf (JSON, its buffers as base64 data URIs or files beside it) and .glb (the
// binary container: a JSON chunk and a BIN chunk). The file is read once into memory and checked in
// two passes of our own around Debian's tinygltf, which parses the JSON and loads the buffers:
//   before: the GLB container (magic, version, length, chunk lengths and alignment, with their byte
//     offsets: tinygltf 2.7 lets a BIN chunk run 8 bytes past the file), then the JSON itself with
//     nlohmann's SAX parser (syntax errors at their line or byte; nesting deeper than kMaxDepth,
//     which tinygltf would recurse into; non-finite numbers; index-valued members that are not
//     integers in 0..2^31-1, which tinygltf would silently drop or truncate; a glTF version other
//     than 2.x; any extensionsRequired, since none is supported);
//   after: every index the model uses (scene, node, mesh, accessor, buffer view, buffer,
//     material, texture, sampler, image) and every accessor's bytes against its buffer.
// tinygltf's own errors and warnings are refused as they are ("tinygltf: ..."). It reads external
// files through our callbacks only (regular files beside the .gltf, at most kMaxFileBytes), and its
// image loader is replaced by one that keeps the encoded bytes: only the images a drawn primitive
// samples are decoded, by stb_image, after checking that they are PNG or JPEG of a sane size.
//
// Promise: reads into a mesh (readers.hpp) the triangle primitives (TRIANGLES, TRIANGLE_STRIP and
// TRIANGLE_FAN, fanned and stripped as the glTF spec orders the corners) of every node of the
// default scene (`scene`, else scene 0, else every root node when the file has no scenes). Points
// and lines primitives are skipped; a scene without any triangle primitive is refused. Each
// vertex is transformed by its node's world matrix (`matrix`, else T * R * S, composed from the
// root down, in double) and then rounded to float; a node whose world matrix mirrors (negative
// determinant) has its faces' corners swapped, as the spec makes such faces clockwise. Vertices
// are stored per drawn primitive and node in traversal order (depth first, children in order),
// faces in index order, any face naming a vertex twice dropped. A skinned mesh is read in its
// bind pose (its vertices as stored: joints, weights and the node's transform are not applied, as
// the spec says to ignore that transform); morph targets are not applied.
// Colours (RGB per vertex) follow the spec's base colour: baseColorFactor * baseColorTexture *
// COLOR_0, each present factor multiplied in linear light (the texture, sRGB-encoded, decoded
// first; COLOR_0 and the factor are linear), then encoded to sRGB bytes (round(255 s)). The texture
// counts only when the primitive has its TEXCOORD_n; it is sampled at the vertex's UV, nearest
// texel, with its sampler's wrap modes. A model gets colours when some drawn primitive has COLOR_0,
// a sampled texture, or a baseColorFactor other than white; a primitive without any of these is
// then white (the spec's default material). Float colours are clamped to 0..1; alpha is ignored.
// At most kMaxElements vertices and faces in all, each instance of a mesh counted, checked before
// anything is stored. Members of the wrong type that tinygltf passes over without a word (a name
// that is a number, a pbrMetallicRoughness that is an array) read as absent; index members do not
// (see "before" above).
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include "input/faces.hpp"
#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc::input {
namespace {

// tinygltf takes a file's length as unsigned int and a GLB's header is 32-bit: 2 GiB is beyond
// any model this generator bakes and safely inside both.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 31;
// glTF itself nests 6 deep; extras may go deeper, but tinygltf copies them recursively.
constexpr size_t kMaxDepth = 64;
// 8192 x 8192: the largest textures exporters write; decoded as RGB, 192 MiB.
constexpr uint64_t kMaxTexels = uint64_t(1) << 26;

using Json = nlohmann::json;

// A message from a library or the file as one printable line of at most 300 bytes.
std::string clean(const std::string &s) {
    std::string r;
    for (char ch : s) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '\n' || c == '\r') {
            if (!r.empty() && r.back() != ' ') r += "; ";
        } else {
            r += c < 32 || c == 127 ? '?' : ch;
        }
        if (r.size() >= 300) break;
    }
    while (!r.empty() && (r.back() == ' ' || r.back() == ';')) r.pop_back();
    return r;
}

uint32_t le32(const std::vector<unsigned char> &b, size_t at) {
    return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

// ---- the container ---------------------------------------------------------------------------

std::vector<unsigned char> read_all(const std::string &path, uint64_t size) {
    if (size > kMaxFileBytes) fail_none(path, "file is larger than " + num(kMaxFileBytes) + " bytes (glTF files are read whole)");
    std::vector<unsigned char> data(static_cast<size_t>(size));
    ByteReader in(path);
    if (in.read(reinterpret_cast<char *>(data.data()), data.size()) != data.size() || !in.at_end())
        fail_none(path, "cannot read: the file changed size while being read");
    return data;
}

// The JSON chunk's place in a .glb; the BIN chunk, if any, follows it (checked here).
struct Chunk {
    size_t at = 0, size = 0;
};

Chunk glb_container(const std::string &path, const std::vector<unsigned char> &b) {
    const uint64_t n = b.size();
    if (n >= 1 && b[0] == '{') fail_byte(path, 0, "this is a JSON glTF, not a binary one: name it .gltf");
    if (n < 12) fail_byte(path, n, "file ends inside the 12-byte GLB header");
    if (std::memcmp(b.data(), "glTF", 4) != 0) fail_byte(path, 0, "not a binary glTF file (no 'glTF' magic)");
    if (le32(b, 4) != 2) fail_byte(path, 4, "GLB version " + num(le32(b, 4)) + " is not supported (2 only)");
    const uint64_t length = le32(b, 8);
    if (length != n)
        fail_byte(path, 8, "the header says " + num(length) + " bytes but the file has " + num(n) +
                               (length > n ? " (truncated?)" : ""));
    if (n < 20) fail_byte(path, n, "file ends inside the JSON chunk's header");
    const uint64_t json_len = le32(b, 12);
    if (le32(b, 16) != 0x4E4F534Au) fail_byte(path, 16, "the first chunk is not JSON");
    if (json_len == 0) fail_byte(path, 12, "the JSON chunk is empty");
    if (json_len % 4 != 0) fail_byte(path, 12, "the JSON chunk's length " + num(json_len) + " is not a multiple of 4");
    if (20 + json_len > n)
        fail_byte(path, 12, "the JSON chunk's " + num(json_len) + " bytes run past the end of the file (" + num(n) + " bytes)");
    uint64_t at = 20 + json_len;
    for (int k = 1; at < n; ++k) {
        if (n - at < 8) fail_byte(path, at, "file ends inside a chunk header");
        const uint64_t len = le32(b, static_cast<size_t>(at)), type = le32(b, static_cast<size_t>(at + 4));
        if (len % 4 != 0) fail_byte(path, at, "chunk length " + num(len) + " is not a multiple of 4");
        if (len > n - at - 8)
            fail_byte(path, at, "the chunk's " + num(len) + " bytes run past the end of the file (" + num(n) + " bytes)");
        if (k == 1 && type != 0x004E4942u)  // tinygltf refuses any other second chunk
            fail_byte(path, at + 4, "the chunk after the JSON is not BIN");
        if (k == 1 && len == 0) fail_byte(path, at, "the BIN chunk is empty (omit it instead)");
        at += 8 + len;
    }
    return {20, static_cast<size_t>(json_len)};
}

// ---- the JSON, before tinygltf -------------------------------------------------------------------

// Members whose value tinygltf reads as an int index or enum, and which are silently dropped
// (wrong type) or truncated (beyond int) there: here they must be integers in 0..2^31-1.
bool int_member(const std::string &k) {
    static const char *const keys[] = {"buffer",   "bufferView", "indices",  "material", "mesh",    "skin",
                                       "camera",   "scene",      "nodes",    "children", "joints",  "source",
                                       "sampler",  "index",      "texCoord", "node",     "input",   "output",
                                       "skeleton", "inverseBindMatrices",    "mode",     "magFilter",
                                       "minFilter", "wrapS",     "wrapT",    "width",    "height"};
    for (const char *key : keys)
        if (k == key) return true;
    return false;
}

class Scan : public nlohmann::json_sax<Json> {
public:
    Scan(const std::string &path) : path_(path) {}
    std::string version;
    std::vector<std::string> required;

    bool null() override { return scalar("null"); }
    bool boolean(bool v) override { return scalar(v ? "true" : "false"); }
    bool number_integer(number_integer_t v) override { return integer(v < 0, static_cast<uint64_t>(v), std::to_string(v)); }
    bool number_unsigned(number_unsigned_t v) override { return integer(false, v, std::to_string(v)); }
    bool number_float(number_float_t v, const string_t &s) override {
        if (!skipped() && !std::isfinite(v)) fail(where() + ": number " + quote(s) + " is out of range");
        return scalar(s);
    }
    bool string(string_t &s) override {
        if (frames_.size() == 2 && !frames_[1].array && frames_[0].cur == "asset" && frames_[1].cur == "version") version = s;
        if (frames_.size() == 2 && frames_[1].array && frames_[1].key == "extensionsRequired") required.push_back(s);
        return scalar(quote(s));
    }
    bool binary(binary_t &) override { return scalar("binary"); }
    bool start_object(std::size_t) override { return push(false); }
    bool key(string_t &k) override {
        frames_.back().cur = k;
        return true;
    }
    bool end_object() override { return pop(); }
    bool start_array(std::size_t) override { return push(true); }
    bool end_array() override { return pop(); }
    bool parse_error(std::size_t pos, const std::string &, const nlohmann::detail::exception &e) override {
        error_at = pos ? pos - 1 : 0;
        std::string s = e.what();  // "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
        if (!s.empty() && s[0] == '[' && s.find("] ") != std::string::npos) s = s.substr(s.find("] ") + 2);
        const size_t c = s.find("column ");
        if (c != std::string::npos && s.find(": ", c) != std::string::npos) s = s.substr(s.find(": ", c) + 2);
        error = clean(s);
        return false;
    }

    size_t error_at = 0;  // byte offset in the JSON of a syntax error
    std::string error;

private:
    struct Frame {
        bool array;
        std::string key;  // the member this container is the value of (arrays: also their elements')
        bool skips;       // inside extras or extensions: free-form, not checked
        std::string cur;  // objects: the member being read
        uint64_t index = 0;
    };

    [[noreturn]] void fail(const std::string &msg) const { fail_none(path_, msg); }

    std::string context() const {
        if (frames_.empty()) return "";
        return frames_.back().array ? frames_.back().key : frames_.back().cur;
    }
    std::string where() const {
        std::string p;
        for (size_t i = 0; i < frames_.size(); ++i) {
            const Frame &f = frames_[i];
            if (i >= 4 && i + 2 < frames_.size()) {  // deep paths: the start and the end
                if (i == 4) p += "...";
                continue;
            }
            if (f.array) {
                p += "[" + num(f.index) + "]";
            } else {
                if (!p.empty()) p += ".";
                p += f.cur;
            }
        }
        return p.empty() ? "the document" : p;
    }
    // Free-form parts: extras, extensions, and members glTF 2.0 does not define (old drafts' techniques).
    bool skipped() const {
        static const char *const core[] = {"asset",     "accessors", "animations", "buffers", "bufferViews",
                                           "cameras",   "images",    "materials",  "meshes",  "nodes",
                                           "samplers",  "scene",     "scenes",     "skins",   "textures",
                                           "extensionsUsed", "extensionsRequired"};
        if (skip_ > 0 || context() == "extras" || context() == "extensions") return true;
        return !frames_.empty() && std::none_of(std::begin(core), std::end(core), [&](const char *k) { return frames_[0].cur == k; });
    }
    // An index member; a primitive's attributes (and morph targets) also name accessors by index:
    // meshes[i].primitives[j].attributes.NAME and ...targets[k].NAME.
    bool index_here() const {
        if (frames_.empty() || skipped()) return false;
        const Frame &f = frames_.back();
        const bool attr = frames_.size() >= 6 && frames_[0].cur == "meshes" && !f.array && (f.key == "attributes" || f.key == "targets");
        return attr || int_member(context());
    }
    bool integer(bool negative, uint64_t v, const std::string &text) {
        if (index_here() && (negative || v > 0x7FFFFFFFu))
            fail(where() + ": " + text + " is out of range (an index or enum, 0.." + num(0x7FFFFFFFu) + ")");
        // the schema's minimum for buffers and buffer views; tinygltf 2.7 throws on an empty BIN buffer
        if (v == 0 && !skipped() && context() == "byteLength") fail(where() + ": 0 bytes (at least 1)");
        return done();
    }
    bool scalar(const std::string &text) {
        if (index_here()) fail(where() + ": expected an integer, found " + text);
        return done();
    }
    bool done() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
        return true;
    }
    bool push(bool array) {
        const std::string k = context();
        if (frames_.size() >= kMaxDepth) fail(where() + ": nested deeper than " + num(kMaxDepth) + " levels");
        const bool skips = !frames_.empty() && (k == "extras" || k == "extensions");
        skip_ += skips;
        frames_.push_back({array, k, skips, std::string()});
        return true;
    }
    bool pop() {
        skip_ -= frames_.back().skips;
        frames_.pop_back();
        return done();
    }

    std::string path_;
    std::vector<Frame> frames_;
    int skip_ = 0;
};

// Line (1-based) of byte AT of TEXT.
long long line_of(const unsigned char *text, size_t at) {
    return 1 + std::count(text, text + at, '\n');
}

void scan_json(const std::string &path, const std::vector<unsigned char> &file, Chunk json, bool glb) {
    Scan scan(path);
    const unsigned char *begin = file.data() + json.at;
    if (!Json::sax_parse(begin, begin + json.size, &scan)) {
        const std::string msg = "JSON: " + scan.error;
        const size_t at = std::min(scan.error_at, json.size);
        if (glb) fail_byte(path, json.at + at, msg);
        fail_line(path, line_of(begin, at), msg);
    }
    if (scan.version.empty()) fail_none(path, "asset.version is missing (not a glTF file?)");
    if (scan.version.substr(0, 2) != "2.")
        fail_none(path, "asset.version: glTF " + quote(scan.version) + " is not supported (2.0 only)");
    for (const std::string &e : scan.required)
        fail_none(path, "extensionsRequired: extension " + quote(e) + " is not supported (modelc reads core glTF 2.0)");
}

// ---- tinygltf's file access and image loading ---------------------------------------------------

struct Files {
    std::string base;                                // the .gltf's directory ("" for the working one)
    std::map<int, std::vector<unsigned char>> images;  // encoded bytes of uri images, by index
};

// Only regular files, and only under the file's own directory: tinygltf also tries "./URI".
bool file_exists(const std::string &p, void *u) {
    const std::string &base = static_cast<Files *>(u)->base;
    if (!base.empty() && p.compare(0, base.size(), base) != 0) return false;
    struct stat st;
    return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

std::string expand_path(const std::string &p, void *) { return p; }

bool read_file(std::vector<unsigned char> *out, std::string *err, const std::string &p, void *) {
    struct stat st;
    if (stat(p.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
        *err += "not a readable regular file";
        return false;
    }
    if (static_cast<uint64_t>(st.st_size) > kMaxFileBytes) {
        *err += "larger than " + num(kMaxFileBytes) + " bytes";
        return false;
    }
    FILE *f = std::fopen(p.c_str(), "rb");
    if (!f) {
        *err += std::strerror(errno);
        return false;
    }
    out->resize(static_cast<size_t>(st.st_size));
    const size_t got = out->empty() ? 0 : std::fread(out->data(), 1, out->size(), f);
    std::fclose(f);
    if (got != out->size()) {
        *err += "cannot read it whole";
        return false;
    }
    return true;
}

bool write_file(std::string *err, const std::string &, const std::vector<unsigned char> &, void *) {
    *err += "modelc writes no files through tinygltf";
    return false;
}

// Keeps a uri image's bytes for later. An image in a buffer view is taken from the buffer later,
// range-checked: tinygltf 2.7 hands the loader a pointer into the buffer without checking the
// view's bounds.
bool keep_image(tinygltf::Image *image, const int index, std::string *, std::string *, int, int,
                const unsigned char *bytes, int size, void *u) {
    if (image->bufferView < 0 && size > 0) static_cast<Files *>(u)->images[index].assign(bytes, bytes + size);
    return true;
}

// ---- the model ----------------------------------------------------------------------------------

using Mat = std::array<double, 16>;  // column-major, as glTF writes it
const Mat kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat mul(const Mat &a, const Mat &b) {
    Mat r{};
    for (int c = 0; c < 4; ++c)
        for (int rr = 0; rr < 4; ++rr) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[k * 4 + rr] * b[c * 4 + k];
            r[c * 4 + rr] = s;
        }
    return r;
}

double det3(const Mat &m) {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
}

std::string stb_reason() {
    const char *r = stbi_failure_reason();
    return clean(r ? r : "unknown");
}

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1 / 2.4) - 0.055; }
uint8_t srgb_byte(double linear) {
    const double s = linear_to_srgb(std::clamp(linear, 0.0, 1.0));
    return static_cast<uint8_t>(std::floor(255 * s + 0.5));
}

// An accessor's elements, checked against its buffer view and buffer.
struct Elements {
    const unsigned char *at = nullptr;
    size_t stride = 0, count = 0;
    int comps = 0, type = 0;
    bool normalized = false;
};

struct Texture {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    int wrap_s = TINYGLTF_TEXTURE_WRAP_REPEAT, wrap_t = TINYGLTF_TEXTURE_WRAP_REPEAT;
};

class Builder {
public:
    Builder(const std::string &path, const tinygltf::Model &g, const Files &files) : path_(path), g_(g), files_(files) {}

    Model run() {
        m_.is_mesh = true;
        for (size_t i = 0; i < g_.nodes.size(); ++i) check_node(static_cast<int>(i));
        std::vector<int> parent(g_.nodes.size(), -1);
        for (size_t i = 0; i < g_.nodes.size(); ++i)
            for (size_t k = 0; k < g_.nodes[i].children.size(); ++k) {
                const int c = g_.nodes[i].children[k];
                const std::string at = "nodes[" + num(i) + "].children[" + num(k) + "]";
                if (c < 0 || size_t(c) >= g_.nodes.size()) fail(at + ": " + missing("node", c, g_.nodes.size()));
                if (parent[c] >= 0)
                    fail(at + ": nodes[" + num(c) + "] is already a child of nodes[" + num(parent[c]) +
                         "] (the node hierarchy must be a tree)");
                parent[c] = static_cast<int>(i);
            }
        std::vector<int> roots;
        std::string from;
        if (g_.defaultScene >= 0 || !g_.scenes.empty()) {
            const int s = g_.defaultScene >= 0 ? g_.defaultScene : 0;
            if (size_t(s) >= g_.scenes.size()) fail("scene: " + missing("scene", s, g_.scenes.size()));
            from = "scenes[" + num(s) + "].nodes";
            roots = g_.scenes[s].nodes;
            for (size_t k = 0; k < roots.size(); ++k) {
                const int r = roots[k];
                if (r < 0 || size_t(r) >= g_.nodes.size()) fail(from + "[" + num(k) + "]: " + missing("node", r, g_.nodes.size()));
                if (parent[r] >= 0)
                    fail(from + "[" + num(k) + "]: nodes[" + num(r) + "] is a child of nodes[" + num(parent[r]) +
                         "] (a scene lists root nodes)");
            }
        } else {
            from = "the root nodes (the file has no scene)";
            for (size_t i = 0; i < g_.nodes.size(); ++i)
                if (parent[i] < 0) roots.push_back(static_cast<int>(i));
        }
        walk(roots, from);
        if (triangle_prims_ == 0)
            fail(from + ": no triangle primitives to draw" +
                 (skipped_prims_ ? " (" + num(skipped_prims_) + " points or lines primitives are not read)" : ""));
        if (!coloured_) m_.colors = {};
        return std::move(m_);
    }

private:
    [[noreturn]] void fail(const std::string &msg) const { fail_none(path_, msg); }
    static std::string missing(const std::string &what, long long i, size_t n) {
        return what + " " + std::to_string(i) + " does not exist (the file has " + num(n) + " " +
               (n == 1 ? what : what == "mesh" ? "meshes" : plural(what)) + ")";
    }

    void check_node(int i) const {
        const tinygltf::Node &n = g_.nodes[i];
        const std::string at = "nodes[" + num(i) + "]";
        auto sizes = [&](const std::vector<double> &v, size_t want, const char *name) {
            if (!v.empty() && v.size() != want)
                fail(at + "." + name + " has " + num(v.size()) + " numbers (" + num(want) + " expected)");
        };
        sizes(n.matrix, 16, "matrix");
        sizes(n.translation, 3, "translation");
        sizes(n.rotation, 4, "rotation");
        sizes(n.scale, 3, "scale");
        if (n.mesh >= 0 && size_t(n.mesh) >= g_.meshes.size()) fail(at + ".mesh: " + missing("mesh", n.mesh, g_.meshes.size()));
    }

    Mat local(int i) const {
        const tinygltf::Node &n = g_.nodes[i];
        if (n.matrix.size() == 16) {
            Mat m;
            std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
            return m;
        }
        Mat t = kIdentity, r = kIdentity, s = kIdentity;
        if (n.translation.size() == 3) t[12] = n.translation[0], t[13] = n.translation[1], t[14] = n.translation[2];
        if (n.scale.size() == 3) s[0] = n.scale[0], s[5] = n.scale[1], s[10] = n.scale[2];
        if (n.rotation.size() == 4) {
            double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
            const double len = std::sqrt(x * x + y * y + z * z + w * w);
            if (!(len > 0) || !std::isfinite(len)) fail("nodes[" + num(i) + "].rotation is not a rotation quaternion");
            if (len != 1) x /= len, y /= len, z /= len, w /= len;
            r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
                 2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
                 2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
                 0,                       0,                       0,                       1};
        }
        return mul(t, mul(r, s));
    }

    // Depth first from the roots, children in order, each node once (run() made the hierarchy a
    // forest); every primitive's vertices and triangles counted before any is stored, so that a
    // small file that instances a mesh too often is refused before it takes the memory.
    void walk(const std::vector<int> &roots, const std::string &from) {
        std::vector<std::pair<int, Mat>> stack, drawn;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, kIdentity});
        std::vector<char> seen(g_.nodes.size(), 0);
        while (!stack.empty()) {
            const int i = stack.back().first;
            const Mat world = mul(stack.back().second, local(i));
            stack.pop_back();
            if (seen[i]) fail("nodes[" + num(i) + "] is reached twice from the scene (listed twice?)");
            seen[i] = 1;
            const tinygltf::Node &n = g_.nodes[i];
            if (n.mesh >= 0) drawn.push_back({i, n.skin >= 0 ? kIdentity : world});
            for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) stack.push_back({*it, world});
        }
        uint64_t points = 0, tris = 0;
        for (const auto &d : drawn) {
            const tinygltf::Mesh &mesh = g_.meshes[g_.nodes[d.first].mesh];
            for (size_t p = 0; p < mesh.primitives.size(); ++p) {
                const Shape sh = shape(g_.nodes[d.first].mesh, static_cast<int>(p));
                points += sh.v.count;  // counts checked against their buffers: no overflow before the limit
                tris += sh.tris;
                if (points > kMaxElements || tris > kMaxElements)
                    fail(from + ": more than " + kLimit + " " + (points > kMaxElements ? "vertices" : "triangles") +
                         " with nodes[" + num(d.first) + "] (the limit; each instance of a mesh counts)");
            }
        }
        m_.points.reserve(points);
        m_.colors.reserve(points);
        m_.tris.reserve(tris);
        for (const auto &d : drawn) {
            const tinygltf::Mesh &mesh = g_.meshes[g_.nodes[d.first].mesh];
            for (size_t p = 0; p < mesh.primitives.size(); ++p)
                primitive(g_.nodes[d.first].mesh, static_cast<int>(p), d.second, d.first);
        }
    }

    Elements elements(int a, const std::string &at, const std::vector<int> &types, const std::vector<int> &ctypes) const {
        if (a < 0 || size_t(a) >= g_.accessors.size()) fail(at + ": " + missing("accessor", a, g_.accessors.size()));
        const tinygltf::Accessor &acc = g_.accessors[a];
        const std::string where = at + " (accessors[" + num(a) + "])";
        if (acc.sparse.isSparse) fail(where + ": sparse accessors are not supported");
        if (std::find(types.begin(), types.end(), acc.type) == types.end() ||
            std::find(ctypes.begin(), ctypes.end(), acc.componentType) == ctypes.end())
            fail(where + ": " + type_name(acc.type, acc.componentType, acc.normalized) + " is not one of the types allowed here");
        if (acc.bufferView < 0)
            fail(where + ": no bufferView (Draco-compressed or zero-filled data is not supported)");
        if (size_t(acc.bufferView) >= g_.bufferViews.size())
            fail(where + ": " + missing("bufferView", acc.bufferView, g_.bufferViews.size()));
        const tinygltf::BufferView &bv = g_.bufferViews[acc.bufferView];
        const std::string bvs = "bufferViews[" + num(acc.bufferView) + "]";
        if (bv.buffer < 0 || size_t(bv.buffer) >= g_.buffers.size())
            fail(bvs + ": " + missing("buffer", bv.buffer, g_.buffers.size()));
        const size_t have = g_.buffers[bv.buffer].data.size();
        if (bv.byteOffset > have || bv.byteLength > have - bv.byteOffset)
            fail(bvs + ": " + num(bv.byteLength) + " bytes from byte " + num(bv.byteOffset) + " run past the end of buffers[" +
                 num(bv.buffer) + "] (" + num(have) + " bytes)");
        Elements e;
        e.comps = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
        const size_t elem = size_t(e.comps) * size_t(tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType)));
        e.stride = bv.byteStride ? bv.byteStride : elem;
        if (e.stride < elem) fail(bvs + ": byteStride " + num(e.stride) + " is smaller than an element of " + where + " (" + num(elem) + " bytes)");
        e.count = acc.count;
        e.type = acc.componentType;
        e.normalized = acc.normalized;
        if (e.count > 0 && (acc.byteOffset > bv.byteLength || e.count > bv.byteLength ||
                            (e.count - 1) * e.stride + elem > bv.byteLength - acc.byteOffset))
            fail(where + ": " + num(e.count) + " elements of " + num(elem) + " bytes every " + num(e.stride) +
                 " bytes from byte " + num(acc.byteOffset) + " run past the end of " + bvs + " (" + num(bv.byteLength) + " bytes)");
        e.at = g_.buffers[bv.buffer].data.data() + bv.byteOffset + acc.byteOffset;
        return e;
    }

    static std::string type_name(int type, int ctype, bool normalized) {
        std::string t;
        switch (type) {
        case TINYGLTF_TYPE_SCALAR: t = "SCALAR"; break;
        case TINYGLTF_TYPE_VEC2: t = "VEC2"; break;
        case TINYGLTF_TYPE_VEC3: t = "VEC3"; break;
        case TINYGLTF_TYPE_VEC4: t = "VEC4"; break;
        default: t = "a matrix";
        }
        std::string c;
        switch (ctype) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: c = "byte"; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: c = "unsigned byte"; break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: c = "short"; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: c = "unsigned short"; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: c = "unsigned int"; break;
        case TINYGLTF_COMPONENT_TYPE_FLOAT: c = "float"; break;
        default: c = "component type " + std::to_string(ctype);
        }
        return t + " of " + (normalized ? "normalized " : "") + c;
    }

    // Component J of element I as a number: floats as they are, integers as themselves, or
    // normalized to 0..1 (the spec's formulas) when NORMALIZED.
    static double component(const Elements &e, size_t i, int j) {
        const unsigned char *p = e.at + i * e.stride;
        switch (e.type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p + 4 * j, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return e.normalized ? p[j] / 255.0 : p[j];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p + 2 * j, 2);
            return e.normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p + 4 * j, 4);
            return v;
        }
        default: return 0;  // not allowed by any caller
        }
    }

    static const int *attribute(const tinygltf::Primitive &p, const std::string &name) {
        auto it = p.attributes.find(name);
        return it == p.attributes.end() ? nullptr : &it->second;
    }

    // A primitive's checked accessors and triangle count (none for points and lines: skipped).
    struct Shape {
        bool drawn = false;
        Elements v, ie;  // POSITION; the indices when indexed (else ie.at is null)
        uint64_t n = 0, tris = 0;  // corners listed (indices, else vertices); triangles they make
    };

    Shape shape(int mi, int pi) const {
        const tinygltf::Primitive &p = g_.meshes[mi].primitives[pi];
        const std::string at = "meshes[" + num(mi) + "].primitives[" + num(pi) + "]";
        Shape sh;
        if (p.mode >= TINYGLTF_MODE_POINTS && p.mode <= TINYGLTF_MODE_LINE_STRIP) return sh;
        if (p.mode < TINYGLTF_MODE_TRIANGLES || p.mode > TINYGLTF_MODE_TRIANGLE_FAN)
            fail(at + ".mode: " + std::to_string(p.mode) + " is not a primitive mode (0..6)");
        sh.drawn = true;
        const int *pos = attribute(p, "POSITION");
        if (!pos) fail(at + ".attributes: no POSITION");
        sh.v = elements(*pos, at + ".attributes.POSITION", {TINYGLTF_TYPE_VEC3}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
        if (sh.v.normalized) fail(at + ".attributes.POSITION: normalized positions are not supported");
        sh.n = sh.v.count;
        if (p.indices >= 0) {
            sh.ie = elements(p.indices, at + ".indices", {TINYGLTF_TYPE_SCALAR},
                             {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
            sh.ie.normalized = false;  // indices are whole numbers whatever the flag says
            sh.n = sh.ie.count;
        }
        if (p.mode == TINYGLTF_MODE_TRIANGLES && sh.n % 3 != 0)
            fail(at + ": " + num(sh.n) + " " + (p.indices >= 0 ? "indices" : "vertices") + " do not make whole triangles");
        sh.tris = p.mode == TINYGLTF_MODE_TRIANGLES ? sh.n / 3 : sh.n >= 3 ? sh.n - 2 : 0;
        return sh;
    }

    void primitive(int mi, int pi, const Mat &world, int node) {
        const tinygltf::Primitive &p = g_.meshes[mi].primitives[pi];
        const std::string at = "meshes[" + num(mi) + "].primitives[" + num(pi) + "]";
        const Shape sh = shape(mi, pi);
        if (!sh.drawn) {
            ++skipped_prims_;
            return;
        }
        ++triangle_prims_;
        const std::string pos_at = at + ".attributes.POSITION";
        const Elements &v = sh.v;
        const uint64_t base = m_.points.size();

        // the vertices, transformed
        for (size_t i = 0; i < v.count; ++i) {
            double x[3];
            for (int j = 0; j < 3; ++j) {
                x[j] = component(v, i, j);
                if (!std::isfinite(x[j])) fail(pos_at + ": vertex " + num(i) + " has a coordinate that is not finite");
            }
            std::array<double, 3> q;
            for (int r = 0; r < 3; ++r) {
                const double w = world[r] * x[0] + world[4 + r] * x[1] + world[8 + r] * x[2] + world[12 + r];
                if (const char *why = bad_coordinate(w))
                    fail(pos_at + ": vertex " + num(i) + " under nodes[" + num(node) + "]'s transform: " + why + " (" + show(w) + ")");
                q[r] = static_cast<float>(w);
            }
            m_.points.push_back(q);
        }
        colours(p, at, v.count);

        // the faces
        const bool flip = det3(world) < 0;
        auto index = [&](size_t k) -> uint32_t {
            if (p.indices < 0) return static_cast<uint32_t>(base + k);
            const uint64_t i = static_cast<uint64_t>(component(sh.ie, k, 0));
            if (i >= v.count)
                fail(at + ".indices: index " + num(i) + " (element " + num(k) + ") is out of range (POSITION has " +
                     num(v.count) + " vertices)");
            return static_cast<uint32_t>(base + i);
        };
        const size_t tris = static_cast<size_t>(sh.tris);
        Faces faces(m_.tris);
        std::vector<uint32_t> c(3);
        for (size_t t = 0; t < tris; ++t) {
            if (p.mode == TINYGLTF_MODE_TRIANGLES) {
                c = {index(3 * t), index(3 * t + 1), index(3 * t + 2)};
            } else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                c = {index(t), index(t + 1 + t % 2), index(t + 2 - t % 2)};
            } else {
                c = {index(t + 1), index(t + 2), index(0)};
            }
            if (flip) std::swap(c[1], c[2]);
            faces.add(c);
        }
    }

    // The base colour of the primitive's N vertices just added (linear light, then sRGB bytes).
    void colours(const tinygltf::Primitive &p, const std::string &at, size_t n) {
        std::array<double, 3> factor = {1, 1, 1};
        const Texture *tex = nullptr;
        Elements uv;
        std::string uv_at;
        const std::string mat_at = "materials[" + std::to_string(p.material) + "].pbrMetallicRoughness";
        if (p.material >= 0) {
            if (size_t(p.material) >= g_.materials.size())
                fail(at + ".material: " + missing("material", p.material, g_.materials.size()));
            const tinygltf::PbrMetallicRoughness &pbr = g_.materials[p.material].pbrMetallicRoughness;
            const std::vector<double> &f = pbr.baseColorFactor;
            if (f.size() != 4) fail(mat_at + ".baseColorFactor has " + num(f.size()) + " numbers (4 expected)");
            for (int k = 0; k < 4; ++k)
                if (!(f[k] >= 0 && f[k] <= 1)) fail(mat_at + ".baseColorFactor[" + num(k) + "]: " + show(f[k]) + " is outside 0..1");
            factor = {f[0], f[1], f[2]};
            const tinygltf::TextureInfo &ti = pbr.baseColorTexture;
            if (ti.index >= 0) {
                const int *tc = attribute(p, "TEXCOORD_" + std::to_string(ti.texCoord));
                if (tc) tex = texture(ti.index, mat_at + ".baseColorTexture");
                if (tex) {
                    uv_at = at + ".attributes.TEXCOORD_" + std::to_string(ti.texCoord);
                    uv = elements(*tc, uv_at, {TINYGLTF_TYPE_VEC2},
                                  {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
                    same_count(uv, n, uv_at);
                }
            }
        }
        Elements c0;
        const int *col = attribute(p, "COLOR_0");
        if (col) {
            c0 = elements(*col, at + ".attributes.COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4},
                          {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
            same_count(c0, n, at + ".attributes.COLOR_0");
        }
        if (col || tex || factor != std::array<double, 3>{1, 1, 1}) coloured_ = true;
        for (size_t i = 0; i < n; ++i) {
            std::array<double, 3> c = factor;
            if (tex) {
                double st[2];
                for (int j = 0; j < 2; ++j) {
                    st[j] = component(uv, i, j);
                    if (!std::isfinite(st[j])) fail(uv_at + ": element " + num(i) + " is not finite");
                }
                const size_t x = texel(st[0], tex->w, tex->wrap_s), y = texel(st[1], tex->h, tex->wrap_t);
                const unsigned char *t = &tex->rgb[3 * (y * size_t(tex->w) + x)];
                for (int k = 0; k < 3; ++k) c[k] *= srgb_to_linear(t[k] / 255.0);
            }
            if (col)
                for (int k = 0; k < 3; ++k) {
                    const double v = component(c0, i, k);
                    if (!std::isfinite(v)) fail(at + ".attributes.COLOR_0: element " + num(i) + " is not finite");
                    c[k] *= std::clamp(v, 0.0, 1.0);
                }
            m_.colors.push_back({srgb_byte(c[0]), srgb_byte(c[1]), srgb_byte(c[2])});
        }
    }

    // Colours and texture coordinates: integers only normalized, one per vertex.
    void same_count(const Elements &e, size_t n, const std::string &at) const {
        if (e.type != TINYGLTF_COMPONENT_TYPE_FLOAT && !e.normalized) fail(at + ": integer values must be normalized");
        if (e.count != n) fail(at + ": " + num(e.count) + " elements, but POSITION has " + num(n));
    }

    // The texel column (or row) of coordinate S on a side of N texels: nearest, after the wrap.
    static size_t texel(double s, int n, int wrap) {
        double u = s;
        if (wrap == TINYGLTF_TEXTURE_WRAP_REPEAT) {
            u = s - std::floor(s);
        } else if (wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) {
            u = s - 2 * std::floor(s / 2);  // 0..2
            if (u > 1) u = 2 - u;
        }
        const double k = std::floor(u * n);
        return static_cast<size_t>(std::clamp(k, 0.0, double(n - 1)));
    }

    // Texture T decoded (once), or nullptr when it names no image (an extension's source).
    const Texture *texture(int t, const std::string &at) {
        if (size_t(t) >= g_.textures.size()) fail(at + ".index: " + missing("texture", t, g_.textures.size()));
        auto done = textures_.find(t);
        if (done != textures_.end()) return &done->second;
        const tinygltf::Texture &gt = g_.textures[t];
        const std::string tat = "textures[" + num(t) + "]";
        if (gt.source < 0) return nullptr;
        if (size_t(gt.source) >= g_.images.size()) fail(tat + ".source: " + missing("image", gt.source, g_.images.size()));
        Texture tex;
        if (gt.sampler >= 0) {
            if (size_t(gt.sampler) >= g_.samplers.size()) fail(tat + ".sampler: " + missing("sampler", gt.sampler, g_.samplers.size()));
            const tinygltf::Sampler &s = g_.samplers[gt.sampler];
            const std::string sat = "samplers[" + num(gt.sampler) + "]";
            tex.wrap_s = wrap(s.wrapS, sat + ".wrapS");
            tex.wrap_t = wrap(s.wrapT, sat + ".wrapT");
        }
        decode(gt.source, tex);
        return &textures_.emplace(t, std::move(tex)).first->second;
    }

    int wrap(int w, const std::string &at) const {
        if (w != TINYGLTF_TEXTURE_WRAP_REPEAT && w != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE &&
            w != TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT)
            fail(at + ": " + std::to_string(w) + " is not a wrap mode (33071, 33648, 10497)");
        return w;
    }

    void decode(int i, Texture &tex) const {
        const tinygltf::Image &img = g_.images[i];
        const std::string at = "images[" + num(i) + "]";
        const unsigned char *bytes = nullptr;
        size_t size = 0;
        if (img.bufferView >= 0) {
            const tinygltf::BufferView &bv = g_.bufferViews[img.bufferView];  // tinygltf checked both indices
            const size_t have = g_.buffers[bv.buffer].data.size();
            if (bv.byteOffset > have || bv.byteLength > have - bv.byteOffset)
                fail(at + ": bufferViews[" + num(img.bufferView) + "] runs past the end of buffers[" + num(bv.buffer) + "]");
            bytes = g_.buffers[bv.buffer].data.data() + bv.byteOffset;
            size = bv.byteLength;
        } else {
            auto it = files_.images.find(i);
            if (it == files_.images.end()) fail(at + ": no image data");
            bytes = it->second.data();
            size = it->second.size();
        }
        // glTF 2.0 allows PNG and JPEG. A texel needs at least one bit of a PNG's deflated data
        // (1-bit depth; deflate expands at most 1032 times) and a 64th of a bit of a JPEG's (one
        // code per 8x8 block): more texels than that is a header that lies.
        const bool png = size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
        const bool jpeg = size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
        if (!png && !jpeg) fail(at + ": neither PNG nor JPEG (the image formats of glTF 2.0)");
        if (size > size_t(INT32_MAX)) fail(at + ": larger than " + num(INT32_MAX) + " bytes");
        int w = 0, h = 0, comp = 0;
        if (!stbi_info_from_memory(bytes, static_cast<int>(size), &w, &h, &comp))
            fail(at + ": cannot read the image header (stb_image: " + stb_reason() + ")");
        const uint64_t texels = uint64_t(w) * uint64_t(h);
        if (w <= 0 || h <= 0 || texels > kMaxTexels)
            fail(at + ": " + std::to_string(w) + " x " + std::to_string(h) + " texels (at most " + num(kMaxTexels) + ")");
        if (texels > (png ? 8 * 1032 : 512) * uint64_t(size))
            fail(at + ": " + std::to_string(w) + " x " + std::to_string(h) + " texels cannot be coded in " + num(size) + " bytes");
        unsigned char *rgb = stbi_load_from_memory(bytes, static_cast<int>(size), &w, &h, &comp, 3);
        if (!rgb) fail(at + ": cannot decode (stb_image: " + stb_reason() + ")");
        tex.w = w;
        tex.h = h;
        tex.rgb.assign(rgb, rgb + size_t(w) * size_t(h) * 3);
        stbi_image_free(rgb);
    }

    std::string path_;
    const tinygltf::Model &g_;
    const Files &files_;
    Model m_;
    std::map<int, Texture> textures_;
    size_t triangle_prims_ = 0, skipped_prims_ = 0;
    bool coloured_ = false;
};

}  // namespace

Model read_gltf(const std::string &path, uint64_t size) {
    const std::vector<unsigned char> file = read_all(path, size);
    const bool glb = path.size() >= 4 && lower(path.substr(path.size() - 4)) == ".glb";
    Chunk json{0, file.size()};
    if (glb) {
        json = glb_container(path, file);
    } else if (file.size() >= 4 && std::memcmp(file.data(), "glTF", 4) == 0) {
        fail_byte(path, 0, "this is a binary glTF (GLB), not JSON: name it .glb");
    }
    scan_json(path, file, json, glb);

    Files files;
    const size_t slash = path.find_last_of('/');
    files.base = slash == std::string::npos ? "" : slash == 0 ? "/" : path.substr(0, slash);
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&file_exists, &expand_path, &read_file, &write_file, &files});
    loader.SetImageLoader(&keep_image, &files);
    tinygltf::Model g;
    std::string err, warn;
    bool ok = false;
    try {
        ok = glb ? loader.LoadBinaryFromMemory(&g, &err, &warn, file.data(), static_cast<unsigned int>(file.size()), files.base)
                 : loader.LoadASCIIFromString(&g, &err, &warn, reinterpret_cast<const char *>(file.data()),
                                              static_cast<unsigned int>(file.size()), files.base);
    } catch (const std::bad_alloc &) {
        throw;
    } catch (const std::exception &e) {  // e.g. std::out_of_range from a buffer of byteLength 0
        fail_none(path, "tinygltf: " + clean(e.what()));
    }
    if (!ok || !err.empty() || !warn.empty())
        fail_none(path, "tinygltf: " + clean(!err.empty() ? err : !warn.empty() ? warn : "cannot load the file"));
    return Builder(path, g, files).run();
}

}  // namespace mc::input
