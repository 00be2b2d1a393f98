/* Interactive terminal viewer: truecolour half-block cells, arrow keys rotate, + and - zoom, m changes
 * the mode and [ ] the mesh's level of detail (with a mesh part), q quits. */
#ifndef MODELC_HOST_TERM_H
#define MODELC_HOST_TERM_H

#include <modelc/app.h>
#include "scene.h"
#include "stream_in.h"

/* Degrees to runtime angle units, rounded. */
int32_t mc_host_angle(double degrees);

/* Shows the scene (its mode, options and level of detail; scene.h) from view `start`. Runs until q
 * (or end of input); returns the process exit status. With a stream (or NULL), the points are its
 * deepest complete level, redrawn as levels arrive; the status line says where the stream is, and
 * a stream that fails leaves the last good level on screen. */
int mc_host_interactive(mc_host_scene *scene, mc_view start, mc_host_stream *stream);

#endif
