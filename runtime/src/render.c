/* Point-octree renderer: see modelc/render.h for what it promises. */
#include "modelc/render.h"

#define F MC_FRAC_BITS

/* Depth coordinates are in the same Q F pixels as x and y (so that perspective divides by a
 * distance as exact as the position it scales), offset so the model's bounding sphere spans
 * [0, 2 * radius]; the depth buffer keeps z >> zshift, with zshift chosen per frame to fit 16 bits. */
#define DEPTH_OF(z) ((uint16_t)((uint32_t)(z) >> c->zshift))

/* sqrt(3)/2 in Q30, rounded up, for bounding spheres that are never too small */
#define HALF_SQRT3_Q30 929887697

/* A read position in a chunked byte array. */
typedef struct cursor {
    const uint8_t *p, *end;
    const mc_chunk *next;
} cursor;

typedef struct ctx {
    cursor mask[MC_MAX_DEPTH];
    cursor color;                        /* colours of the drawn level */
    int32_t vx[MC_MAX_DEPTH][8], vy[MC_MAX_DEPTH][8], vz[MC_MAX_DEPTH][8]; /* level-l node -> child k */
    int32_t radius[MC_MAX_DEPTH + 1];    /* bounding sphere of a level-l node, Q F pixels */
    uint8_t *fb;
    uint16_t *zb;
    int32_t w, h, wf, hf;                /* size in pixels and in Q F */
    unsigned d;                          /* drawn level */
    unsigned zshift;                     /* depth buffer value = z >> zshift */
    int perspective;
    int32_t cx, cy;                      /* perspective: screen centre plus translation, Q F */
    int64_t eye, near;                   /* perspective: eye distance and near plane, Q F pixels */
    mc_abort_fn abort;
    void *user;
    uint32_t points, polls;
    int aborted;
} ctx;

static const uint8_t popcount8[256] = {
#define B2(n) n, n + 1, n + 1, n + 2
#define B4(n) B2(n), B2(n + 1), B2(n + 1), B2(n + 2)
#define B6(n) B4(n), B4(n + 1), B4(n + 1), B4(n + 2)
    B6(0), B6(1), B6(1), B6(2)
#undef B2
#undef B4
#undef B6
};

static int lowest_bit(unsigned m)
{
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctz(m);
#else
    int k = 0;
    while (!(m & 1u)) { m >>= 1; k++; }
    return k;
#endif
}

static void cursor_init(cursor *c, const mc_chunk *chunks)
{
    c->p = chunks->data;
    c->end = chunks->data + chunks->size;
    c->next = chunks + 1;
}

/* Moves to the next non-empty chunk once the current one is used up. */
static void cursor_refill(cursor *c)
{
    while (c->p == c->end && c->next->data) {
        c->p = c->next->data;
        c->end = c->p + c->next->size;
        c->next++;
    }
}

static unsigned cursor_byte(cursor *c)
{
    if (c->p == c->end) cursor_refill(c);
    return *c->p++;
}

static void cursor_skip(cursor *c, uint32_t n)
{
    while (n > (uint32_t)(c->end - c->p)) {
        n -= (uint32_t)(c->end - c->p);
        c->p = c->end;
        cursor_refill(c);
        if (c->p == c->end) return;   /* end of data: only reachable with a corrupt scene */
    }
    c->p += n;
}

/* Steps over the subtree of one node at level l without drawing it: reads the masks of levels
 * l..d-1 inside the subtree only to count how far each cursor must move. */
static void skip_subtree(ctx *c, unsigned l)
{
    uint32_t n = 1;
    for (unsigned lev = l; lev < c->d; lev++) {
        uint32_t children = 0;
        for (uint32_t i = 0; i < n; i++) children += popcount8[cursor_byte(&c->mask[lev])];
        n = children;
    }
    cursor_skip(&c->color, n);
}

/* Draws the children of one node at level d-1: the hot loop, one pixel per set bit. */
static void draw_leaves(ctx *c, unsigned m, int32_t x, int32_t y, int32_t z, int clip)
{
    const unsigned l = c->d - 1;
    const int32_t *vx = c->vx[l], *vy = c->vy[l], *vz = c->vz[l];
    if (c->color.p == c->color.end) cursor_refill(&c->color);  /* siblings never straddle chunks */
    const uint8_t *col = c->color.p;
    c->color.p += popcount8[m];
    uint8_t *fb = c->fb;
    uint16_t *zb = c->zb;
    const int32_t w = c->w;
    if (!clip) {
        c->points += popcount8[m];
        for (; m; m &= m - 1, col++) {
            int k = lowest_bit(m);
            int32_t fx = x + vx[k], fy = y + vy[k];
            int32_t px = fx >> F, py = fy >> F;
            uint16_t depth = DEPTH_OF(z + vz[k]);
            int32_t i = py * w + px;
            MC_PLOT_HOOK(fx, fy, col);
            if (depth < zb[i]) { zb[i] = depth; fb[i] = *col; }
        }
        return;
    }
    for (; m; m &= m - 1, col++) {
        int k = lowest_bit(m);
        int32_t fx = x + vx[k], fy = y + vy[k];
        int32_t px = fx >> F, py = fy >> F;
        if ((uint32_t)px >= (uint32_t)w || (uint32_t)py >= (uint32_t)c->h) continue;
        uint16_t depth = DEPTH_OF(z + vz[k]);
        int32_t i = py * w + px;
        c->points++;
        MC_PLOT_HOOK(fx, fy, col);
        if (depth < zb[i]) { zb[i] = depth; fb[i] = *col; }
    }
}

/* Perspective variant of draw_leaves: each point divides by its own distance (exact, not
 * linearised, so it places points as the double reference does). Points nearer than the near plane
 * (1/64 cube side in front of the eye) are not drawn. */
static void draw_leaves_perspective(ctx *c, unsigned m, int32_t x, int32_t y, int32_t z)
{
    const unsigned l = c->d - 1;
    const int32_t *vx = c->vx[l], *vy = c->vy[l], *vz = c->vz[l];
    if (c->color.p == c->color.end) cursor_refill(&c->color);
    const uint8_t *col = c->color.p;
    c->color.p += popcount8[m];
    for (; m; m &= m - 1, col++) {
        int k = lowest_bit(m);
        int32_t zk = z + vz[k];
        int64_t dist = c->eye + zk - c->radius[0];       /* z carries a +radius offset */
        if (dist < c->near) continue;
        int64_t q = (c->eye << 24) / dist;                /* magnification, Q24, at most 2^38 */
        /* exact and saturating: near the eye the magnification reaches 2^14 */
        int64_t ox = mc_mul_shift64(x + vx[k], q, 24), oy = mc_mul_shift64(y + vy[k], q, 24);
        if (ox < -c->cx || oy < -c->cy || ox >= c->wf - c->cx || oy >= c->hf - c->cy) continue;
        int32_t fx = (int32_t)(c->cx + ox), fy = (int32_t)(c->cy + oy);
        int32_t px = fx >> F, py = fy >> F;
        int32_t i = py * c->w + px;
        uint16_t depth = DEPTH_OF(zk);
        c->points++;
        MC_PLOT_HOOK(fx, fy, col);
        if (depth < c->zb[i]) { c->zb[i] = depth; c->fb[i] = *col; }
    }
}

/* 0: partly on screen, 1: wholly on screen, -1: wholly off screen (orthographic only). */
static int classify(const ctx *c, int32_t x, int32_t y, int32_t r)
{
    if (x + r < 0 || y + r < 0 || x - r >= c->wf || y - r >= c->hf) return -1;
    return x - r >= 0 && y - r >= 0 && x + r < c->wf && y + r < c->hf;
}

/* Visits one node at level l < d whose centre is at (x, y, z). clip: the node may reach off screen. */
static void visit(ctx *c, unsigned l, int32_t x, int32_t y, int32_t z, int clip)
{
    if (l == MC_ABORT_LEVEL && c->abort) {
        c->polls++;
        if (c->abort(c->user)) { c->aborted = 1; return; }
    }
    unsigned m = cursor_byte(&c->mask[l]);
    if (l + 1 == c->d) {
        if (c->perspective) draw_leaves_perspective(c, m, x, y, z);
        else draw_leaves(c, m, x, y, z, clip);
        return;
    }
    const int32_t *vx = c->vx[l], *vy = c->vy[l], *vz = c->vz[l];
    for (; m; m &= m - 1) {
        int k = lowest_bit(m);
        int32_t cx = x + vx[k], cy = y + vy[k];
        int child_clip = clip;
        if (clip && !c->perspective) {
            int where = classify(c, cx, cy, c->radius[l + 1]);
            if (where < 0) { skip_subtree(c, l + 1); continue; }
            child_clip = !where;
        }
        visit(c, l + 1, cx, cy, z + vz[k], child_clip);
        if (c->aborted) return;
    }
}

/* Builds the per-level displacement vectors. Each is rounded once from the exact product of the
 * Q30 rotation and the Q16 scale, so a leaf's position is off by at most (d + 1) / 2 units of Q F
 * per axis: the root's rounding plus one per level. */
static void setup_vectors(ctx *c, const mc_view *v)
{
    int32_t r[3][3];
    mc_view_rotation(v, r);
    uint32_t side = (uint32_t)(c->w < c->h ? c->w : c->h);
    int64_t scale = (int64_t)v->zoom * side;       /* pixels per cube side, Q16 */
    for (unsigned l = 0; l < c->d; l++) {
        for (int k = 0; k < 8; k++) {
            int64_t sx = k & 1 ? 1 : -1, sy = k & 2 ? 1 : -1, sz = k & 4 ? 1 : -1;
            /* child k's centre is +-1/4 of the node's side 2^-l from its parent's: 2^-(l+2) */
            int64_t ex = sx * r[0][0] + sy * r[0][1] + sz * r[0][2];
            int64_t ey = sx * r[1][0] + sy * r[1][1] + sz * r[1][2];
            int64_t ez = sx * r[2][0] + sy * r[2][1] + sz * r[2][2];
            c->vx[l][k] = (int32_t)mc_mul_shift64(ex, scale, 30 + 16 + (int)l + 2 - F);
            c->vy[l][k] = (int32_t)-mc_mul_shift64(ey, scale, 30 + 16 + (int)l + 2 - F);
            c->vz[l][k] = (int32_t)-mc_mul_shift64(ez, scale, 30 + 16 + (int)l + 2 - F);
        }
    }
    for (unsigned l = 0; l <= c->d; l++)
        c->radius[l] = (int32_t)mc_mul_shift64(scale, HALF_SQRT3_Q30, 30 + 16 + (int)l - F) + 2;
    c->zshift = 0;
    while (((uint32_t)(2 * c->radius[0]) >> c->zshift) >= MC_DEPTH_EMPTY - 1) c->zshift++;
    c->eye = mc_mul_shift64(v->eye, scale, 32 - F);                 /* Q16 sides * Q16 px -> Q F px */
    c->near = mc_mul_shift64(scale, (int64_t)1 << F, 16 + 6);        /* 1/64 cube side, Q F px */
}

void mc_clear(const mc_target *t)
{
    uint32_t n = (uint32_t)t->width * t->height;
    for (uint32_t i = 0; i < n; i++) { t->depth[i] = MC_DEPTH_EMPTY; t->color[i] = 0; }
}

int mc_render(const mc_scene *scene, const mc_view *view, unsigned depth, const mc_target *t,
              mc_abort_fn abort, void *user, mc_stats *stats)
{
    if (!scene || !view || !t || !t->color || !t->depth) return MC_ERR_ARG;
    if (depth < 1 || depth > scene->depth || depth > MC_MAX_DEPTH) return MC_ERR_DEPTH;
    if (t->width == 0 || t->height == 0 || t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX)
        return MC_ERR_SIZE;

    ctx c;
    mc_view v = mc_view_clamp(view, t->width, t->height);
    c.fb = t->color;
    c.zb = t->depth;
    c.w = t->width;
    c.h = t->height;
    c.wf = c.w << F;
    c.hf = c.h << F;
    c.d = depth;
    c.perspective = v.projection == MC_PERSPECTIVE;
    c.abort = abort;
    c.user = user;
    c.points = c.polls = 0;
    c.aborted = 0;
    for (unsigned l = 0; l < depth; l++) cursor_init(&c.mask[l], scene->levels[l].masks);
    cursor_init(&c.color, scene->levels[depth].colors);
    setup_vectors(&c, &v);

    /* the root's centre: the screen centre plus translation (orthographic), or the view axis
     * (perspective: projected per point); depth offset by the bounding radius to keep it positive */
    int32_t centre_x = (int32_t)(((int64_t)c.w << (F - 1)) + ((int64_t)v.tx << F));
    int32_t centre_y = (int32_t)(((int64_t)c.h << (F - 1)) + ((int64_t)v.ty << F));
    if (c.perspective) {
        c.cx = centre_x;
        c.cy = centre_y;
        visit(&c, 0, 0, 0, c.radius[0], 1);
    } else {
        int where = classify(&c, centre_x, centre_y, c.radius[0]);
        if (where >= 0) visit(&c, 0, centre_x, centre_y, c.radius[0], !where);
    }
    if (stats) {
        stats->points = c.points;
        stats->polls = c.polls;
        stats->aborted = c.aborted;
    }
    return MC_OK;
}
