/* Interactive terminal viewer: truecolour half-block cells, arrow keys rotate, + and - zoom, q quits. */
#ifndef MODELC_HOST_TERM_H
#define MODELC_HOST_TERM_H

#include <modelc/app.h>
#include <modelc/finish.h>
#include <modelc/octree_render.h>

/* Degrees to runtime angle units, rounded. */
int32_t mc_host_angle(double degrees);

/* Shows app's octree from view `start`, drawn with opt and each frame finished with fill
 * (modelc/finish.h). Runs until q (or end of input); returns the process exit status. */
int mc_host_interactive(const mc_app *app, mc_view start, const mc_octree_options *opt, mc_fill fill);

#endif
