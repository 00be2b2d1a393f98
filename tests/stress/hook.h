/* Forced into every file of the stress test so the runtime's MC_PLOT_HOOK can call the recorder. */
#include <stdint.h>
void stress_point(int32_t fx, int32_t fy, const uint8_t *color);
