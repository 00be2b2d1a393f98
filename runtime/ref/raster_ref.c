/* Double-precision reference of the triangle rasterizer: see raster_ref.h. */
#include "raster_ref.h"

/* (b - a) x (p - a) with y down: positive when p is clockwise of a -> b on screen */
static double cross(double ax, double ay, double bx, double by, double px, double py)
{
    return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

uint32_t mc_raster_ref_triangle(unsigned width, unsigned height, const mc_raster_vertex v[3], unsigned flags,
                                uint8_t *covered, double *depth)
{
    double x[3], y[3], z[3];
    for (unsigned i = 0; i < width * height; i++) covered[i] = 0;
    for (int k = 0; k < 3; k++) {
        if (v[k].x < -MC_RASTER_COORD_LIMIT || v[k].x > MC_RASTER_COORD_LIMIT || v[k].y < -MC_RASTER_COORD_LIMIT ||
            v[k].y > MC_RASTER_COORD_LIMIT)
            return 0;
        x[k] = v[k].x / 16.0;
        y[k] = v[k].y / 16.0;
        z[k] = v[k].z > MC_DEPTH_EMPTY - 2 ? MC_DEPTH_EMPTY - 2 : v[k].z;
    }
    const double area = cross(x[0], y[0], x[1], y[1], x[2], y[2]);
    if (area == 0) return 0;
    if ((flags & MC_RASTER_CULL_BACK) && !(area < 0)) return 0;

    /* per edge k (from corner k+1 to corner k+2, opposite corner k): the sign of the opposite corner,
     * and whether a centre on the edge's line counts */
    double side[3];
    int tie[3];
    for (int k = 0; k < 3; k++) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        side[k] = cross(x[a], y[a], x[b], y[b], x[k], y[k]);
        if (y[a] == y[b]) {
            tie[k] = y[k] > y[a];                   /* top edge: the triangle below it */
        } else {
            /* x of the edge's line at the opposite corner's height, compared without dividing */
            const double lhs = (x[k] - x[a]) * (y[b] - y[a]), rhs = (x[b] - x[a]) * (y[k] - y[a]);
            tie[k] = y[b] > y[a] ? lhs > rhs : lhs < rhs;   /* left edge: the corner right of it */
        }
    }
    uint32_t n = 0;
    for (unsigned j = 0; j < height; j++) {
        for (unsigned i = 0; i < width; i++) {
            const double px = i + 0.5, py = j + 0.5;
            double w[3];
            int in = 1;
            for (int k = 0; k < 3 && in; k++) {
                const int a = (k + 1) % 3, b = (k + 2) % 3;
                w[k] = cross(x[a], y[a], x[b], y[b], px, py);
                if (w[k] == 0) in = tie[k];
                else in = (w[k] > 0) == (side[k] > 0);
            }
            if (!in) continue;
            covered[j * width + i] = 1;
            /* barycentric weights w[k] / side[k] (side[k] is the area with the corner's sign) */
            depth[j * width + i] = (w[0] * z[0] + w[1] * z[1] + w[2] * z[2]) / area;
            n++;
        }
    }
    return n;
}
