/* modelc build/models/bunny00.off --emit lib --depth 7 -o firmware/  ->  bunny00.h, bunny00_*.c */
#include <stdio.h>
#include <modelc/modelc.h>
#include "bunny00.h"

#define W 160
#define H 128
static uint8_t color[W * H];      /* palette indices */
static uint16_t depth[W * H];     /* z-buffer */

/* The board's display driver: takes one RGB565 line. Here it only counts what is lit. */
static long lit;
static void display_line(int y, const uint16_t *rgb565, int w)
{
    for (int x = 0; x < w; x++) lit += rgb565[x] != 0 && depth[y * W + x] != MC_DEPTH_EMPTY;
}

int main(void)
{
    const mc_octree *s = mc_model_bunny00.octree;     /* the model's point octree */
    mc_target t = {color, depth, W, H};
    mc_view v = mc_view_default();
    uint16_t line[W];
    for (int frame = 0; frame < 8; frame++) {
        v.yaw = frame * (MC_ANGLE_FULL / 8);           /* an eighth of a turn per frame */
        mc_clear(&t);
        mc_octree_render(s, &v, MC_BUNNY00_DEPTH, NULL, &t, NULL, NULL, NULL);   /* default options */
        mc_finish_pixel_holes(&t);
        for (int y = 0; y < H; y++) {
            for (int x = 0; x < W; x++) {
                const uint8_t *rgb = s->palette + 3 * color[y * W + x];
                line[x] = (uint16_t)((rgb[0] >> 3) << 11 | (rgb[1] >> 2) << 5 | rgb[2] >> 3);
            }
            display_line(y, line, W);
        }
        printf("frame %d: %ld pixels lit\n", frame, lit);
        lit = 0;
    }
    return 0;
}
