/* Sine and cosine of integer angles from a quarter-wave table.
 *
 * Angles are integers, MC_ANGLE_FULL units per turn; any int32 is accepted (taken modulo a turn).
 * Results are Q30 (1.0 = 1 << 30). The table is exact to within 0.5 units of Q30 of sin(2 pi a / 4096)
 * (tests/unit/test_trig.c checks every angle). Rotations are rebuilt from the angles every frame, so
 * no error accumulates however long the model turns.
 */
#ifndef MODELC_TRIG_H
#define MODELC_TRIG_H

#include <stdint.h>
#include "config.h"

#define MC_ANGLE_FULL ((int32_t)1 << MC_ANGLE_BITS)
#define MC_TRIG_ONE ((int32_t)1 << 30)

int32_t mc_sin(int32_t angle);
int32_t mc_cos(int32_t angle);

#endif
