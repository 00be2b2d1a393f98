/* A baked model: one descriptor per bake, naming the model and pointing at each part it has.
 *
 * Promise: modelc writes one const mc_model per bake (mc_model_NAME, in NAME_model.c), whatever it
 * was asked to prepare. A front end asks the model what it has: a part pointer is NULL when the bake
 * did not make that part: a bake with --as points makes the octree, --as both adds the pmesh
 * (progressive mesh, pmesh.h), and --as edges makes the edge model for tracking (edges.h) alone.
 *
 * The normalization says where the model sits in its file's coordinates, so that a front end can
 * map between file units and the unit cube every part is drawn in (xform.h: at zoom 1 the cube's
 * side spans the target's shorter side). The generator mapped the cube of side `side` centred on
 * `centre` (file coordinates) to the unit cube [-1/2, 1/2]^3 centred on the origin:
 *   up = MC_UP_Y: unit = (p - centre) / side
 *   up = MC_UP_Z: q = (p - centre) / side, unit = (q.x, q.z, -q.y)  (the file's +z is shown as up)
 * The runtime has no floating point, so centre and side are Q32.32 fixed point in the file's units
 * (int64: value * 2^32, rounded to nearest; magnitudes up to 2^31 units, saturated beyond, which no
 * catalogue model comes near). side is positive.
 */
#ifndef MODELC_MODEL_H
#define MODELC_MODEL_H

#include <stdint.h>
#include "edges.h"
#include "octree.h"
#include "pmesh.h"

/* The file's axis that is shown as up (the runtime's +y). */
enum { MC_UP_Y = 1, MC_UP_Z = 2 };

/* One in Q32.32 (model.h's normalization). */
#define MC_MODEL_UNIT ((int64_t)1 << 32)

typedef struct mc_model {
    int64_t centre[3];          /* Q32.32 file units: centre of the cube mapped to the unit cube */
    int64_t side;               /* Q32.32 file units: its side */
    const char *name;
    const mc_octree *octree;    /* point octree (octree.h, drawn by octree_render.h), or NULL */
    const mc_pmesh *pmesh;      /* progressive mesh (pmesh.h), or NULL */
    const mc_edges *edges;      /* edge model for tracking (edges.h), or NULL */
    uint8_t up;                 /* MC_UP_Y or MC_UP_Z */
} mc_model;

#endif
