/* Forced into octree_render.c (the one source that calls MC_PLOT_HOOK) and the other files of the
 * render and stress tests, so that the runtime's MC_PLOT_HOOK can call the recorder each defines:
 * one name and one header for both, so that their runtime objects are the same (tests/cc_cached.sh). */
#include <stdint.h>
#if defined(MC_FLOAT) && MC_FLOAT
void record_point(float fx, float fy, const uint8_t *color);   /* float pixels (config.h) */
#else
void record_point(int32_t fx, int32_t fy, const uint8_t *color);   /* Q MC_FRAC_BITS pixels */
#endif
