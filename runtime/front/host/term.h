/* Interactive terminal viewer: truecolour half-block cells, arrow keys rotate, + and - zoom, m changes
 * the mode and [ ] the mesh's level of detail (with a mesh part), q quits. */
#ifndef MODELC_HOST_TERM_H
#define MODELC_HOST_TERM_H

#include <modelc/app.h>
#include "scene.h"

/* Degrees to runtime angle units, rounded. */
int32_t mc_host_angle(double degrees);

/* Shows the scene (its mode, options and level of detail; scene.h) from view `start`. Runs until q
 * (or end of input); returns the process exit status. */
int mc_host_interactive(mc_host_scene *scene, mc_view start);

#endif
