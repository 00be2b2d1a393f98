/* A version-3 stream's packed splits (modelc/stream.h, kind 8), decoded into the same mesh arrays a
 * version-2 stream's plain splits fill.
 *
 * The decoder keeps the mesh of the level it has reached, in the buffer after those arrays: each
 * face corner's vertex at the level, and per vertex the list of its corners. That is what lets the
 * stream leave out what it implies: the split vertex (its parent's next child in depth-first order),
 * a new face's third corner (a rank among the parent's neighbours) and most of each position's bits
 * (a difference to the mean of the new vertex's neighbours). Work per split: the parent's and the
 * new vertex's corners, times the rank plus one for the third corner of each new face. */
#include <stdint.h>
#include "stream_mesh.h"

#define NONE 0xFFFFFFFFu

static uint32_t le(const uint8_t *p, unsigned bytes) { return mc_le_index(p, bytes); }

/* Bits of an offset below n (0 for n <= 1). */
static unsigned width(uint32_t n)
{
    unsigned b = 0;
    while (b < 32 && ((uint64_t)1 << b) < n) b++;
    return b;
}

/* Bits, most significant first within each byte; reading past the end marks the reader bad. */
typedef struct {
    const uint8_t *p;
    uint32_t bits, at;   /* bits in p, the next one */
    int bad;
} bit_reader;

static uint32_t get(bit_reader *b, unsigned n)
{
    if (n > b->bits - b->at) {
        b->bad = 1;
        return 0;
    }
    uint32_t v = 0;
    while (n) {   /* a byte's worth at a time */
        const unsigned left = 8u - (b->at & 7u), take = n < left ? n : left;
        v = (uint32_t)((uint64_t)v << take) | (uint32_t)(b->p[b->at >> 3] >> (left - take) & ((1u << take) - 1u));
        b->at += take, n -= take;
    }
    return v;
}

/* Exp-Golomb of order k: z zeros, a one, then z + k bits; the value is what they spell less 2^k. */
static uint32_t exp_golomb(bit_reader *b, unsigned k)
{
    unsigned z = 0;
    while (!get(b, 1)) {
        if (b->bad || ++z + k > 31) {
            b->bad = 1;
            return 0;
        }
    }
    const unsigned n = z + k;
    return (((uint32_t)1 << n) | get(b, n)) - ((uint32_t)1 << k);
}

/* The mesh arrays' fields (stream_mesh.h). */
static uint8_t *positions(mc_stream *s) { return mc_stream_array(s, 0); }
static uint32_t size_of(mc_stream *s, uint32_t v) { return le(mc_stream_tree(s, v), s->pmesh.index_bytes); }
static uint8_t *corner_at(mc_stream *s, uint32_t c)
{
    return mc_stream_array(s, 3) + c * s->pmesh.index_bytes;   /* c = 3 f + k */
}

static void push(mc_stream *s, uint32_t u, uint32_t c)
{
    s->pk_level[c] = u;
    s->pk_next[c] = s->pk_head[u];
    s->pk_head[u] = c;
}

void mc_stream_packed_start(mc_stream *s, uint8_t *area)
{
    const uint32_t V = s->pmesh.vertices, F = s->pmesh.faces;
    uint32_t *w = (uint32_t *)(void *)(area + ((4u - ((uintptr_t)area & 3u)) & 3u));
    s->pk_level = w, w += 3u * F;
    s->pk_next = w, w += 3u * F;
    s->pk_head = w, w += V;
    s->pk_slot = w, w += V;
    s->pk_stamp = w;
    for (uint32_t v = 0; v < V; v++) s->pk_head[v] = NONE, s->pk_slot[v] = v + 1u, s->pk_stamp[v] = 0;
    s->pk_now = 0;
}

void mc_stream_packed_base(mc_stream *s, const uint8_t *roots, uint32_t per)
{
    const mc_pmesh *pm = &s->pmesh;
    const unsigned ib = pm->index_bytes;
    for (uint32_t c = 0; c < 3u * pm->base_faces; c++) {
        const uint32_t full = le(corner_at(s, c), ib);
        uint32_t lo = 0, hi = pm->base_vertices;   /* the last root at or before full */
        while (hi - lo > 1) {
            const uint32_t mid = lo + (hi - lo) / 2;
            if (le(roots + mid * per, ib) <= full) lo = mid;
            else hi = mid;
        }
        push(s, le(roots + lo * per, ib), c);
    }
}

/* The distinct vertices that share a face with u at the level: with sum, their positions' sums; with
 * list, all of them in index order when there are at most RING_LIST. */
#ifndef MC_STREAM_RING_LIST   /* a test hook: small values send every rank through the passes */
#define MC_STREAM_RING_LIST 32
#endif
#define RING_LIST MC_STREAM_RING_LIST
static uint32_t ring(mc_stream *s, uint32_t u, uint64_t sum[3], uint32_t list[RING_LIST])
{
    const uint32_t now = ++s->pk_now;
    uint32_t n = 0;
    if (sum) sum[0] = sum[1] = sum[2] = 0;
    for (uint32_t c = s->pk_head[u]; c != NONE; c = s->pk_next[c]) {
        const uint32_t f = c / 3u * 3u;
        for (uint32_t k = f; k < f + 3u; k++) {
            const uint32_t w = s->pk_level[k];
            if (w == u || s->pk_stamp[w] == now) continue;
            s->pk_stamp[w] = now;
            if (list && n < RING_LIST) {   /* insertion, while the list has room */
                uint32_t i = n;
                for (; i > 0 && list[i - 1] > w; i--) list[i] = list[i - 1];
                list[i] = w;
            }
            n++;
            if (sum)
                for (unsigned a = 0; a < 3; a++) sum[a] += mc_le16(positions(s) + 6u * w + 2u * a);
        }
    }
    return n;
}

/* u's neighbour of the given rank in index order (rank < the ring's size), for rings longer than
 * RING_LIST: rank + 1 passes, each taking the least neighbour above the last. */
static uint32_t neighbour(const mc_stream *s, uint32_t u, uint32_t rank)
{
    uint32_t last = 0, x = 0;
    for (uint32_t r = 0; r <= rank; r++) {
        x = NONE;
        for (uint32_t c = s->pk_head[u]; c != NONE; c = s->pk_next[c]) {
            const uint32_t f = c / 3u * 3u;
            for (uint32_t k = f; k < f + 3u; k++) {
                const uint32_t w = s->pk_level[k];
                if (w != u && (r == 0 || w > last) && (x == NONE || w < x)) x = w;
            }
        }
        last = x;
    }
    return x;
}

int mc_stream_packed_splits(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at)
{
    const mc_pmesh *pm = &s->pmesh;
    const unsigned ib = pm->index_bytes, wv = width(pm->vertices);
    const uint32_t S = pm->vertices - pm->base_vertices;
    if (n < 9) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at - 8);
    const uint32_t first = le(p, 4), k = le(p + 4, 4);
    const unsigned order = p[8];
    if (first != s->splits_read || k < 1 || k > S - first || order > 16) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at);
    bit_reader b = {p + 9, 8u * (n - 9u), 0, 0};
    uint32_t faces = s->faces_read;
#define FAIL_AT() mc_stream_fail(s, b.bad ? MC_STREAM_ERR_RECORD : MC_STREAM_ERR_MESH, at + 9u + b.at / 8u)
    for (uint32_t i = 0; i < k; i++) {
        /* the parent, present; the vertex its next child; the vertex's subtree inside the parent's */
        const uint32_t parent = get(&b, wv);
        if (b.bad || parent >= pm->vertices) return FAIL_AT();
        const uint32_t psize = size_of(s, parent), v = s->pk_slot[parent];
        if (psize == 0 || v - parent >= psize) return FAIL_AT();
        const uint32_t size = exp_golomb(&b, 0) + 1u, nf = get(&b, 1) + 1u;
        if (b.bad || size > psize - (v - parent) || nf > pm->faces - faces || size_of(s, v) != 0)
            return FAIL_AT();
        uint32_t list[RING_LIST];
        const uint32_t around = ring(s, parent, 0, list);
        mc_stream_put(mc_stream_tree(s, v), size, ib);
        /* the new faces: v, the parent and a neighbour of the parent at the split's level, each corner
         * then the full mesh's vertex at that offset in its subtree (the parent's outside v's, which
         * is what a collapse reads the parent from: pmesh.h) */
        uint32_t at_level[2][3];
        for (uint32_t j = 0; j < nf; j++) {
            const uint32_t parent_first = get(&b, 1), rank = get(&b, width(around));
            if (b.bad || rank >= around) return FAIL_AT();
            uint32_t *a = at_level[j];
            a[0] = parent_first ? parent : v, a[1] = parent_first ? v : parent, a[2] = around <= RING_LIST ? list[rank] : neighbour(s, parent, rank);
            for (unsigned c = 0; c < 3; c++) {
                const uint32_t sz = size_of(s, a[c]), off = get(&b, width(sz));
                if (b.bad || off >= sz || (a[c] == parent && a[c] + off - v < size)) return FAIL_AT();
                mc_stream_put(corner_at(s, 3u * (faces + j) + c), a[c] + off, ib);
            }
        }
        /* the split: the parent's corners whose full-mesh vertex is in v's subtree go to v */
        for (uint32_t *link = &s->pk_head[parent]; *link != NONE;) {
            const uint32_t c = *link;
            if (le(corner_at(s, c), ib) - v < size) {
                *link = s->pk_next[c];
                push(s, v, c);
            } else {
                link = &s->pk_next[c];
            }
        }
        for (uint32_t j = 0; j < nf; j++, faces++)
            for (unsigned c = 0; c < 3; c++) push(s, at_level[j][c], 3u * faces + c);
        /* the position: the rounded mean of v's neighbours after the split, plus the difference */
        uint64_t sum[3];
        const uint32_t m = ring(s, v, sum, 0);
        if (m == 0) return FAIL_AT();   /* never: the new faces give v two neighbours */
        for (unsigned a = 0; a < 3; a++) {
            const uint32_t u = exp_golomb(&b, order);
            const int64_t q = (int64_t)((sum[a] + m / 2u) / m) + ((u & 1u) ? -(int64_t)(u >> 1) - 1 : (int64_t)(u >> 1));
            if (b.bad || q < 0 || q > 65535) return FAIL_AT();
            mc_stream_put(positions(s) + 6u * v + 2u * a, (uint32_t)q, 2);
        }
        s->pk_slot[parent] = v + size;
        mc_stream_put_split(s, first + i, v, nf);
    }
    /* the record ends within a byte of the last split, its padding zero */
    if (b.bits - b.at >= 8u || (b.at < b.bits && get(&b, b.bits - b.at) != 0)) return FAIL_AT();
#undef FAIL_AT
    s->splits_read += k;
    s->faces_read = faces;
    return MC_STREAM_OK;
}

int mc_stream_packed_adjacency(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at)
{
    const mc_pmesh *pm = &s->pmesh;
    const unsigned ib = pm->index_bytes, hb = pm->half_bytes;
    const uint32_t F = pm->faces, E = pm->edges, w = width(3u * F);
    if (s->splits_read != pm->vertices - pm->base_vertices || s->faces_read != F || n != ((uint64_t)E * w + 7u) / 8u)
        return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at - 8);
    if (E > 3u * F) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at - 8);
    /* the opposites: the half-edge back along each edge, found among the corners at its end; written
     * over the corners' levels, which the full mesh no longer needs (3 F entries of 4 bytes) */
    uint8_t *opposite = (uint8_t *)s->pk_level;
    for (uint32_t c = 0; c < 3u * F; c++) {
        const uint32_t f = c / 3u, k = c - 3u * f;
        const uint32_t a = le(corner_at(s, c), ib), b = le(corner_at(s, 3u * f + (k == 2u ? 0u : k + 1u)), ib);
        uint32_t o = hb == 2 ? 0xFFFFu : MC_NO_HALF_EDGE;
        for (uint32_t d = s->pk_head[b]; d != NONE; d = s->pk_next[d]) {   /* d: corner j of face g, at b */
            const uint32_t g = d / 3u, j = d - 3u * g;
            if (le(corner_at(s, 3u * g + (j == 2u ? 0u : j + 1u)), ib) == a) {
                o = MC_HALF_EDGE(g, j);
                break;
            }
        }
        mc_stream_put(opposite + c * hb, o, hb);
    }
    /* the edge order, over the corners' lists (E <= 3 F entries of 4 bytes) */
    uint8_t *order = (uint8_t *)s->pk_next;
    bit_reader b = {p, 8u * n, 0, 0};
    for (uint32_t e = 0; e < E; e++) {
        const uint32_t x = get(&b, w);
        if (x >= 3u * F) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at + e * w / 8u);
        mc_stream_put(order + e * hb, MC_HALF_EDGE(x / 3u, x % 3u), hb);
    }
    if (b.at < b.bits && get(&b, b.bits - b.at) != 0) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at + n - 1u);
    return mc_stream_adjacency(s, opposite, order, at, 0);
}
