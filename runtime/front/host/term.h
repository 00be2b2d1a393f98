/* Interactive terminal viewer: truecolour half-block cells, arrow keys rotate, + and - zoom, q quits. */
#ifndef MODELC_HOST_TERM_H
#define MODELC_HOST_TERM_H

#include <modelc/app.h>
#include <modelc/view.h>
#include <modelc/finish.h>

/* Degrees to runtime angle units, rounded. */
int32_t mc_host_angle(double degrees);

/* The finishing of each shown frame (modelc/finish.h); the viewer's --fill sets it. */
extern mc_fill mc_host_fill;

/* Runs until q (or end of input); returns the process exit status. */
int mc_host_interactive(const mc_app *app, mc_view start);

#endif
