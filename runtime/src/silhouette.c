/* Silhouette edges, exact and searched: see modelc/silhouette.h. */
#include "modelc/silhouette.h"
#include "modelc/mesh_lines.h"   /* mc_mesh_front: the facing both line drawings share */

/* marks[f]: facing known this call, front-facing, edge k of f tested this call */
#define KNOWN 1u
#define FRONT 2u
#define TESTED(k) (4u << (k))
/* the most edges a walk around one vertex visits (a valid level has far fewer per vertex) */
#define FAN_MAX 64u

/* A step of the walks (a vertex's projection, a face's facing, an edge's test): inlined into every
 * walk on x86-64 (MC_MESH_SELECT: a fifth fewer instructions a search on bunny00), kept once on a
 * firmware (four times the flash inlined). */
#if MC_MESH_SELECT
#define STEP MC_ALWAYS_INLINE
#else
#define STEP static
#endif

void mc_sil_init(mc_sil *s, uint8_t *marks, uint32_t *list, uint32_t capacity, uint32_t seed)
{
    s->marks = marks;
    s->list = list;
    s->capacity = capacity;
    s->count = 0;
    s->rng = seed ? seed : 2463534242u;
    s->cache = 0;
    s->seen = 0;
}

void mc_sil_cache(mc_sil *s, mc_xvertex *cache, uint32_t *seen)
{
    s->cache = cache && seen ? cache : 0;
    s->seen = cache && seen ? seen : 0;
}

/* All marks of the level's faces to zero: whole words, eight adjacent stores a step (so compilers
 * merge them, and do not turn the loop into a memset call a freestanding build lacks). */
static void clear_marks(uint8_t *marks, uint32_t faces)
{
    uint32_t *w = (uint32_t *)(void *)marks, n = MC_SIL_FACE_BYTES(faces) / 4u, i = 0;
    for (; i + 8 <= n; i += 8) {
        w[i] = 0; w[i + 1] = 0; w[i + 2] = 0; w[i + 3] = 0;
        w[i + 4] = 0; w[i + 5] = 0; w[i + 6] = 0; w[i + 7] = 0;
    }
    for (; i < n; i++) w[i] = 0;
}

typedef struct walk {
    mc_sil *s;
    const mc_pmesh_lod *lod;
    const mc_xform *x;
    mc_sil_stats st;
    uint32_t budget;
    uint32_t total;   /* silhouettes found, listed or not (mc_sil_exact's count) */
} walk;

/* Vertex v's projection this call, from the cache when it was met before. */
STEP const mc_xvertex *vertex(walk *w, uint32_t v)
{
    mc_xvertex *e = &w->s->cache[v];
    uint32_t *bits = &w->s->seen[v >> 5];
    const uint32_t bit = UINT32_C(1) << (v & 31u);
    if (!(*bits & bit)) {
        int32_t p[3];
        mc_pmesh_position(w->lod->pm, v, p);
        mc_xform_vertex(w->x, p, e);
        *bits |= bit;
    }
    return e;
}

/* Face f's facing as mc_mesh_front finds it, its corners' projections from the cache: the sign of its
 * projected area, or (a corner flagged, which is rare) mc_mesh_front's plane test itself. */
STEP int front_cached(walk *w, uint32_t f)
{
    uint32_t c[3];
    mc_pmesh_lod_face(w->lod, f, c);
    const mc_xvertex *a = vertex(w, c[0]), *b = vertex(w, c[1]), *d = vertex(w, c[2]);
    if (a->flags | b->flags | d->flags) return mc_mesh_front(w->lod, w->x, f);
    return mc_mesh_front_of(a, b, d);
}

STEP int front(walk *w, uint32_t f)
{
    uint8_t *m = &w->s->marks[f];
    if (!(*m & KNOWN)) {
        const int fr = w->s->cache ? front_cached(w, f) : mc_mesh_front(w->lod, w->x, f);
        *m |= (uint8_t)(KNOWN | (fr ? FRONT : 0u));
        w->st.facings++;
    }
    return (*m & FRONT) != 0;
}

/* Tests the edge of half-edge h (a present face's) unless it was tested this call; lists it when it
 * is a silhouette. Returns 1 when it was newly found a silhouette. */
STEP int test(walk *w, uint32_t h)
{
    const uint32_t f = MC_HALF_FACE(h), k = MC_HALF_EDGE_INDEX(h);
    if (w->s->marks[f] & TESTED(k)) return 0;
    w->s->marks[f] |= (uint8_t)TESTED(k);
    w->st.tests++;
    const uint32_t o = mc_pmesh_lod_opposite(w->lod, h);
    if (o == MC_NO_HALF_EDGE) return 0;   /* a border: one face */
    w->s->marks[MC_HALF_FACE(o)] |= (uint8_t)TESTED(MC_HALF_EDGE_INDEX(o));
    if (front(w, f) == front(w, MC_HALF_FACE(o))) return 0;
    w->total++;
    if (w->s->count < w->s->capacity) w->s->list[w->s->count++] = h;
    return 1;
}

/* The half-edge after h in its face: edge (k + 1) mod 3, from a table in a constant (0 -> 1 -> 2 -> 0:
 * two bits each; a division by 3 costs more on every step of a fan). */
MC_ALWAYS_INLINE uint32_t next_in_face(uint32_t h)
{
    return MC_HALF_EDGE(MC_HALF_FACE(h), (0x09u >> (2u * MC_HALF_EDGE_INDEX(h))) & 3u);
}

/* Tests the edges around the vertex half-edge h ends at, turning through the faces from h's face,
 * while budget lasts. */
static void fan(walk *w, uint32_t h)
{
    uint32_t cur = next_in_face(h);   /* leaves the vertex */
    for (uint32_t i = 0; i < FAN_MAX && w->st.tests < w->budget; i++) {
        test(w, cur);
        const uint32_t o = mc_pmesh_lod_opposite(w->lod, cur);   /* enters the vertex */
        if (o == MC_NO_HALF_EDGE) return;
        cur = next_in_face(o);
        if (MC_HALF_FACE(cur) == MC_HALF_FACE(h)) return;   /* around */
    }
}

/* Follows the chains from list entry `from` on: both endpoints of each entry. */
static void follow(walk *w, uint32_t from)
{
    for (uint32_t i = from; i < w->s->count && w->st.tests < w->budget; i++) {
        const uint32_t h = w->s->list[i];
        fan(w, h);   /* around its end */
        const uint32_t o = mc_pmesh_lod_opposite(w->lod, h);
        if (o != MC_NO_HALF_EDGE) fan(w, o);   /* around its start: the end of the opposite half-edge */
    }
}

static uint32_t next_random(mc_sil *s)
{
    uint32_t r = s->rng;
    r ^= r << 13;
    r ^= r >> 17;
    r ^= r << 5;
    s->rng = r;
    return r;
}

static void finish(walk *w, mc_sil_stats *stats)
{
    w->st.found = w->s->count;
    if (stats) *stats = w->st;
}

static void start(walk *w, mc_sil *s, const mc_pmesh_lod *lod, const mc_xform *x, uint32_t budget)
{
    w->s = s;
    w->lod = lod;
    w->x = x;
    w->st.tests = w->st.facings = w->st.kept = w->st.seeds = w->st.found = 0;
    w->budget = budget;
    w->total = 0;
    clear_marks(s->marks, lod->faces);
    if (s->cache)
        for (uint32_t i = 0; i < MC_SIL_SEEN_WORDS(lod->pm->vertices); i++) s->seen[i] = 0;
}

uint32_t mc_sil_exact(mc_sil *s, const mc_pmesh_lod *lod, const mc_xform *x, mc_sil_stats *stats)
{
    walk w;
    start(&w, s, lod, x, UINT32_MAX);
    s->count = 0;
    for (uint32_t f = 0; f < lod->faces; f++) front(&w, f);
    for (uint32_t f = 0; f < lod->faces; f++)
        for (uint32_t k = 0; k < 3; k++) test(&w, MC_HALF_EDGE(f, k));
    finish(&w, stats);
    return w.total;
}

uint32_t mc_sil_search(mc_sil *s, const mc_pmesh_lod *lod, const mc_xform *x, uint32_t budget, uint32_t seeds,
                       mc_sil_stats *stats)
{
    walk w;
    start(&w, s, lod, x, budget);
    /* 1. the previous list, retested in place (entries kept move down, never past the one read) */
    const uint32_t old = s->count;
    s->count = 0;
    for (uint32_t i = 0; i < old && w.st.tests < budget; i++) {
        const uint32_t h = s->list[i];
        if (MC_HALF_FACE(h) < lod->faces && test(&w, h)) w.st.kept++;
    }
    /* 2. the chains from what was kept; 3. seeds, each followed */
    follow(&w, 0);
    const uint32_t E = lod->pm->edges;
    for (uint32_t i = 0; i < seeds && w.st.tests < budget && E > 0; i++) {
        const uint32_t u = next_random(s) >> 16;                                   /* 16 bits */
        const uint32_t at = (uint32_t)(((uint64_t)u * u * E) >> 32);               /* E u^2 */
        const uint32_t h = mc_pmesh_edge(lod->pm, at);
        w.st.seeds++;
        if (MC_HALF_FACE(h) >= lod->faces) continue;   /* its face is not at this level */
        const uint32_t before = s->count;
        if (test(&w, h)) follow(&w, before);
    }
    finish(&w, stats);
    return s->count;
}
