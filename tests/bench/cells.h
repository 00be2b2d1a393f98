/* Benchmark helper: decodes a baked scene's leaf cells, independently of the runtime's renderer.
 *
 * Follows modelc/octree.h only: level l holds one child-mask byte per node (levels 0..D-1) and one
 * palette index per node (levels 1..D), each level in depth-first order, split into chunks ending
 * with a {0, 0} sentinel. A depth-first walk with one read cursor per level meets every level's
 * entries in stored order. Child k of a node is offset by +-1/4 of the node's side along x (bit 0),
 * y (bit 1) and z (bit 2), so a leaf at depth D has integer cell coordinates in 0..2^D-1 per axis
 * (bit set = upper half) and its centre, in cube sides with the cube centred on the origin, is
 * (i + 0.5) / 2^D - 0.5.
 *
 * Header-only (static functions) so that each bench program stays one file plus this header.
 */
#ifndef MODELC_BENCH_CELLS_H
#define MODELC_BENCH_CELLS_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <modelc/octree.h>

typedef struct bench_cell {
    uint32_t ix, iy, iz;   /* integer cell coordinates, 0..2^D-1 */
    double x, y, z;        /* cell centre in cube sides, cube centred on the origin */
    uint8_t color;         /* palette index */
} bench_cell;

typedef struct bench_cursor {
    const mc_chunk *chunk;
    uint32_t pos;
} bench_cursor;

static int bench_cursor_byte(bench_cursor *c, uint8_t *out)
{
    while (c->chunk->data && c->pos >= c->chunk->size) { c->chunk++; c->pos = 0; }
    if (!c->chunk->data) return -1;
    *out = c->chunk->data[c->pos++];
    return 0;
}

typedef struct bench_walk {
    const mc_octree *scene;
    unsigned depth;
    bench_cursor mask[32];
    bench_cursor color;
    bench_cell *cells;
    uint32_t n, cap;
    int error;
} bench_walk;

static void bench_walk_node(bench_walk *w, unsigned l, uint32_t ix, uint32_t iy, uint32_t iz)
{
    uint8_t m;
    if (w->error) return;
    if (bench_cursor_byte(&w->mask[l], &m)) { w->error = 1; return; }
    for (unsigned k = 0; k < 8; k++) {
        if (!(m & (1u << k))) continue;
        uint32_t cx = 2 * ix + (k & 1), cy = 2 * iy + ((k >> 1) & 1), cz = 2 * iz + ((k >> 2) & 1);
        if (l + 1 < w->depth) {
            bench_walk_node(w, l + 1, cx, cy, cz);
            if (w->error) return;
            continue;
        }
        uint8_t col;
        if (bench_cursor_byte(&w->color, &col) || w->n >= w->cap) { w->error = 1; return; }
        double inv = 1.0 / (double)(1u << w->depth);
        bench_cell *c = &w->cells[w->n++];
        c->ix = cx; c->iy = cy; c->iz = cz;
        c->x = (cx + 0.5) * inv - 0.5;
        c->y = (cy + 0.5) * inv - 0.5;
        c->z = (cz + 0.5) * inv - 0.5;
        c->color = col;
    }
}

/* Decodes every leaf of `scene` at its full depth, in depth-first order (the order mc_octree_render draws
 * them). Returns a malloc'd array and sets *count, or NULL on a malformed scene. */
static bench_cell *bench_decode_cells(const mc_octree *scene, uint32_t *count)
{
    bench_walk w = {0};
    unsigned d = scene->depth;
    if (d < 1 || d >= 32) return NULL;
    w.scene = scene;
    w.depth = d;
    w.cap = scene->levels[d].nodes;
    w.cells = malloc((size_t)(w.cap ? w.cap : 1) * sizeof *w.cells);
    if (!w.cells) return NULL;
    for (unsigned l = 0; l < d; l++) { w.mask[l].chunk = scene->levels[l].masks; w.mask[l].pos = 0; }
    w.color.chunk = scene->levels[d].colors;
    w.color.pos = 0;
    bench_walk_node(&w, 0, 0, 0, 0);
    if (w.error || w.n != w.cap) {
        fprintf(stderr, "cells: malformed scene (decoded %u of %u leaves)\n", w.n, w.cap);
        free(w.cells);
        return NULL;
    }
    *count = w.n;
    return w.cells;
}

#endif
