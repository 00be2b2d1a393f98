/* The depth buffer's scale, shared by the renderer and the generator.
 *
 * Promise: an orthographic frame stores depths shifted right by the smallest zshift that brings the
 * model's bounding-sphere diameter, in depth units, below MC_DEPTH_SPAN; so that diameter spans
 * fewer than MC_DEPTH_SPAN units of the 16-bit buffer, and at least MC_DEPTH_SPAN / 2 whenever the
 * model is at least a pixel wide on screen. The generator's frontal-view pruning (gen/visibility.cpp)
 * relies on that lower bound to know which cells can tie in depth.
 */
#ifndef MODELC_DEPTH_H
#define MODELC_DEPTH_H

/* below 65536 with room for a depth unit of rounding per level (MC_MAX_DEPTH) */
#define MC_DEPTH_SPAN 65000u

#endif
