/* The binding between a baked model and a front end (viewer or firmware main).
 *
 * Promise: modelc writes NAME_app.c defining mc_app_model: the model (model.h) and static frame
 * buffers of exactly the size asked for at bake time (--screen), and, with a mesh part, the static
 * memory its level of detail and line drawings need. A front end links against this
 * one symbol and so works with any model; it asks app->model which parts it has. Libraries built
 * with --emit lib leave it out.
 */
#ifndef MODELC_APP_H
#define MODELC_APP_H

#include <stdint.h>
#include "model.h"
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
} mc_app;

extern const mc_app mc_app_model;

#endif
