/* pmesh.h's level of detail against a naive reference, on synthetic progressive meshes built here
 * the way the generator lays them out (no generator needed):
 *   - a random forest of collapses: V0 roots, every other vertex with a parent split before it, in a
 *     random split order; vertices numbered depth-first (roots in order, children in the order of
 *     their splits), so subtree(v) = [v, v + size(v)); arrays chunked as indexed records (chunk.h),
 *     each chunk its own allocation (so the sanitizers see a read past a chunk), with small
 *     record_shift (0, 1, 3: many chunk boundaries) and index_bytes 2 and 4;
 *   - the reference: at level n, vertex v stands for its nearest ancestor-or-self of rank < n (a root
 *     has rank < V0, the vertex of split s rank V0 + s), found by walking up the parents; F(n) is F0
 *     plus the first n - V0 face counts; a face's corners are its stored corners so mapped; a position
 *     is q - 32768;
 *   - checked: init is the base level; random level changes (clamped below V0 and above V, single
 *     steps, big jumps, the same level) on many small meshes, the whole map and every face after each;
 *     1e5 changes on a mesh of a few thousand vertices, whose whole ancestor memory is compared after
 *     each with that of a second state freshly initialised and set straight to the same level (the
 *     promise: the same bytes however the level was reached; made once per level, and again now and
 *     then), plus sampled vertices and faces against the reference, and the whole map every 64
 *     changes (and 2e4 such changes with index_bytes 4 and deeper trees); the degenerate forests
 *     V0 = V (no splits) and V0 = 1 (one tree); indices above 65535 with index_bytes 4.
 * The corners are random vertices, but for the layout's rule that a collapse reads the parent from:
 * each split's first face has as corners 0 and 1 a vertex of the split vertex's subtree and the
 * parent, in either order. The distinct-corner promise needs real meshes (the generator's tests
 * check it); here only the mapping is checked. PCG32 with fixed seeds: runs are deterministic.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <modelc/chunk.h>
#include <modelc/pmesh.h>
#include <modelc/rng.h>

/* A synthetic progressive mesh: the reference's view (plain arrays by vertex index) and the
 * runtime's (chunked little-endian records). */
typedef struct mesh {
    uint32_t V, V0, F, F0;
    unsigned ib, shift;
    uint32_t *parent, *size, *rank;   /* by vertex index; a root is its own parent */
    uint32_t *split_vertex;           /* by split */
    uint8_t *split_faces;             /* by split: 1 or 2 */
    uint32_t *faces_at;               /* by level - V0: F(level), F0 plus the first face counts */
    uint32_t *corner;                 /* 3 per face */
    uint16_t *pos;                    /* 3 per vertex */
    mc_chunk *positions, *tree, *splits, *corners, *split_bits;
    mc_pmesh pm;
} mesh;

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    assert_non_null(p);
    return p;
}

static void put_le(uint8_t *p, uint32_t v, unsigned bytes)
{
    for (unsigned k = 0; k < bytes; k++) p[k] = (uint8_t)(v >> (8 * k));
}

/* count records of rsize bytes, chunks of exactly 2^shift records but the last, each chunk copied
 * into its own allocation of exactly its size, then the {0, 0} sentinel */
static mc_chunk *chunk_records(const uint8_t *bytes, uint32_t count, uint32_t rsize, unsigned shift)
{
    const uint32_t per = UINT32_C(1) << shift, n = (count + per - 1) / per;
    mc_chunk *list = xmalloc((n + 1) * sizeof *list);
    for (uint32_t c = 0; c < n; c++) {
        const uint32_t recs = count - c * per < per ? count - c * per : per;
        uint8_t *d = xmalloc((size_t)recs * rsize);
        memcpy(d, bytes + (size_t)c * per * rsize, (size_t)recs * rsize);
        list[c].data = d;
        list[c].size = recs * rsize;
    }
    list[n].data = NULL;
    list[n].size = 0;
    return list;
}

/* pmesh.h's split_faces bits of count splits (faces: 1 or 2 each), chunked as chunk_records chunks
 * (each chunk 2^shift bits in its own allocation of (2^shift + 7) / 8 bytes, the last only its own
 * bits' bytes) */
static mc_chunk *chunk_bits(const uint8_t *faces, uint32_t count, unsigned shift)
{
    const uint32_t per = UINT32_C(1) << shift, n = (count + per - 1) / per;
    mc_chunk *list = xmalloc((n + 1) * sizeof *list);
    for (uint32_t c = 0; c < n; c++) {
        const uint32_t bits = count - c * per < per ? count - c * per : per;
        uint8_t *d = xmalloc((bits + 7) / 8);
        memset(d, 0, (bits + 7) / 8);
        for (uint32_t i = 0; i < bits; i++)
            if (faces[c * per + i] == 2) d[i >> 3] |= (uint8_t)(1u << (i & 7));
        list[c].data = d;
        list[c].size = (bits + 7) / 8;
    }
    list[n].data = NULL;
    list[n].size = 0;
    return list;
}

static void free_chunks(mc_chunk *list)
{
    for (mc_chunk *c = list; c->data; c++) free((void *)c->data);
    free(list);
}

/* chain: out of 8, how often a split's parent is one of the 4 vertices split just before it (deep
 * trees) rather than any earlier vertex (bushy ones) */
static void mesh_build(mesh *m, mc_rng *r, uint32_t V, uint32_t V0, uint32_t F0, unsigned ib, unsigned shift,
                       unsigned chain)
{
    memset(m, 0, sizeof *m);
    m->V = V;
    m->V0 = V0;
    m->F0 = F0;
    m->ib = ib;
    m->shift = shift;

    /* the forest by rank (rank = split order: roots 0 .. V0-1, split s is V0 + s) */
    uint32_t *plabel = xmalloc(V * sizeof *plabel), *sz = xmalloc(V * sizeof *sz);
    for (uint32_t i = 0; i < V; i++) {
        if (i < V0) plabel[i] = i;
        else if (mc_rng_below(r, 8) < chain) plabel[i] = i - 1 - mc_rng_below(r, i < 4 ? i : 4);
        else plabel[i] = mc_rng_below(r, i);
        sz[i] = 1;
    }
    for (uint32_t i = V; i-- > V0;) sz[plabel[i]] += sz[i];   /* children rank after their parents */

    /* children lists in rank order, then a preorder walk: roots in order, children in split order */
    uint32_t *first = xmalloc((V + 1) * sizeof *first), *kids = xmalloc(V * sizeof *kids);
    uint32_t *fill = xmalloc(V * sizeof *fill), *stack = xmalloc(V * sizeof *stack), *idx = xmalloc(V * sizeof *idx);
    memset(first, 0, (V + 1) * sizeof *first);
    for (uint32_t i = V0; i < V; i++) first[plabel[i] + 1]++;
    for (uint32_t i = 0; i < V; i++) first[i + 1] += first[i];
    memcpy(fill, first, V * sizeof *fill);
    for (uint32_t i = V0; i < V; i++) kids[fill[plabel[i]]++] = i;
    uint32_t top = 0, next = 0;
    for (uint32_t i = V0; i-- > 0;) stack[top++] = i;
    while (top) {
        const uint32_t u = stack[--top];
        idx[u] = next++;
        for (uint32_t k = first[u + 1]; k-- > first[u];) stack[top++] = kids[k];
    }
    assert_int_equal(next, V);

    m->parent = xmalloc(V * sizeof *m->parent);
    m->size = xmalloc(V * sizeof *m->size);
    m->rank = xmalloc(V * sizeof *m->rank);
    for (uint32_t i = 0; i < V; i++) {
        m->parent[idx[i]] = idx[plabel[i]];
        m->size[idx[i]] = sz[i];
        m->rank[idx[i]] = i;
    }
    /* the numbering is what the header promises: a subtree is the run just after its vertex */
    for (uint32_t v = 0; v < V; v++) {
        const uint32_t p = m->parent[v];
        if (p == v) continue;
        assert_true(p < v && v + m->size[v] <= p + m->size[p] && m->rank[p] < m->rank[v]);
    }

    const uint32_t S = V - V0;
    m->split_vertex = xmalloc(S * sizeof *m->split_vertex);
    m->split_faces = xmalloc(S);
    m->faces_at = xmalloc((S + 1) * sizeof *m->faces_at);
    uint32_t F = F0;
    for (uint32_t s = 0; s < S; s++) {
        m->split_vertex[s] = idx[V0 + s];
        m->split_faces[s] = (uint8_t)(1 + mc_rng_below(r, 2));
        F += m->split_faces[s];
    }
    m->faces_at[0] = F0;
    for (uint32_t s = 0; s < S; s++) m->faces_at[s + 1] = m->faces_at[s] + m->split_faces[s];
    m->F = F;
    m->corner = xmalloc((size_t)3 * F * sizeof *m->corner);
    for (uint32_t k = 0; k < 3 * F; k++) m->corner[k] = mc_rng_below(r, V);
    for (uint32_t s = 0; s < S; s++) {   /* edge 0 of a split's first face: the vertex and its parent */
        const uint32_t v = m->split_vertex[s], swap = mc_rng_below(r, 2);
        uint32_t *c = &m->corner[3 * m->faces_at[s]];
        c[swap] = v + mc_rng_below(r, m->size[v]);
        c[1 - swap] = m->parent[v];
    }
    m->pos = xmalloc((size_t)3 * V * sizeof *m->pos);
    for (uint32_t k = 0; k < 3 * V; k++) m->pos[k] = (uint16_t)mc_rng_next(r);
    /* the extremes of the coordinate range */
    m->pos[0] = 0;
    if (3 * V > 1) m->pos[1] = 0xFFFF;
    if (3 * V > 2) m->pos[2] = 0x8000;

    /* the runtime's records */
    uint8_t *b = xmalloc((size_t)V * 6);
    for (uint32_t k = 0; k < 3 * V; k++) put_le(b + 2 * k, m->pos[k], 2);
    m->positions = chunk_records(b, V, 6, shift);
    free(b);
    b = xmalloc((size_t)V * ib);
    for (uint32_t v = 0; v < V; v++) put_le(b + (size_t)v * ib, m->size[v], ib);
    m->tree = chunk_records(b, V, ib, shift);
    free(b);
    b = xmalloc((size_t)S * ib);
    for (uint32_t s = 0; s < S; s++) put_le(b + (size_t)s * ib, m->split_vertex[s], ib);
    m->splits = chunk_records(b, S, ib, shift);
    free(b);
    m->split_bits = chunk_bits(m->split_faces, S, shift);
    b = xmalloc((size_t)F * 3 * ib);
    for (uint32_t k = 0; k < 3 * F; k++) put_le(b + (size_t)k * ib, m->corner[k], ib);
    m->corners = chunk_records(b, F, 3 * ib, shift);
    free(b);

    m->pm = (mc_pmesh){.vertices = V, .base_vertices = V0, .faces = F, .base_faces = F0,
                       .index_bytes = (uint8_t)ib, .record_shift = (uint8_t)shift,
                       .positions = m->positions, .tree = m->tree, .splits = m->splits, .corners = m->corners,
                       .split_faces = m->split_bits};
    free(plabel);
    free(sz);
    free(first);
    free(kids);
    free(fill);
    free(stack);
    free(idx);
}

static void mesh_free(mesh *m)
{
    free(m->parent);
    free(m->size);
    free(m->rank);
    free(m->split_vertex);
    free(m->split_faces);
    free(m->faces_at);
    free(m->corner);
    free(m->pos);
    free_chunks(m->positions);
    free_chunks(m->tree);
    free_chunks(m->splits);
    free_chunks(m->corners);
    free_chunks(m->split_bits);
}

/* the reference: v's nearest ancestor-or-self present at level n (rank < n) */
static uint32_t ref_vertex(const mesh *m, uint32_t n, uint32_t v)
{
    while (m->rank[v] >= n) v = m->parent[v];
    return v;
}

static uint32_t clamp_level(const mesh *m, uint32_t n) { return n < m->V0 ? m->V0 : n > m->V ? m->V : n; }

static void check_vertex(const mesh *m, const mc_pmesh_lod *lod, uint32_t v)
{
    const uint32_t got = mc_pmesh_lod_vertex(lod, v), want = ref_vertex(m, lod->level, v);
    if (got != want) fail_msg("level %u: vertex %u stands for %u, want %u", lod->level, v, got, want);
}

static void check_face(const mesh *m, const mc_pmesh_lod *lod, uint32_t f)
{
    uint32_t c[3];
    mc_pmesh_lod_face(lod, f, c);
    for (unsigned k = 0; k < 3; k++) {
        const uint32_t want = ref_vertex(m, lod->level, m->corner[3 * f + k]);
        if (c[k] != want) fail_msg("level %u: face %u corner %u is %u, want %u", lod->level, f, k, c[k], want);
    }
}

/* level n, its face count, and (full) every vertex and every face present against the reference */
static void check_state(const mesh *m, const mc_pmesh_lod *lod, uint32_t n, int full)
{
    assert_ptr_equal(lod->pm, &m->pm);
    assert_int_equal(lod->level, n);
    if (lod->faces != m->faces_at[n - m->V0])
        fail_msg("level %u: %u faces, want %u", n, lod->faces, m->faces_at[n - m->V0]);
    if (!full) return;
    for (uint32_t v = 0; v < m->V; v++) check_vertex(m, lod, v);
    for (uint32_t f = 0; f < lod->faces; f++) check_face(m, lod, f);
}

/* a target level: below V0 (clamped), above V (clamped), a single step, a small move, the ends,
 * the same level, or anywhere in 0 .. V+2 (big jumps) */
static uint32_t random_target(mc_rng *r, const mesh *m, uint32_t cur)
{
    switch (mc_rng_below(r, 10)) {
    case 0: return mc_rng_below(r, 2) ? 0 : mc_rng_below(r, m->V0);
    case 1: return mc_rng_below(r, 2) ? UINT32_MAX : m->V + 1 + mc_rng_below(r, 1000);
    case 2: return cur + 1;
    case 3: return cur - 1;   /* cur >= 1: V0 >= 1 */
    case 4: return cur - 3 + mc_rng_below(r, 7);
    case 5: return m->V0;
    case 6: return m->V;
    case 7: return cur;
    default: return mc_rng_below(r, m->V + 3);
    }
}

static void test_init_and_positions(void **state)
{
    (void)state;
    static const unsigned shifts[3] = {0, 1, 3};
    mc_rng r;
    mc_rng_seed(&r, 1, 1);
    for (unsigned ib = 2; ib <= 4; ib += 2)
        for (unsigned si = 0; si < 3; si++)
            for (int k = 0; k < 10; k++) {
                mesh m;
                const uint32_t V = 1 + mc_rng_below(&r, 300), V0 = 1 + mc_rng_below(&r, V);
                mesh_build(&m, &r, V, V0, mc_rng_below(&r, 20), ib, shifts[si], (unsigned)k % 9);
                uint32_t *anc = xmalloc(MC_PMESH_LOD_BYTES(V, ib));
                memset(anc, 0xA5, MC_PMESH_LOD_BYTES(V, ib));   /* init must not rely on the memory */
                mc_pmesh_lod lod;
                mc_pmesh_lod_init(&lod, &m.pm, anc);
                assert_ptr_equal(lod.anc, anc);
                check_state(&m, &lod, V0, 1);   /* the base level: every vertex to its root */
                for (uint32_t v = 0; v < V; v++) {
                    uint32_t root = v;
                    while (m.parent[root] != root) root = m.parent[root];
                    assert_int_equal(mc_pmesh_lod_vertex(&lod, v), root);
                }
                for (uint32_t v = 0; v < V; v++) {
                    int32_t xyz[3];
                    mc_pmesh_position(&m.pm, v, xyz);
                    for (unsigned c = 0; c < 3; c++) assert_int_equal(xyz[c], (int32_t)m.pos[3 * v + c] - 32768);
                }
                free(anc);
                mesh_free(&m);
            }
    /* the extremes: vertex 0 was given 0, 0xFFFF, 0x8000 */
    mesh m;
    mesh_build(&m, &r, 5, 2, 1, 2, 0, 0);
    int32_t xyz[3];
    mc_pmesh_position(&m.pm, 0, xyz);
    assert_int_equal(xyz[0], -32768);
    assert_int_equal(xyz[1], 32767);
    assert_int_equal(xyz[2], 0);
    mesh_free(&m);
}

/* many small meshes, every index width and shift, the whole map and every face after each change */
static void test_small_random_walks(void **state)
{
    (void)state;
    static const unsigned shifts[3] = {0, 1, 3};
    mc_rng r;
    mc_rng_seed(&r, 2, 1);
    for (unsigned ib = 2; ib <= 4; ib += 2)
        for (unsigned si = 0; si < 3; si++)
            for (int k = 0; k < 20; k++) {
                mesh m;
                const uint32_t V = 1 + mc_rng_below(&r, 60), V0 = 1 + mc_rng_below(&r, k < 4 && V > 3 ? 3 : V);
                mesh_build(&m, &r, V, V0, mc_rng_below(&r, 10), ib, shifts[si], (unsigned)k % 9);
                void *anc = xmalloc(MC_PMESH_LOD_BYTES(V, ib));
                mc_pmesh_lod lod;
                mc_pmesh_lod_init(&lod, &m.pm, anc);
                uint32_t n = V0;
                for (int step = 0; step < 500; step++) {
                    const uint32_t t = random_target(&r, &m, n);
                    n = mc_pmesh_lod_set(&lod, t);
                    assert_int_equal(n, clamp_level(&m, t));
                    check_state(&m, &lod, n, 1);
                }
                free(anc);
                mesh_free(&m);
            }
}

/* 1e5 changes on a few thousand vertices: the bytes of the map equal a fresh state's set straight to
 * the same level (whatever path led there), sampled vertices and faces the reference's every change,
 * all of them every 64 */
static void big_walk(uint32_t V, uint32_t V0, unsigned ib, unsigned shift, unsigned chain, uint64_t seed, int steps)
{
    mc_rng r;
    mc_rng_seed(&r, seed, 3);
    mesh m;
    mesh_build(&m, &r, V, V0, 2 * V0, ib, shift, chain);
    const uint32_t bytes = MC_PMESH_LOD_BYTES(V, ib);
    void *anc = xmalloc(bytes), *fresh_anc = xmalloc(bytes);
    /* the fresh state of each level, made the first time the walk reaches it: making one every step
     * (an init and every split up to the level) took most of the run time. Every 97th step makes it
     * again, so a state that depended on anything but the level and the arrays would still show. */
    uint8_t *fresh_at = xmalloc((size_t)(V + 1) * bytes), *made = calloc(V + 1, 1);
    assert_non_null(made);
    mc_pmesh_lod lod, fresh;
    mc_pmesh_lod_init(&lod, &m.pm, anc);
    check_state(&m, &lod, V0, 1);
    uint32_t n = V0;
    unsigned long long moved = 0;
    for (int step = 0; step < steps; step++) {
        const uint32_t t = random_target(&r, &m, n), before = n;
        n = mc_pmesh_lod_set(&lod, t);
        assert_int_equal(n, clamp_level(&m, t));
        moved += n > before ? n - before : before - n;
        if (!made[n] || step % 97 == 0) {
            mc_pmesh_lod_init(&fresh, &m.pm, fresh_anc);
            assert_int_equal(mc_pmesh_lod_set(&fresh, n), n);
            assert_int_equal(fresh.level, n);
            assert_int_equal(fresh.faces, m.faces_at[n - V0]);
            if (made[n] && memcmp(fresh_at + (size_t)n * bytes, fresh_anc, bytes) != 0)
                fail_msg("step %d: two fresh states set to level %u differ", step, n);
            memcpy(fresh_at + (size_t)n * bytes, fresh_anc, bytes);
            made[n] = 1;
        }
        if (memcmp(anc, fresh_at + (size_t)n * bytes, bytes) != 0)
            fail_msg("step %d: level %u reached from %u differs from a fresh state set to it", step, n, before);
        check_state(&m, &lod, n, step % 64 == 0);
        for (int k = 0; k < 8; k++) check_vertex(&m, &lod, mc_rng_below(&r, V));
        for (int k = 0; k < 4 && lod.faces; k++) check_face(&m, &lod, mc_rng_below(&r, lod.faces));
    }
    assert_true(moved > (unsigned long long)steps * 10);   /* the walk really went up and down */
    free(anc);
    free(fresh_anc);
    free(fresh_at);
    free(made);
    mesh_free(&m);
}

static void test_big_walk(void **state)
{
    (void)state;
    big_walk(3000, 40, 2, 3, 2, 4, 100000);
}

static void test_big_walk_wide(void **state)
{
    (void)state;
    big_walk(2000, 7, 4, 1, 5, 5, 20000);   /* 4-byte indices, deeper trees, a chunk every 2 records */
}

/* V0 = V: no splits, the splits list only its sentinel; every level clamps to V, every vertex is a
 * root standing for itself */
/* mc_pmesh_lod_fit from random levels to random face budgets: the level is the reference's finest
 * with at most that many faces (F(level) grows with the level), the base when none fits, and the
 * state is what mc_pmesh_lod_set makes there; mc_pmesh_lod_fit_to likewise, not above a random cap */
static void test_fit(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 7, 3);
    for (int k = 0; k < 30; k++) {
        mesh m;
        const uint32_t V = 2 + mc_rng_below(&r, 300), V0 = 1 + mc_rng_below(&r, V / 2);
        mesh_build(&m, &r, V, V0, mc_rng_below(&r, 10), k % 2 ? 4 : 2, (unsigned)k % 4, (unsigned)k % 9);
        void *anc = xmalloc(MC_PMESH_LOD_BYTES(V, m.ib));
        mc_pmesh_lod lod;
        mc_pmesh_lod_init(&lod, &m.pm, anc);
        for (int step = 0; step < 200; step++) {
            mc_pmesh_lod_set(&lod, m.V0 + mc_rng_below(&r, m.V - m.V0 + 1));
            const uint32_t budget = mc_rng_below(&r, m.F + 3);
            uint32_t want = m.V0;
            for (uint32_t n = m.V0; n <= m.V; n++)
                if (m.faces_at[n - m.V0] <= budget) want = n;
            assert_int_equal(mc_pmesh_lod_fit(&lod, budget), want);
            check_state(&m, &lod, want, 0);
            /* capped (a streamed mesh's level that has come), from a level above or below the cap */
            const uint32_t cap = m.V0 + mc_rng_below(&r, m.V - m.V0 + 1);
            mc_pmesh_lod_set(&lod, m.V0 + mc_rng_below(&r, m.V - m.V0 + 1));
            uint32_t want_cap = m.V0;
            for (uint32_t n = m.V0; n <= cap; n++)
                if (m.faces_at[n - m.V0] <= budget) want_cap = n;
            assert_int_equal(mc_pmesh_lod_fit_to(&lod, budget, cap), want_cap);
            check_state(&m, &lod, want_cap, 0);
        }
        free(anc);
        mesh_free(&m);
    }
}

static void test_no_splits(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 6, 1);
    const uint32_t sizes[3] = {1, 2, 50};
    for (unsigned ib = 2; ib <= 4; ib += 2)
        for (unsigned i = 0; i < 3; i++) {
            mesh m;
            const uint32_t V = sizes[i];
            mesh_build(&m, &r, V, V, 3 * V, ib, i, 0);
            assert_null(m.pm.splits[0].data);
            void *anc = xmalloc(MC_PMESH_LOD_BYTES(V, ib));
            mc_pmesh_lod lod;
            mc_pmesh_lod_init(&lod, &m.pm, anc);
            check_state(&m, &lod, V, 1);
            const uint32_t targets[6] = {0, 1, V - 1, V, V + 1, UINT32_MAX};
            for (int k = 0; k < 6; k++) {
                assert_int_equal(mc_pmesh_lod_set(&lod, targets[k]), V);
                check_state(&m, &lod, V, 1);
                for (uint32_t v = 0; v < V; v++) assert_int_equal(mc_pmesh_lod_vertex(&lod, v), v);
            }
            free(anc);
            mesh_free(&m);
        }
}

/* V0 = 1: one tree, every vertex its root's at the base level, vertex 0 the root */
static void test_one_root(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 7, 1);
    for (unsigned ib = 2; ib <= 4; ib += 2)
        for (unsigned chain = 0; chain <= 8; chain += 4) {
            mesh m;
            const uint32_t V = 200;
            mesh_build(&m, &r, V, 1, 0, ib, ib == 2 ? 0 : 3, chain);
            void *anc = xmalloc(MC_PMESH_LOD_BYTES(V, ib));
            mc_pmesh_lod lod;
            mc_pmesh_lod_init(&lod, &m.pm, anc);
            check_state(&m, &lod, 1, 1);
            for (uint32_t v = 0; v < V; v++) assert_int_equal(mc_pmesh_lod_vertex(&lod, v), 0);
            assert_int_equal(lod.faces, 0);
            uint32_t n = 1;
            for (int step = 0; step < 2000; step++) {
                const uint32_t t = random_target(&r, &m, n);
                n = mc_pmesh_lod_set(&lod, t);
                assert_int_equal(n, clamp_level(&m, t));
                check_state(&m, &lod, n, 1);
            }
            /* back to the base: all of it stands for the root again */
            assert_int_equal(mc_pmesh_lod_set(&lod, 0), 1);
            for (uint32_t v = 0; v < V; v++) assert_int_equal(mc_pmesh_lod_vertex(&lod, v), 0);
            free(anc);
            mesh_free(&m);
        }
}

/* index_bytes 4 with indices above 65535: a field read or an entry stored as 16 bits would show */
static void test_wide_indices(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 8, 1);
    mesh m;
    const uint32_t V = 70000, V0 = 3;
    mesh_build(&m, &r, V, V0, 4, 4, 3, 1);
    void *anc = xmalloc(MC_PMESH_LOD_BYTES(V, 4));
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &m.pm, anc);
    check_state(&m, &lod, V0, 1);
    const uint32_t targets[8] = {V, V / 2, V0, 65535, 65537, V - 1, 66000, 0};
    for (int k = 0; k < 8; k++) {
        const uint32_t n = mc_pmesh_lod_set(&lod, targets[k]);
        assert_int_equal(n, clamp_level(&m, targets[k]));
        check_state(&m, &lod, n, 1);
    }
    free(anc);
    mesh_free(&m);
}

int main(void)
{
    setvbuf(stdout, NULL, _IONBF, 0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_and_positions),
        cmocka_unit_test(test_small_random_walks),
        cmocka_unit_test(test_big_walk),
        cmocka_unit_test(test_big_walk_wide),
        cmocka_unit_test(test_fit),
        cmocka_unit_test(test_no_splits),
        cmocka_unit_test(test_one_root),
        cmocka_unit_test(test_wide_indices),
    };
    return cmocka_run_group_tests_name("pmesh", tests, NULL, NULL);
}
