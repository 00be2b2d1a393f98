/* One finished frame out through semihosting, as a binary PPM file on the host.
 *
 * Promise: mc_fw_write_ppm writes "P6\n<w> <h>\n255\n" and the target's pixels, each palette index
 * expanded through the palette and every empty pixel (depth MC_DEPTH_EMPTY) in the front ends'
 * background colour (../common/rgb.h): byte for byte what the host viewer's --ppm writes for the
 * same frame. Uses the semihosting file calls (SYS_OPEN/SYS_WRITE/SYS_CLOSE) with a small buffer on the
 * stack, no FILE and no heap. Returns 0, or -1 if the host refused a call.
 */
#ifndef MODELC_FW_PPM_OUT_H
#define MODELC_FW_PPM_OUT_H

#include <modelc/target.h>

int mc_fw_write_ppm(const char *path, const mc_target *t, const uint8_t *palette);

#endif
