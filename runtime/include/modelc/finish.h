/* 2D finishing: closes holes the one-pixel-per-leaf renderer leaves when a view is rotated or zoomed.
 *
 * mc_finish_pixel_holes fills every empty pixel whose four neighbours (left, right, up, down) are all
 * drawn, with the colour and depth of the nearest of them. A filled pixel's right and lower neighbours
 * were drawn before the pass, so a fill never enables another: exactly the one-pixel holes of the
 * input are closed, in one pass, with no scratch memory. Border pixels are never filled.
 * Returns the number of pixels filled.
 */
#ifndef MODELC_FINISH_H
#define MODELC_FINISH_H

#include <stdint.h>
#include "render.h"

uint32_t mc_finish_pixel_holes(const mc_target *t);

#endif
