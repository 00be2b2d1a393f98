/* Double-precision image edges: see imgedge_ref.h. */
#include "imgedge_ref.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

/* distance in degrees from a to the nearest of the boundaries first + step k */
static double boundary_gap(double a, double first, double step)
{
    double r = fmod(a - first, step);
    if (r < 0) r += step;
    return r < step - r ? r : step - r;
}

uint32_t mc_imgedge_ref(const uint8_t *img, uint32_t stride, unsigned w, unsigned h, unsigned threshold,
                        double margin, uint8_t *out, uint8_t *near)
{
    const size_t n = (size_t)w * h;
    for (size_t i = 0; i < n; i++) out[i] = 0, near[i] = 0;
    if (w < 3 || h < 3) return 0;
    if (threshold < 1) threshold = 1;
    if (threshold > 1442) threshold = 1442;
    double *mag = calloc(n, sizeof *mag);   /* gx^2 + gy^2: exact in doubles */
    int *bin = calloc(n, sizeof *bin), *sector = calloc(n, sizeof *sector), *cand = calloc(n, sizeof *cand);
    uint8_t *close = calloc(n, 1);
    const double margin_deg = margin * 180.0 / PI;
    for (unsigned y = 1; y + 1 < h; y++)
        for (unsigned x = 1; x + 1 < w; x++) {
#define I(dx, dy) ((double)img[(size_t)(y + (dy)) * stride + x + (dx)])
            const double gx = I(1, -1) + 2 * I(1, 0) + I(1, 1) - I(-1, -1) - 2 * I(-1, 0) - I(-1, 1);
            const double gy = I(-1, 1) + 2 * I(0, 1) + I(1, 1) - I(-1, -1) - 2 * I(0, -1) - I(1, -1);
#undef I
            const size_t i = (size_t)y * w + x;
            mag[i] = gx * gx + gy * gy;
            if (mag[i] < (double)threshold * threshold) continue;
            cand[i] = 1;
            double a = atan2(gy, gx) * 180.0 / PI;   /* (-180, 180], y down */
            a = fmod(a + 360.0, 180.0);              /* orientation, [0, 180) */
            bin[i] = (int)floor((a + 11.25) / 22.5) % 8;
            sector[i] = (int)floor((a + 22.5) / 45.0) % 4;
            close[i] = boundary_gap(a, 11.25, 22.5) < margin_deg || boundary_gap(a, 22.5, 45.0) < margin_deg;
        }
    uint32_t kept = 0;
    static const int ahead[4][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}};
    for (unsigned y = 1; y + 1 < h; y++)
        for (unsigned x = 1; x + 1 < w; x++) {
            const size_t i = (size_t)y * w + x;
            if (!cand[i]) continue;
            const int s = sector[i];
            const size_t pa = (size_t)((int)y + ahead[s][1]) * w + (size_t)((int)x + ahead[s][0]);
            const size_t pb = (size_t)((int)y - ahead[s][1]) * w + (size_t)((int)x - ahead[s][0]);
            near[i] = close[i];
            if (mag[i] > mag[pb] && mag[i] >= mag[pa]) {
                out[i] = (uint8_t)(1 + bin[i]);
                kept++;
            }
        }
    free(mag), free(bin), free(sector), free(cand), free(close);
    return kept;
}
