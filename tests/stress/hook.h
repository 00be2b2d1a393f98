/* Forced into every file of the stress test so the runtime's MC_PLOT_HOOK can call the recorder. */
#include <stdint.h>
#if defined(MC_FLOAT) && MC_FLOAT
void stress_point(float fx, float fy, const uint8_t *color);   /* float pixels (config.h) */
#else
void stress_point(int32_t fx, int32_t fy, const uint8_t *color);   /* Q MC_FRAC_BITS pixels */
#endif
