/* Interactive terminal viewer: truecolour half-block cells, arrow keys rotate, + and - zoom, q quits. */
#ifndef MODELC_HOST_TERM_H
#define MODELC_HOST_TERM_H

#include <modelc/app.h>
#include <modelc/view.h>

/* Degrees to runtime angle units, rounded. */
int32_t mc_host_angle(double degrees);

/* Runs until q (or end of input); returns the process exit status. */
int mc_host_interactive(const mc_app *app, mc_view start);

#endif
