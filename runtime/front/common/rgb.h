/* Frames as RGB pictures, the same on every front end: the background colour, palette conversion
 * and the binary PPM header.
 *
 * Promise: mc_front_rgb turns pixels of a finished target into RGB triplets through the model's
 * palette (modelc/target.h, mc_target_rgb), pixels nothing was drawn on in mc_front_background;
 * mc_front_rgba the same as RGBA quadruplets, opaque (a canvas's ImageData).
 * mc_front_ppm_header writes "P6\n<w> <h>\n255\n". A PPM written as the header followed by
 * mc_front_rgb of every pixel is byte for byte the same file on the host and on the firmware, which
 * the firmware test compares. Freestanding (no stdio), no heap.
 */
#ifndef MODELC_FRONT_RGB_H
#define MODELC_FRONT_RGB_H

#include <stdint.h>
#include <modelc/target.h>

/* The background of every picture and display: RGB of pixels nothing was drawn on. */
extern const uint8_t mc_front_background[3];

/* Pixels first .. first + n - 1 of t (row-major) into rgb[0 .. 3n - 1]. */
void mc_front_rgb(const mc_target *t, const uint8_t *palette, uint32_t first, uint32_t n, uint8_t *rgb);

/* The same into rgba[0 .. 4n - 1], alpha 255. */
void mc_front_rgba(const mc_target *t, const uint8_t *palette, uint32_t first, uint32_t n, uint8_t *rgba);

/* Longest header mc_front_ppm_header writes: "P6\n65535 65535\n255\n" is 19 bytes. */
#define MC_FRONT_PPM_HEADER_MAX 20

/* Writes the header of a w x h binary PPM into buf (MC_FRONT_PPM_HEADER_MAX bytes, no terminating
 * zero) and returns its length. */
unsigned mc_front_ppm_header(char *buf, unsigned w, unsigned h);

#endif
