/* Linked with one bake: what its levels hold, read back from the generated arrays alone.
 *
 *   levels LAST    prints, for each level 1..LAST (at most the bake's depth), one line per node:
 *                  "L CODE R G B", the node's Morton code at level L (hex; bit 0 x, 1 y, 2 z, as the
 *                  generator's) and the RGB its palette index stands for, in the arrays' order.
 *
 * Two bakes of one model at different depths are compared level for level with it (tests/gen/suite.sh:
 * level l of a deeper mesh bake holds the cells and colours of a depth-l bake). */
#include <stdio.h>
#include <stdlib.h>

#include <modelc/app.h>
#include <modelc/modelc.h>

/* one chunk list as a flat stream, read byte by byte */
typedef struct {
    const mc_chunk *c;
    uint32_t i;
} stream;

static int next_byte(stream *s, uint8_t *b)
{
    while (s->c && s->c->data && s->i == s->c->size) s->c++, s->i = 0;
    if (!s->c || !s->c->data) return -1;
    *b = s->c->data[s->i++];
    return 0;
}

int main(int argc, char **argv)
{
    const mc_octree *t = mc_app_model.model->octree;
    const int last = argc > 1 ? atoi(argv[1]) : t->depth;
    if (last < 1 || last > t->depth) {
        fprintf(stderr, "levels: LAST must be in 1..%u\n", (unsigned)t->depth);
        return 2;
    }
    uint64_t *codes = malloc(sizeof *codes), *next = NULL;
    size_t n = 1;
    if (!codes) return 1;
    codes[0] = 0;   /* the root */
    for (int l = 1; l <= last; l++) {
        const mc_octree_level *up = &t->levels[l - 1], *at = &t->levels[l];
        if (up->nodes != n) { fprintf(stderr, "levels: level %d has %u nodes, %zu walked\n", l - 1, up->nodes, n); return 1; }
        next = malloc(at->nodes * sizeof *next);
        if (!next) return 1;
        stream masks = {up->masks, 0}, colors = {at->colors, 0};
        size_t k = 0;
        for (size_t i = 0; i < n; i++) {
            uint8_t m;
            if (next_byte(&masks, &m)) { fprintf(stderr, "levels: level %d: masks end early\n", l - 1); return 1; }
            if (!m) { fprintf(stderr, "levels: level %d node %zu has no child\n", l - 1, i); return 1; }
            for (unsigned b = 0; b < 8; b++) {
                if (!(m >> b & 1u)) continue;
                uint8_t ci;
                if (k == at->nodes || next_byte(&colors, &ci) || ci >= t->palette_size) {
                    fprintf(stderr, "levels: level %d: more children than nodes or colours, or a colour off the palette\n", l);
                    return 1;
                }
                next[k] = codes[i] << 3 | b;
                const uint8_t *rgb = &t->palette[3 * ci];
                printf("%d %llx %u %u %u\n", l, (unsigned long long)next[k], rgb[0], rgb[1], rgb[2]);
                k++;
            }
        }
        if (k != at->nodes) { fprintf(stderr, "levels: level %d has %u nodes, %zu children\n", l, at->nodes, k); return 1; }
        free(codes);
        codes = next, n = k;
    }
    free(codes);
    return 0;
}
