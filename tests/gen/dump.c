/* Linked with one bake: checks the chunk lists and prints what a different chunking must not change.
 *
 *   dump LIMIT    prints, per level, the node count and an FNV-1a hash of the reassembled mask and
 *                 colour streams, then a checksum of a rendered frame; exits 1 (with a message) when
 *                 a chunk is larger than LIMIT, a level's chunks do not add up to its node count, or
 *                 a chunk boundary splits a group the renderer reads at once (octree.h). */
#include <stdio.h>
#include <stdlib.h>

#include <modelc/app.h>
#include <modelc/modelc.h>

static uint32_t fnv(uint32_t h, uint8_t b) { return (h ^ b) * 16777619u; }

/* Walks a chunk list: total bytes, hash, and whether every chunk is within limit. */
static int walk(const mc_chunk *c, unsigned long limit, uint32_t *total, uint32_t *hash, const char *what, unsigned l)
{
    int bad = 0;
    *total = 0;
    for (; c->data; c++) {
        if (c->size == 0 || c->size > limit) {
            printf("level %u %s: chunk of %u bytes (limit %lu)\n", l, what, c->size, limit);
            bad = 1;
        }
        for (uint32_t i = 0; i < c->size; i++) *hash = fnv(*hash, c->data[i]);
        *total += c->size;
    }
    return bad;
}

/* prefix[l][i]: children of the first i nodes of level l = where node i's children start at l+1 */
static uint32_t prefix_store[1u << 23];
static uint32_t *prefix[MC_MAX_DEPTH];

static void build_prefixes(const mc_octree *s)
{
    uint32_t *p = prefix_store;
    for (unsigned l = 0; l < s->depth; l++) {
        prefix[l] = p;
        uint32_t i = 0, sum = 0;
        p[0] = 0;
        for (const mc_chunk *c = s->levels[l].masks; c->data; c++)
            for (uint32_t b = 0; b < c->size; b++) {
                for (unsigned m = c->data[b]; m; m &= m - 1) sum++;
                p[++i] = sum;
            }
        p += i + 1;
    }
}

/* Every chunk of `chunks` (entries of level l) must end where the descendants of some node at level
 * l - up end: the renderer reads such a group from one chunk. */
static int check_groups(const mc_octree *s, const mc_chunk *chunks, unsigned l, unsigned up, const char *what)
{
    unsigned a = l < up ? 0 : l - up;
    uint32_t i = 0, end = 0;
    for (const mc_chunk *c = chunks; c->data; c++) {
        end += c->size;
        uint32_t boundary = 0;
        while (boundary < end && i < s->levels[a].nodes) {
            uint32_t b = ++i;
            for (unsigned j = a; j < l; j++) b = prefix[j][b];
            boundary = b;
        }
        if (boundary != end) {
            printf("level %u %s: a chunk ends at %u, inside a group read at once\n", l, what, end);
            return 1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    const mc_model *model = mc_app_model.model;
    printf("model %s up %s octree %s pmesh %s edges %s\n", model->name, model->up == MC_UP_Z ? "z" : "y",
           model->octree ? "yes" : "no", model->pmesh ? "yes" : "no", model->edges ? "yes" : "no");
    const mc_octree *s = model->octree;
    if (!s) return 1;
    unsigned long limit = argc > 1 ? strtoul(argv[1], NULL, 10) : 65536;
    int bad = 0;
    build_prefixes(s);
    for (unsigned l = 0; l <= s->depth; l++) {
        const mc_octree_level *lv = &s->levels[l];
        uint32_t hm = 2166136261u, hc = 2166136261u, nm = 0, nc = 0;
        if (lv->masks) bad |= walk(lv->masks, limit, &nm, &hm, "masks", l);
        if (lv->colors) bad |= walk(lv->colors, limit, &nc, &hc, "colours", l);
        if ((l < s->depth && nm != lv->nodes) || (l > 0 && nc != lv->nodes)) {
            printf("level %u: chunks hold %u masks and %u colours for %u nodes\n", l, nm, nc, lv->nodes);
            bad = 1;
        }
        if (l > 0 && l < s->depth) bad |= check_groups(s, lv->masks, l, 1, "masks");
        if (l > 0) bad |= check_groups(s, lv->colors, l, 2, "colours");
        printf("level %u nodes %u masks %08x colours %08x\n", l, lv->nodes, hm, hc);
    }
    mc_target t = {mc_app_model.color, mc_app_model.depth, 320, 240};
    mc_view v = mc_view_default();
    v.yaw = 300, v.pitch = 100;
    mc_clear(&t);
    mc_octree_render(s, &v, s->depth, NULL, &t, NULL, NULL, NULL);
    uint32_t h = 2166136261u;
    for (int i = 0; i < 320 * 240; i++) h = fnv(fnv(fnv(h, t.color[i]), (uint8_t)t.depth[i]), (uint8_t)(t.depth[i] >> 8));
    printf("frame %08x\n", h);
    return bad;
}
