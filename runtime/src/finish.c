/* One-pixel hole filling: see modelc/finish.h. */
#include "modelc/finish.h"

uint32_t mc_finish_pixel_holes(const mc_target *t)
{
    const int32_t w = t->width, h = t->height;
    uint16_t *zb = t->depth;
    uint8_t *fb = t->color;
    uint32_t filled = 0;
    for (int32_t y = 1; y + 1 < h; y++) {
        for (int32_t x = 1; x + 1 < w; x++) {
            int32_t i = y * w + x;
            if (zb[i] != MC_DEPTH_EMPTY) continue;
            const int32_t nb[4] = {i - 1, i + 1, i - w, i + w};
            int32_t best = nb[0];
            int all = 1;
            for (int n = 0; n < 4; n++) {
                if (zb[nb[n]] == MC_DEPTH_EMPTY) { all = 0; break; }
                if (zb[nb[n]] < zb[best]) best = nb[n];
            }
            if (!all) continue;
            zb[i] = zb[best];
            fb[i] = fb[best];
            filled++;
        }
    }
    return filled;
}
