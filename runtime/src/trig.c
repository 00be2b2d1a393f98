/* Sine and cosine from the quarter-wave table: symmetry gives the other three quarters exactly. */
#include "modelc/trig.h"
#include "sintab.h"

#define QUARTER (MC_ANGLE_FULL / 4)

int32_t mc_sin(int32_t angle)
{
    /* modulo a turn without the sign trouble of %: two's complement masking (the cast keeps it defined) */
    uint32_t a = (uint32_t)angle & (uint32_t)(MC_ANGLE_FULL - 1);
    uint32_t q = a / QUARTER, r = a % QUARTER;
    switch (q) {
    case 0: return mc_sintab[r];
    case 1: return mc_sintab[QUARTER - r];
    case 2: return -mc_sintab[r];
    default: return -mc_sintab[QUARTER - r];
    }
}

int32_t mc_cos(int32_t angle)
{
    return mc_sin((int32_t)((uint32_t)angle + QUARTER));
}
