/* The particle filter over camera poses: see modelc/particles.h. */
#include "modelc/particles.h"
#include "modelc/detect.h"

/* the largest translation a particle takes, um (camera.h: below 2^28 per axis) */
#define T_MAX (((int32_t)1 << 28) - 1)

/* 2^(-i/16) in Q16, rounded: the weight's fraction */
static const uint32_t pow2_frac[16] = {65536, 62757, 60097, 57549, 55109, 52773, 50535, 48393,
                                       46341, 44376, 42495, 40693, 38968, 37316, 35734, 34219};

/* 2^(-x / 2^16) in Q16 for an exponent x >= 0 in Q16, truncated to sixteenths (0 below 2^-16) */
static uint32_t pow2_neg(uint32_t x)
{
    const uint32_t ip = x >> 16;
    return ip > 16 ? 0 : pow2_frac[(x >> 12) & 15u] >> ip;
}

/* *d = *s field by field (a struct assignment may become a memcpy call, which a freestanding
 * program does not have) */
static void copy(mc_particle *d, const mc_particle *s)
{
    for (int k = 0; k < 4; k++) d->q[k] = s->q[k];
    for (int k = 0; k < 3; k++) d->t[k] = s->t[k];
    d->weight = s->weight, d->visible = s->visible, d->matched = s->matched;
}

int mc_filter_init(mc_filter *f, const mc_filter_params *prm, mc_particle *p, mc_particle *spare, uint64_t seed,
                   const int32_t q[4], const int32_t t[3])
{
    if (!f || !prm || !p || !spare || !q || !t) return MC_ERR_ARG;
    if (!prm->particles || prm->particles > 65535u || prm->fresh >= prm->particles || prm->step_t < 0 ||
        prm->step_r < 0 || prm->step_t > (1 << 28) || prm->step_r > (1 << 28) || prm->fresh_r < 0 ||
        prm->fresh_r > (1 << 28) || prm->layers > 4 || !prm->sharpness ||
        prm->sharpness > 64 || prm->recall > 64 || (prm->dof != 3 && prm->dof != 6) || prm->detect > prm->fresh ||
        (prm->detect && (!prm->detect_stride || prm->detect_stride > 16 || prm->detect_reach > 1024)))
        return MC_ERR_ARG;
    for (int k = 0; k < 3; k++)
        if (prm->lo[k] > prm->hi[k] || prm->lo[k] < -T_MAX || prm->hi[k] > T_MAX || t[k] < -T_MAX || t[k] > T_MAX)
            return MC_ERR_ARG;
    int32_t u[4];
    if (mc_quat_unit(q, u) != MC_OK) return MC_ERR_ARG;
    mc_filter_params *fp = &f->prm;   /* field by field, as copy() */
    fp->particles = prm->particles, fp->fresh = prm->fresh, fp->step_t = prm->step_t, fp->step_r = prm->step_r;
    fp->fresh_r = prm->fresh_r, fp->layers = prm->layers ? prm->layers : 1;
    for (int k = 0; k < 3; k++) fp->lo[k] = prm->lo[k], fp->hi[k] = prm->hi[k];
    fp->min_visible = prm->min_visible, fp->sharpness = prm->sharpness, fp->recall = prm->recall, fp->dof = prm->dof;
    fp->detect = prm->detect, fp->detect_reach = prm->detect_reach, fp->detect_stride = prm->detect_stride;
    fp->detect_below = prm->detect_below;
    f->p = p, f->spare = spare;
    mc_rng_seed(&f->rng, seed, 0x7261636bu);
    for (uint32_t i = 0; i < prm->particles; i++) {
        for (int k = 0; k < 4; k++) p[i].q[k] = u[k];
        for (int k = 0; k < 3; k++) p[i].t[k] = t[k];
        p[i].weight = 65536u, p[i].visible = p[i].matched = 0;
    }
    copy(&f->estimate, &p[0]);
    f->confidence = 0;
    return MC_OK;
}

uint32_t mc_filter_weight(const mc_filter *f, uint32_t visible, uint32_t matched)
{
    if (!visible || visible < f->prm.min_visible) return 0;
    const uint32_t r = (uint32_t)(((uint64_t)matched << 16) / visible);   /* Q16, <= 65536 */
    return pow2_neg(f->prm.sharpness * (65536u - r));                     /* Q16 exponent, < 2^23 */
}

void mc_filter_recall(const mc_filter *f, mc_particle *p, uint32_t n)
{
    const uint32_t k = f->prm.recall;
    if (!k) return;
    uint32_t most = 0;
    for (uint32_t i = 0; i < n; i++)
        if (p[i].weight && p[i].matched > most) most = p[i].matched;
    if (!most) return;
    for (uint32_t i = 0; i < n; i++) {
        if (!p[i].weight) continue;
        /* k (1 - m / M) in Q16: below 64 * 2^16 */
        const uint32_t x = (uint32_t)(((uint64_t)(most - p[i].matched) * k << 16) / most);
        p[i].weight = (uint32_t)(((uint64_t)p[i].weight * pow2_neg(x)) >> 16);
    }
}

/* a step of s: four uniform integers in [-s, s], summed and halved */
static int32_t step(mc_rng *r, int32_t s)
{
    if (!s) return 0;
    int64_t sum = 0;
    for (int k = 0; k < 4; k++) sum += (int64_t)mc_rng_below(r, 2u * (uint32_t)s + 1u) - s;
    return (int32_t)(sum / 2);
}

static void quat_mul(const int32_t a[4], const int32_t b[4], int32_t out[4]);

/* Particle p moved: its translation by a step of step_t per axis (kept inside camera.h's range), its
 * orientation turned by (1, e1, e2, e3) of steps of step_r (none when step_r is 0). */
static void move(mc_rng *r, mc_particle *p, int32_t step_t, int32_t step_r)
{
    for (int k = 0; k < 3; k++) {
        const int32_t v = p->t[k] + step(r, step_t);
        p->t[k] = v > T_MAX ? T_MAX : v < -T_MAX ? -T_MAX : v;
    }
    if (!step_r) return;
    int32_t d[4], q[4];
    d[0] = 1 << 30;
    for (int k = 1; k < 4; k++) d[k] = step(r, step_r);
    quat_mul(p->q, d, q);
    mc_quat_unit(q, p->q);
}

/* a (x) b, Q30 quaternions (components at most 2^30 or so: each product below 2^61) */
static void quat_mul(const int32_t a[4], const int32_t b[4], int32_t out[4])
{
    const int64_t w = (int64_t)a[0] * b[0] - (int64_t)a[1] * b[1] - (int64_t)a[2] * b[2] - (int64_t)a[3] * b[3];
    const int64_t x = (int64_t)a[0] * b[1] + (int64_t)a[1] * b[0] + (int64_t)a[2] * b[3] - (int64_t)a[3] * b[2];
    const int64_t y = (int64_t)a[0] * b[2] - (int64_t)a[1] * b[3] + (int64_t)a[2] * b[0] + (int64_t)a[3] * b[1];
    const int64_t z = (int64_t)a[0] * b[3] + (int64_t)a[1] * b[2] - (int64_t)a[2] * b[1] + (int64_t)a[3] * b[0];
    /* shifted as a whole: mc_quat_unit makes it unit length again */
    out[0] = (int32_t)(w / ((int64_t)1 << 31)), out[1] = (int32_t)(x / ((int64_t)1 << 31));
    out[2] = (int32_t)(y / ((int64_t)1 << 31)), out[3] = (int32_t)(z / ((int64_t)1 << 31));
}

void mc_filter_resample(mc_rng *r, const mc_particle *src, uint32_t n, mc_particle *dst, uint32_t m)
{
    uint64_t total = 0;
    for (uint32_t i = 0; i < n; i++) total += src[i].weight;
    if (!total) {
        for (uint32_t k = 0; k < m; k++) copy(&dst[k], &src[k]);
        return;
    }
    /* draw k takes the particle whose interval [C(i-1) m, C(i) m) holds u + k W, u uniform in [0, W) */
    const uint64_t u = mc_rng_below(r, (uint32_t)total);
    uint64_t cum = src[0].weight;
    uint32_t i = 0;
    for (uint32_t k = 0; k < m; k++) {
        const uint64_t at = u + (uint64_t)k * total;
        while (cum * m <= at) cum += src[++i].weight;
        copy(&dst[k], &src[i]);
    }
}

/* Scores particle p's pose; returns what scoring returned. */
static int score(const mc_filter *f, const mc_track_view *view, mc_particle *p)
{
    mc_pose pose;
    mc_track_score s;
    if (mc_pose_set(&pose, p->q, p->t) != MC_OK) return MC_ERR_ARG;
    const int rc = mc_track_score_pose(view, &pose, &s);
    if (rc != MC_OK) return rc;
    p->visible = s.visible, p->matched = s.matched;
    p->weight = mc_filter_weight(f, s.visible, s.matched);
    return MC_OK;
}

int mc_filter_step(mc_filter *f, const mc_track_view *view, const int32_t orientation[4])
{
    const mc_filter_params *prm = &f->prm;
    const uint32_t n = prm->particles, drawn = n - prm->fresh;
    const int given = prm->dof == 3;
    int32_t g[4];
    g[0] = 1 << 30, g[1] = g[2] = g[3] = 0;
    if (given && (!orientation || mc_quat_unit(orientation, g) != MC_OK)) return MC_ERR_ARG;
    mc_rng *r = &f->rng;
    mc_filter_resample(r, f->p, n, f->spare, drawn);
    mc_particle *p = f->spare;
    /* fresh particles placed by the image search this frame: none while the estimate is confident,
     * nor without the recall term (step 4a, later layers only), which judges them */
    const uint32_t searched =
        prm->layers > 1 && prm->recall && f->confidence < prm->detect_below ? prm->detect : 0;
    for (uint32_t i = 0; i < n; i++) {
        if (i < drawn) {   /* motion */
            move(r, &p[i], prm->step_t, given ? 0 : prm->step_r);
        } else {           /* re-detection */
            const int search = i - drawn < searched;
            for (int k = 0; k < 3; k++)
                p[i].t[k] = search ? f->estimate.t[k]
                                   : prm->lo[k] + (int32_t)mc_rng_below(r, (uint32_t)((int64_t)prm->hi[k] - prm->lo[k]) + 1u);
            if (!given && !prm->fresh_r) {   /* any orientation */
                int32_t q[4];
                for (int k = 0; k < 4; k++) q[k] = step(r, 1 << 28);
                if (!(q[0] | q[1] | q[2] | q[3])) q[0] = 1;
                mc_quat_unit(q, p[i].q);
            } else if (!given) {             /* near the last estimate's */
                for (int k = 0; k < 4; k++) p[i].q[k] = f->estimate.q[k];
                move(r, &p[i], 0, prm->fresh_r);
            } else {
                for (int k = 0; k < 4; k++) p[i].q[k] = g[k];
            }
            if (search) {                    /* where the image fits that orientation best */
                mc_pose pose;
                int32_t dx, dy;
                if (mc_pose_set(&pose, p[i].q, p[i].t) != MC_OK) return MC_ERR_ARG;
                mc_detect_shift(view, &pose, prm->detect_reach, prm->detect_stride, &dx, &dy);
                mc_detect_move(view->cam, p[i].t, dx, dy, p[i].t);
            }
        }
        if (given)
            for (int k = 0; k < 4; k++) p[i].q[k] = g[k];
        const int rc = score(f, view, &p[i]);
        if (rc != MC_OK) return rc;
    }
    /* further layers: all N drawn again from the weights just found and moved by steps halved
     * each layer (an annealed search: the same frame, a finer look around the likely poses) */
    mc_track_view fine;   /* field by field: a struct copy may become a memcpy call */
    fine.model = view->model, fine.cam = view->cam, fine.sd = view->sd, fine.cache = view->cache;
    fine.tolerance = view->tolerance, fine.masks = view->fine ? view->fine : view->masks, fine.fine = 0;
    for (unsigned layer = 1; layer < prm->layers; layer++) {
        mc_particle *d = p == f->spare ? f->p : f->spare;
        mc_filter_resample(r, p, n, d, n);
        p = d;
        for (uint32_t i = 0; i < n; i++) {
            move(r, &p[i], prm->step_t >> layer, given ? 0 : prm->step_r >> layer);
            const int rc = score(f, &fine, &p[i]);
            if (rc != MC_OK) return rc;
        }
        mc_filter_recall(f, p, n);
    }
    if (p != f->p) f->spare = f->p, f->p = p;
    /* the estimate: weighted means, the orientations turned to the heaviest one's hemisphere */
    uint64_t total = 0;
    uint32_t best = 0;
    for (uint32_t i = 0; i < n; i++) {
        total += p[i].weight;
        if (p[i].weight > p[best].weight) best = i;
    }
    if (total) {
        int64_t st[3], sq[4];   /* zeroed in loops: an initialiser may become a memset call */
        for (int k = 0; k < 3; k++) st[k] = 0;
        for (int k = 0; k < 4; k++) sq[k] = 0;
        for (uint32_t i = 0; i < n; i++) {
            const int64_t w = p[i].weight;
            if (!w) continue;
            int64_t dot = 0;
            for (int k = 0; k < 4; k++) dot += (int64_t)p[i].q[k] * p[best].q[k] / 4;
            const int64_t sign = dot < 0 ? -1 : 1;
            for (int k = 0; k < 3; k++) st[k] += w * p[i].t[k];
            for (int k = 0; k < 4; k++) sq[k] += sign * w * p[i].q[k];
        }
        int32_t q[4];
        for (int k = 0; k < 3; k++) f->estimate.t[k] = (int32_t)(st[k] / (int64_t)total);
        for (int k = 0; k < 4; k++) q[k] = (int32_t)(sq[k] / (int64_t)total);
        if (mc_quat_unit(q, f->estimate.q) != MC_OK)
            for (int k = 0; k < 4; k++) f->estimate.q[k] = p[best].q[k];
    }
    if (given)
        for (int k = 0; k < 4; k++) f->estimate.q[k] = g[k];
    const int rc = score(f, view, &f->estimate);
    if (rc != MC_OK) return rc;
    f->confidence = f->estimate.visible && f->estimate.visible >= prm->min_visible
                        ? (uint32_t)(((uint64_t)f->estimate.matched << 16) / f->estimate.visible)
                        : 0;
    return MC_OK;
}
