/* PPM by hand, PNG through stb_image_write (Debian libstb-dev).
 *
 * The viewer must not touch the heap, so stb's allocations go to a static bump arena. stb reallocates
 * its growing buffers with the old size known (STBIW_REALLOC_SIZED), which a bump arena serves by
 * copying; it frees nothing until the file is written, then the arena is reset whole. */
#include "image.h"

#include <stdio.h>
#include <string.h>

#include "../common/rgb.h"

/* MC_PNG_ARENA_BYTES: static memory for one PNG encode. stb needs about 4x the raw image at most
 * (filtered rows, the deflate output growing by doubling); 64 MiB covers 2048x2048. Untouched pages
 * of a static array cost no RAM on a desktop. */
#ifndef MC_PNG_ARENA_BYTES
#define MC_PNG_ARENA_BYTES (64u << 20)
#endif

static unsigned char arena[MC_PNG_ARENA_BYTES];
static size_t arena_used;

static void *arena_alloc(size_t n)
{
    n = (n + 15u) & ~(size_t)15u;
    if (n > sizeof arena - arena_used) return NULL;   /* stb reports the failure */
    void *p = arena + arena_used;
    arena_used += n;
    return p;
}

static void *arena_realloc(void *old, size_t old_size, size_t new_size)
{
    void *p = arena_alloc(new_size);
    if (p && old) memcpy(p, old, old_size < new_size ? old_size : new_size);
    return p;
}

#define STBIW_MALLOC(n) arena_alloc(n)
#define STBIW_REALLOC_SIZED(p, oldsz, newsz) arena_realloc(p, oldsz, newsz)
#define STBIW_FREE(p) ((void)(p))
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

void mc_host_to_rgb(const mc_target *t, const uint8_t *palette, uint8_t *rgb)
{
    mc_front_rgb(t, palette, 0, (uint32_t)t->width * t->height, rgb);
}

int mc_host_write_ppm(const char *path, const uint8_t *rgb, int w, int h)
{
    char header[MC_FRONT_PPM_HEADER_MAX];
    const unsigned n = mc_front_ppm_header(header, (unsigned)w, (unsigned)h);
    FILE *f = fopen(path, "wb");
    if (!f) return -1;
    int ok = fwrite(header, 1, n, f) == n && fwrite(rgb, 3, (size_t)w * h, f) == (size_t)w * h;
    return fclose(f) == 0 && ok ? 0 : -1;
}

int mc_host_write_png(const char *path, const uint8_t *rgb, int w, int h)
{
    arena_used = 0;
    int ok = stbi_write_png(path, w, h, 3, rgb, w * 3);
    arena_used = 0;
    return ok ? 0 : -1;
}
