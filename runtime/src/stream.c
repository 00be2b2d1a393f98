/* Streamed bakes: see modelc/stream.h for the format and what the reader promises. This file frames
 * the records and reads the octree's; stream_mesh.c reads the mesh's. */
#include "stream_mesh.h"
#include "modelc/bits.h"

#define KIND_PALETTE MC_STREAM_KIND_PALETTE
#define KIND_LEVEL MC_STREAM_KIND_LEVEL
#define KIND_END MC_STREAM_KIND_END
#define CONE_BYTES 7   /* octree.h */

/* CRC-32 a nibble at a time: a 64-byte table, since a stream is checked once as it arrives */
static const uint32_t crc_nibble[16] = {
    0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u, 0x4DB26158u, 0x5005713Cu,
    0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu, 0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};

uint32_t mc_stream_crc32(uint32_t crc, const uint8_t *p, uint32_t n)
{
    crc = ~crc;
    for (uint32_t i = 0; i < n; i++) {
        crc ^= p[i];
        crc = (crc >> 4) ^ crc_nibble[crc & 15u];
        crc = (crc >> 4) ^ crc_nibble[crc & 15u];
    }
    return ~crc;
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static uint32_t le16(const uint8_t *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8; }

void mc_stream_init(mc_stream *s, uint8_t *buf, uint32_t cap)
{
    uint8_t *z = (uint8_t *)s;
    for (uint32_t i = 0; i < sizeof *s; i++) z[i] = 0;   /* freestanding: no memset */
    s->buf = buf;
    s->cap = buf ? cap : 0;
}

/* The descriptor of levels 0..d (d = levels_read - 1 >= 1), pointing into the buffer. */
static void describe(mc_stream *s)
{
    const unsigned d = s->levels_read - 1;
    for (unsigned l = 0; l <= d; l++) {
        mc_octree_level *lv = &s->level[l];
        const uint32_t at[3] = {l < d ? s->masks_at[l] : 0, s->colors_at[l], l + 3 <= d ? s->cones_at[l] : 0};
        const uint32_t bytes[3] = {s->nodes[l], s->nodes[l], CONE_BYTES * s->nodes[l]};
        const mc_chunk **list[3] = {&lv->masks, &lv->colors, &lv->cones};
        for (unsigned k = 0; k < 3; k++) {
            mc_chunk *c = s->chunks[l][k];
            c[0].data = s->buf + at[k];
            c[0].size = bytes[k];
            c[1].data = 0;
            c[1].size = 0;
            *list[k] = at[k] ? c : 0;
        }
        lv->nodes = s->nodes[l];
    }
    s->octree.depth = (uint8_t)d;
    s->octree.palette_size = s->palette_size;
    s->octree.palette = s->buf + s->palette_at;
    s->octree.levels = s->level;
}

/* The cones of level l (read with level l+3's record) against the masks of levels l .. l+2: each
 * record's n2 and n3 are the nodes two and three levels below it, which is what the renderer steps
 * over when it culls the node. */
static int check_cones(mc_stream *s, unsigned l, uint32_t at_record)
{
    const uint8_t *cone = s->buf + s->cones_at[l];
    const uint8_t *m0 = s->buf + s->masks_at[l], *m1 = s->buf + s->masks_at[l + 1], *m2 = s->buf + s->masks_at[l + 2];
    uint32_t i1 = 0, i2 = 0;   /* the next node of levels l+1 and l+2 */
    for (uint32_t i = 0; i < s->nodes[l]; i++, cone += CONE_BYTES) {
        uint32_t n2 = 0, n3 = 0;
        for (unsigned c1 = mc_popcount8(m0[i]); c1; c1--, i1++) {
            const unsigned c2 = mc_popcount8(m1[i1]);
            n2 += c2;
            for (unsigned k = 0; k < c2; k++, i2++) n3 += mc_popcount8(m2[i2]);
        }
        if (cone[4] != n2 || le16(cone + 5) != n3) return mc_stream_fail(s, MC_STREAM_ERR_CONE, at_record);
    }
    return MC_STREAM_OK;
}

/* A level record's payload p (n bytes at offset at in buf) for level l. */
static int level_record(mc_stream *s, unsigned l, uint32_t at, uint32_t n, uint32_t at_record)
{
    const unsigned D = s->depth;
    if (n < 4) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at_record);
    const uint32_t nodes = le32(s->buf + at);
    /* the node count the masks above say */
    uint32_t expect = 1;
    if (l > 0) {
        const uint8_t *m = s->buf + s->masks_at[l - 1];
        expect = 0;
        for (uint32_t i = 0; i < s->nodes[l - 1]; i++) expect += mc_popcount8(m[i]);
    }
    if (nodes != expect) return mc_stream_fail(s, MC_STREAM_ERR_NODES, at_record);
    const uint32_t masks = l < D ? nodes : 0, colors = l >= 1 && s->palette_size > 1 ? nodes : 0;
    const uint64_t base = 4u + (uint64_t)masks + colors;
    const int cones = l >= 4 && n == base + (uint64_t)CONE_BYTES * s->nodes[l - 3];   /* level l-3's */
    if (n != base && !cones) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at_record);
    s->nodes[l] = nodes;
    s->masks_at[l] = masks ? at + 4 : 0;
    s->colors_at[l] = colors ? at + 4 + masks : 0;
    if (cones) s->cones_at[l - 3] = at + 4 + masks + colors;
    const uint8_t *m = s->buf + at + 4, *c = m + masks;
    for (uint32_t i = 0; i < masks; i++)
        if (!m[i]) return mc_stream_fail(s, MC_STREAM_ERR_VALUE, at + 4 + i);
    for (uint32_t i = 0; i < colors; i++)
        if (c[i] >= s->palette_size) return mc_stream_fail(s, MC_STREAM_ERR_VALUE, at + 4 + masks + i);
    if (cones && check_cones(s, l - 3, at_record)) return s->error;
    s->levels_read = l + 1;
    if (l >= 1) describe(s);
    return MC_STREAM_OK;
}

static int header(mc_stream *s)
{
    const uint8_t *h = s->buf;
    if (h[0] != 'm' || h[1] != 'c' || h[2] != 's' || h[3] != 0x1A) return mc_stream_fail(s, MC_STREAM_ERR_MAGIC, 0);
    if (mc_stream_crc32(0, h, 16) != le32(h + 16)) return mc_stream_fail(s, MC_STREAM_ERR_CRC, 0);
    const unsigned version = le16(h + 4);
    if (version < 1 || version > MC_STREAM_VERSION) return mc_stream_fail(s, MC_STREAM_ERR_VERSION, 4);
    const unsigned depth = h[6], palette = le16(h + 8);
    const uint32_t total = le32(h + 12);
    if (depth < 1 || depth > MC_MAX_DEPTH || h[7] != (version >= 2 ? 1 : 0) || palette < 1 || palette > 256 ||
        le16(h + 10) != 0 ||
        total < MC_STREAM_HEADER_BYTES + 2 * MC_STREAM_RECORD_BYTES)
        return mc_stream_fail(s, MC_STREAM_ERR_HEADER, 6);
    if (total > s->cap) return mc_stream_fail(s, MC_STREAM_ERR_SIZE, 12);
    s->depth = (uint8_t)depth;
    s->version = (uint8_t)version;
    s->has_mesh = version >= 2;
    s->palette_size = (uint16_t)palette;
    s->total = total;
    s->at = MC_STREAM_HEADER_BYTES;
    return MC_STREAM_OK;
}

/* Checks the next record if all of it is in the buffer; 1 when it did, 0 when more bytes are needed. */
static int next_record(mc_stream *s)
{
    const uint32_t r = s->at;
    /* every record ends within the total, and the last one there is the end record */
    if ((uint64_t)r + MC_STREAM_RECORD_BYTES > s->total) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, r), 1;
    if (s->len - r < 8) return 0;
    const uint8_t *h = s->buf + r;
    const unsigned kind = h[0], level = h[1];
    const uint32_t n = le32(h + 4);
    if (n > s->total - r - MC_STREAM_RECORD_BYTES) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, r), 1;
    if (s->len - r < n + MC_STREAM_RECORD_BYTES) return 0;
    if (mc_stream_crc32(0, h, 8 + n) != le32(h + 8 + n)) return mc_stream_fail(s, MC_STREAM_ERR_CRC, r), 1;
    if (le16(h + 2) != 0) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, r), 1;
    const int palette_read = s->palette_at != 0;
    if (kind == KIND_PALETTE && !palette_read && level == 0 && n == 3u * s->palette_size) {
        s->palette_at = r + 8;
    } else if (kind == KIND_LEVEL && palette_read && level == s->levels_read && level <= s->depth) {
        if (level_record(s, level, r + 8, n, r)) return 1;
    } else if (kind == KIND_END && level == 0 && n == 0 && s->levels_read == s->depth + 1u &&
               (!s->has_mesh || s->mesh_state == 3) && r + MC_STREAM_RECORD_BYTES == s->total) {
        s->ended = 1;
    } else if (kind >= MC_STREAM_KIND_MESH && kind <= MC_STREAM_KIND_PACKED_ADJACENCY && level == 0) {
        if (mc_stream_mesh_record(s, kind, r + 8, n, r)) return 1;
    } else {
        return mc_stream_fail(s, MC_STREAM_ERR_RECORD, r), 1;
    }
    s->at = r + MC_STREAM_RECORD_BYTES + n;
    return 1;
}

int mc_stream_feed(mc_stream *s, const uint8_t *data, uint32_t n)
{
    if (!s) return MC_STREAM_ERR_ARG;
    if (s->error) return s->error;
    if (!s->buf || (!data && n)) return mc_stream_fail(s, MC_STREAM_ERR_ARG, s->len);
    while (n > 0) {
        if (s->ended) return mc_stream_fail(s, MC_STREAM_ERR_TRAILING, s->len);
        /* take no more than the header, or than the stream's total once it is known */
        const uint32_t limit = s->total ? s->total : MC_STREAM_HEADER_BYTES;
        if (s->len >= limit) return mc_stream_fail(s, MC_STREAM_ERR_TRAILING, s->len);
        uint32_t take = limit - s->len;
        if (take > n) take = n;
        if (take > s->cap - s->len) return mc_stream_fail(s, MC_STREAM_ERR_SIZE, s->len);
        for (uint32_t i = 0; i < take; i++) s->buf[s->len + i] = data[i];
        s->len += take;
        data += take;
        n -= take;
        if (!s->total) {
            if (s->len < MC_STREAM_HEADER_BYTES) continue;
            if (header(s)) return s->error;
        }
        while (!s->ended && next_record(s))
            if (s->error) return s->error;
    }
    return MC_STREAM_OK;
}

int mc_stream_end(mc_stream *s)
{
    if (!s) return MC_STREAM_ERR_ARG;
    if (s->error) return s->error;
    return s->ended ? MC_STREAM_OK : mc_stream_fail(s, MC_STREAM_ERR_TRUNCATED, s->len);
}

unsigned mc_stream_depth(const mc_stream *s) { return s && s->levels_read >= 2 ? s->levels_read - 1 : 0; }

const mc_octree *mc_stream_octree(const mc_stream *s) { return mc_stream_depth(s) ? &s->octree : 0; }

const char *mc_stream_error_name(int error)
{
    static const char *const names[] = {"ok",     "magic",  "version", "header",   "size",      "crc",
                                        "record", "nodes",  "value",   "cone",     "trailing",  "truncated",
                                        "arg",    "mesh"};
    return error <= 0 && error >= MC_STREAM_ERR_MESH ? names[-error] : "unknown";
}
