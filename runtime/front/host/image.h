/* Host-only image output for the viewer: palette frames to RGB, PPM and PNG files. */
#ifndef MODELC_HOST_IMAGE_H
#define MODELC_HOST_IMAGE_H

#include <stdint.h>
#include <modelc/render.h>

/* Background of pixels nothing was drawn on. */
#define MC_HOST_BACKGROUND_R 24
#define MC_HOST_BACKGROUND_G 24
#define MC_HOST_BACKGROUND_B 32

/* rgb receives width * height * 3 bytes. */
void mc_host_to_rgb(const mc_target *t, const uint8_t *palette, uint8_t *rgb);

/* Write rgb (w * h * 3 bytes) to path. Return 0, or -1 with errno set / a message printed. */
int mc_host_write_ppm(const char *path, const uint8_t *rgb, int w, int h);
int mc_host_write_png(const char *path, const uint8_t *rgb, int w, int h);

#endif
