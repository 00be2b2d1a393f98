/* Double-precision reference of the image edges (modelc/imgedge.h), for tests only: never linked
 * into a viewer, tracker or firmware. It computes the same Sobel gradient and squared magnitude
 * (exact in doubles), and the orientation bin and thinning sector from the angle itself (atan2 in
 * degrees, boundaries at 11.25 + 22.5 k and at 22.5 + 45 k), with the promised tie rules. A pixel
 * whose angle lies within `margin` radians of a bin or sector boundary is reported in near[] (the
 * runtime's Q16 tangents may put it on the other side), so a test compares the rest exactly. */
#ifndef MODELC_IMGEDGE_REF_H
#define MODELC_IMGEDGE_REF_H

#include <stdint.h>

/* out as mc_imgedge's (w * h codes); near[i] = 1 where candidate i's angle lies within margin of a
 * bin or sector boundary (its code may then differ: the neighbours' magnitudes are exact).
 * Returns the number of edge pixels. */
uint32_t mc_imgedge_ref(const uint8_t *img, uint32_t stride, unsigned w, unsigned h, unsigned threshold,
                        double margin, uint8_t *out, uint8_t *near);

#endif
