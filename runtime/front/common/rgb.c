/* Frames as RGB pictures: see rgb.h. */
#include "rgb.h"

const uint8_t mc_front_background[3] = {24, 24, 32};

void mc_front_rgb(const mc_target *t, const uint8_t *palette, uint32_t first, uint32_t n, uint8_t *rgb)
{
    for (uint32_t k = 0; k < n; k++) mc_target_rgb(t, first + k, palette, mc_front_background, rgb + 3u * k);
}

void mc_front_rgba(const mc_target *t, const uint8_t *palette, uint32_t first, uint32_t n, uint8_t *rgba)
{
    for (uint32_t k = 0; k < n; k++) {
        mc_target_rgb(t, first + k, palette, mc_front_background, rgba + 4u * k);
        rgba[4u * k + 3] = 255;
    }
}

/* decimal digits of v (< 100000) at p; returns how many */
static unsigned put_decimal(char *p, unsigned v)
{
    char d[5];
    unsigned n = 0, k = 0;
    do d[n++] = (char)('0' + v % 10u); while ((v /= 10u) != 0 && n < sizeof d);
    while (n > 0) p[k++] = d[--n];
    return k;
}

unsigned mc_front_ppm_header(char *buf, unsigned w, unsigned h)
{
    unsigned n = 0;
    buf[n++] = 'P';
    buf[n++] = '6';
    buf[n++] = '\n';
    n += put_decimal(buf + n, w);
    buf[n++] = ' ';
    n += put_decimal(buf + n, h);
    buf[n++] = '\n';
    buf[n++] = '2';
    buf[n++] = '5';
    buf[n++] = '5';
    buf[n++] = '\n';
    return n;
}
