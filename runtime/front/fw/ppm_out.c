/* One finished frame out through semihosting: see ppm_out.h. */
#include "ppm_out.h"

#include <semihost.h>

#include "../common/rgb.h"

#define CHUNK 32             /* pixels per SYS_WRITE */

int mc_fw_write_ppm(const char *path, const mc_target *t, const uint8_t *palette)
{
    uint8_t buf[3 * CHUNK];
    int fd = sys_semihost_open(path, SH_OPEN_W_B);
    if (fd < 0) return -1;
    unsigned n = mc_front_ppm_header((char *)buf, t->width, t->height);
    int ok = sys_semihost_write(fd, buf, n) == 0;   /* returns the bytes NOT written */
    const uint32_t count = (uint32_t)t->width * t->height;
    for (uint32_t i = 0; i < count && ok; i += CHUNK) {
        const uint32_t k = count - i < CHUNK ? count - i : CHUNK;
        mc_front_rgb(t, palette, i, k, buf);
        ok = sys_semihost_write(fd, buf, 3u * k) == 0;
    }
    if (sys_semihost_close(fd) != 0) ok = 0;
    return ok ? 0 : -1;
}
