/* Linked with one bake: checks the chunk lists and prints what a different chunking must not change.
 *
 *   dump LIMIT    prints, per level, the node count and an FNV-1a hash of the reassembled mask and
 *                 colour streams, then a checksum of a rendered frame; exits 1 (with a message) when
 *                 a chunk is larger than LIMIT, a level's chunks do not add up to its node count, or
 *                 a colour chunk boundary splits a sibling group. */
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

int main(int argc, char **argv)
{
    const mc_scene *s = mc_app_model.scene;
    unsigned long limit = argc > 1 ? strtoul(argv[1], NULL, 10) : 65536;
    int bad = 0;
    for (unsigned l = 0; l <= s->depth; l++) {
        const mc_level *lv = &s->levels[l];
        uint32_t hm = 2166136261u, hc = 2166136261u, nm = 0, nc = 0;
        if (lv->masks) bad |= walk(lv->masks, limit, &nm, &hm, "masks", l);
        if (lv->colors) bad |= walk(lv->colors, limit, &nc, &hc, "colours", l);
        if ((l < s->depth && nm != lv->nodes) || (l > 0 && nc != lv->nodes)) {
            printf("level %u: chunks hold %u masks and %u colours for %u nodes\n", l, nm, nc, lv->nodes);
            bad = 1;
        }
        /* every colour chunk must end where a sibling group ends: on a running sum of the
         * popcounts of the parent level's masks */
        if (l > 0 && lv->colors) {
            const mc_chunk *pc = s->levels[l - 1].masks;
            uint32_t pi = 0, groups_end = 0, chunk_end = 0;
            for (const mc_chunk *c = lv->colors; c->data; c++) {
                chunk_end += c->size;
                while (groups_end < chunk_end) {
                    while (pi == pc->size) pc++, pi = 0;
                    uint8_t m = pc->data[pi++];
                    for (; m; m &= (uint8_t)(m - 1)) groups_end++;
                }
                if (groups_end != chunk_end) {
                    printf("level %u: colour chunk ends at %u inside a sibling group\n", l, chunk_end);
                    bad = 1;
                }
            }
        }
        printf("level %u nodes %u masks %08x colours %08x\n", l, lv->nodes, hm, hc);
    }
    mc_target t = {mc_app_model.color, mc_app_model.depth, 320, 240};
    mc_view v = mc_view_default();
    v.yaw = 300, v.pitch = 100;
    mc_clear(&t);
    mc_render(s, &v, s->depth, &t, NULL, NULL, NULL);
    uint32_t h = 2166136261u;
    for (int i = 0; i < 320 * 240; i++) h = fnv(fnv(fnv(h, t.color[i]), (uint8_t)t.depth[i]), (uint8_t)(t.depth[i] >> 8));
    printf("frame %08x\n", h);
    return bad;
}
