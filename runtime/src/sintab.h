/* Quarter-wave sine table (internal to the runtime). */
#ifndef MODELC_SINTAB_H
#define MODELC_SINTAB_H
#include <stdint.h>
#define MC_SINTAB_SIZE 1025
extern const int32_t mc_sintab[MC_SINTAB_SIZE];
#endif
