/* The binding between a baked model and a front end (viewer or firmware main).
 *
 * Promise: modelc writes NAME_app.c defining mc_app_model: the model (model.h) and static frame
 * buffers of exactly the size asked for at bake time (--screen). A front end links against this
 * one symbol and so works with any model; it asks app->model which parts it has. Libraries built
 * with --emit lib leave it out.
 */
#ifndef MODELC_APP_H
#define MODELC_APP_H

#include <stdint.h>
#include "model.h"

typedef struct mc_app {
    const mc_model *model;
    uint8_t *color;        /* max_width * max_height palette indices */
    uint16_t *depth;       /* max_width * max_height depths */
    uint16_t max_width, max_height;
} mc_app;

extern const mc_app mc_app_model;

#endif
