/* Host-only image files for the viewer: a finished frame as RGB (../common/rgb.h), PPM and PNG. */
#ifndef MODELC_HOST_IMAGE_H
#define MODELC_HOST_IMAGE_H

#include <stdint.h>
#include <modelc/target.h>

/* rgb receives width * height * 3 bytes: mc_front_rgb of every pixel. */
void mc_host_to_rgb(const mc_target *t, const uint8_t *palette, uint8_t *rgb);

/* Write rgb (w * h * 3 bytes) to path. Return 0, or -1 with errno set / a message printed. */
int mc_host_write_ppm(const char *path, const uint8_t *rgb, int w, int h);
int mc_host_write_png(const char *path, const uint8_t *rgb, int w, int h);

#endif
