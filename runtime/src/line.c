/* The line rasterizer: see modelc/line.h; the walk itself is line_walk.h's. */
#include "modelc/line.h"
#include "line_walk.h"

uint32_t mc_line(const mc_target *t, mc_line_vertex a, mc_line_vertex b, uint8_t color, const mc_line_style *s)
{
    walk k;
    if (!walk_init(t->width, t->height, a, b, &k)) return 0;
    uint32_t idx = k.idx, r = k.r, zr = k.zr;
    int32_t z = k.z;
    const uint32_t ustep = k.ustep, vstep = k.vstep, m2 = k.m2, d2 = k.d2, zrstep = k.zrstep;
    const int32_t zstep = k.zstep, zunit = k.zunit;
    const uint32_t off = s ? s->depth_offset : 0;
    const uint32_t flags = s ? s->flags : 0;
    /* no test: every stored depth (< 2^16) passes z - off < depth + 2^16 */
    const uint32_t pass = flags & MC_LINE_NO_DEPTH_TEST ? 0x10000u : 0;
    const int write = (flags & MC_LINE_WRITE_DEPTH) != 0;
    uint8_t *const cbuf = t->color;
    uint16_t *const dbuf = t->depth;
    const uint32_t count = k.count;
    for (uint32_t n = count;;) {
        MC_LINE_STEP_HOOK();
        const uint32_t zt = (uint32_t)z > off ? (uint32_t)z - off : 0;
        if (zt < dbuf[idx] + pass) {
            cbuf[idx] = color;
            if (write) dbuf[idx] = (uint16_t)z;
        }
        if (--n == 0) break;
        idx += ustep;
        r += m2;
        if (r >= d2) {
            r -= d2;
            idx += vstep;
        }
        z += zstep;
        zr += zrstep;
        if (zr >= d2) {
            zr -= d2;
            z += zunit;
        }
    }
    return count;
}

uint32_t mc_line_sdepth(mc_sdepth *s, mc_line_vertex a, mc_line_vertex b, uint8_t color, uint16_t depth_offset)
{
    return mc_line_walk_sdepth(s, a, b, color, depth_offset, 0, 0);
}
