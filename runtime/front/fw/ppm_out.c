/* One finished frame out through semihosting: see ppm_out.h. */
#include "ppm_out.h"

#include <semihost.h>
#include <stdio.h>

#include "../host/image.h"   /* MC_HOST_BACKGROUND_*: the host's background, so the files compare equal */

#define CHUNK 96             /* bytes per SYS_WRITE: 32 pixels */

int mc_fw_write_ppm(const char *path, const mc_target *t, const mc_scene *scene)
{
    uint8_t buf[CHUNK];
    int fd = sys_semihost_open(path, SH_OPEN_W_B);
    if (fd < 0) return -1;
    int ok = 1;
    int n = snprintf((char *)buf, sizeof buf, "P6\n%u %u\n255\n", (unsigned)t->width, (unsigned)t->height);
    ok = n > 0 && n < CHUNK && sys_semihost_write(fd, buf, (uintptr_t)n) == 0;
    const uint32_t count = (uint32_t)t->width * t->height;
    uint32_t used = 0;
    for (uint32_t i = 0; i < count && ok; i++) {
        const uint8_t *rgb = scene->palette + 3u * t->color[i];
        if (t->depth[i] == MC_DEPTH_EMPTY) {
            buf[used] = MC_HOST_BACKGROUND_R;
            buf[used + 1] = MC_HOST_BACKGROUND_G;
            buf[used + 2] = MC_HOST_BACKGROUND_B;
        } else {
            buf[used] = rgb[0];
            buf[used + 1] = rgb[1];
            buf[used + 2] = rgb[2];
        }
        used += 3;
        if (used == CHUNK || i + 1 == count) {
            ok = sys_semihost_write(fd, buf, used) == 0;   /* returns the bytes NOT written */
            used = 0;
        }
    }
    if (sys_semihost_close(fd) != 0) ok = 0;
    return ok ? 0 : -1;
}
