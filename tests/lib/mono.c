/* Linked with two bakes of one model at one depth: "colr" (full palette) and "mono" (--palette 1,
 * which stores no colour arrays). Renders both from views that exercise every path of the renderer
 * (wholly on screen, clipped, partly and wholly off screen, perspective, every depth) and checks that
 * the monochrome scene covers exactly the same pixels at the same depths, draws palette index 0
 * everywhere, and lands the same number of points. Prints TAP lines. */
#include <stdio.h>
#include <string.h>
#include <modelc/modelc.h>
#include "colr.h"
#include "mono.h"

#define W 200
#define H 150
static uint8_t c1[W * H], c2[W * H];
static uint16_t z1[W * H], z2[W * H];

int main(void)
{
    int fails = 0;
    if (mc_octree_mono.palette_size != 1) { printf("not ok - mono: palette has %u entries\n", mc_octree_mono.palette_size); return 1; }
    for (unsigned l = 0; l <= mc_octree_mono.depth; l++)
        if (mc_octree_mono.levels[l].colors) { printf("not ok - mono: level %u has colours\n", l); return 1; }
    printf("ok - mono: one palette entry, no colour list at any level\n");
    static const int32_t views[][6] = {   /* yaw, pitch, zoom/16, tx, ty, perspective */
        {0, 0, 16, 0, 0, 0}, {341, 113, 16, 0, 0, 0}, {700, -200, 40, 30, -20, 0},
        {1500, 400, 64, -150, 90, 0}, {200, 100, 8, 0, 0, 1}, {3000, 50, 30, 10, 10, 1},
    };
    for (unsigned d = 1; d <= MC_MONO_DEPTH; d++)
        for (unsigned i = 0; i < sizeof views / sizeof views[0]; i++) {
            mc_view v = mc_view_default();
            v.yaw = views[i][0], v.pitch = views[i][1], v.zoom = views[i][2] * (MC_ZOOM_ONE / 16);
            v.tx = views[i][3], v.ty = views[i][4];
            v.projection = views[i][5] ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
            mc_target a = {c1, z1, W, H}, b = {c2, z2, W, H};
            mc_stats sa, sb;
            mc_clear(&a), mc_clear(&b);
            memset(c2, 7, sizeof c2);            /* mono must write index 0 over anything */
            int ra = mc_octree_render(&mc_octree_colr, &v, d, NULL, &a, NULL, NULL, &sa);
            int rb = mc_octree_render(&mc_octree_mono, &v, d, NULL, &b, NULL, NULL, &sb);
            long drawn = 0, wrong = 0;
            for (int p = 0; p < W * H; p++) {
                drawn += z2[p] != MC_DEPTH_EMPTY;
                wrong += z1[p] != z2[p] || (z2[p] != MC_DEPTH_EMPTY && c2[p] != 0);
            }
            if (ra || rb || sa.points != sb.points || wrong || (i < 3 && !drawn)) {
                printf("not ok - mono depth %u view %u: status %d/%d, points %u/%u, %ld pixels differ, %ld drawn\n",
                       d, i, ra, rb, sa.points, sb.points, wrong, drawn);
                fails++;
            }
        }
    if (!fails) printf("ok - mono: same pixels and depths as the coloured bake, all index 0, at depths 1..%d and 6 views\n", MC_MONO_DEPTH);
    return fails != 0;
}
