/* Prints a baked edge model (edges.h) as text for tests/track/suite.sh to compare with its own
 * double-precision reading of the source file: "edges V L F closed", then "v x y z" (um) per vertex,
 * "l a b" per line and "f a b c" per face. Compile with -DDUMP_MODEL=mc_model_NAME and link the
 * bake's .c files. */
#include <stdio.h>

#include <modelc/model.h>

extern const mc_model DUMP_MODEL;

int main(void)
{
    const mc_edges *e = DUMP_MODEL.edges;
    if (!e || DUMP_MODEL.octree || DUMP_MODEL.pmesh) {
        fprintf(stderr, "edges_dump: not an edge-model bake\n");
        return 1;
    }
    printf("edges %lu %lu %lu %u\n", (unsigned long)e->vertices, (unsigned long)e->lines, (unsigned long)e->faces, e->closed);
    for (uint32_t v = 0; v < e->vertices; v++) {
        int32_t p[3];
        mc_edges_position(e, v, p);
        printf("v %ld %ld %ld\n", (long)p[0], (long)p[1], (long)p[2]);
    }
    for (uint32_t i = 0; i < e->lines; i++) {
        uint32_t l[2];
        mc_edges_line(e, i, l);
        printf("l %lu %lu\n", (unsigned long)l[0], (unsigned long)l[1]);
    }
    for (uint32_t i = 0; i < e->faces; i++) {
        uint32_t f[3];
        mc_edges_face(e, i, f);
        printf("f %lu %lu %lu\n", (unsigned long)f[0], (unsigned long)f[1], (unsigned long)f[2]);
    }
    return 0;
}
