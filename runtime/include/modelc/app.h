/* The binding between a baked model and a front end (viewer, tracker or firmware main).
 *
 * Promise: modelc writes NAME_app.c defining mc_app_model: the model (model.h) and static frame
 * buffers of exactly the size asked for at bake time (--screen), and, with a mesh part, the static
 * memory its level of detail and line drawings need; with an edge part, what a tracker needs for
 * camera frames of that size and --particles particles (the frame buffers then hold the sparse depth
 * buffer's depths and colours); with --emit stream, a buffer that holds the whole stream. A front end links against this
 * one symbol and so works with any model; it asks app->model which parts it has. Libraries built
 * with --emit lib leave it out.
 */
#ifndef MODELC_APP_H
#define MODELC_APP_H

#include <stdint.h>
#include "imgedge.h"
#include "model.h"
#include "particles.h"
#include "sdepth.h"
#include "xform.h"

typedef struct mc_app {
    const mc_model *model;
    uint8_t *color;        /* max_width * max_height palette indices */
    uint16_t *depth;       /* max_width * max_height depths */
    uint16_t max_width, max_height;
    void *pmesh_anc;       /* the mesh part's ancestor map (pmesh.h mc_pmesh_lod_init), or NULL */
    uint8_t *pmesh_facing; /* its line drawings' memory (mesh_lines.h MC_MESH_LINES_BYTES), or NULL */
    mc_xvertex *pmesh_cache; /* its vertex projection cache (mesh_render.h), or NULL */
    uint32_t *pmesh_sdepth;  /* its lines style's sparse depth buffer bits, MC_SDEPTH_WORDS of the screen
                                (sdepth.h), or NULL */
    uint8_t *pmesh_nbr;      /* with --mesh-neighbours: room for its level's neighbour table (pmesh.h
                                mc_pmesh_lod_neighbours, MC_PMESH_NEIGHBOUR_BYTES of the bake's mesh), or NULL */
    uint8_t *edges_frame;    /* the edge part's: a grey camera frame, max_width * max_height, or NULL */
    uint8_t *edges_masks;    /* its edge masks (imgedge.h), max_width * max_height */
    uint32_t *edges_scratch; /* the edge detector's rows, MC_IMGEDGE_SCRATCH_WORDS(max_width) words */
    uint32_t *edges_sdepth;  /* the sparse depth buffer's bits, MC_SDEPTH_WORDS of the screen */
    uint32_t *edges_matched; /* and its matched bits, MC_SDEPTH_MATCHED_WORDS of the screen */
    mc_xvertex *edges_cache; /* the projected vertices, one per vertex of the edge model */
    mc_particle *particles;  /* 2 * max_particles: the filter's two arrays (particles.h) */
    uint32_t max_particles;
    uint8_t *stream_buf;     /* a bake with --emit stream: room for its stream (stream.h), or NULL */
    uint32_t stream_cap;     /* MC_NAME_STREAM_BYTES */
} mc_app;

extern const mc_app mc_app_model;

#endif
