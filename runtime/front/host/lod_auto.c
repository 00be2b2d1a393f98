/* The host viewer's automatic level of detail: see lod_auto.h. */
#include "lod_auto.h"

#include <math.h>

/* The weight of a new frame in its level's time: about three frames deep. */
#define LEVEL_WEIGHT 0.3
/* The exponent's range, and the least change of faces (a share) between two levels to measure it. */
#define EXPONENT_MIN 0.25
#define EXPONENT_MAX 1.5
#define EXPONENT_SPAN 0.1
/* The weight of a new measurement of the exponent (two levels' times, each with its view's drift) */
#define EXPONENT_WEIGHT 0.5

void mc_host_lod_auto_init(mc_host_lod_auto *a, double target_ms)
{
    a->target_ms = target_ms;
    a->level_ms = a->last_ms = 0;
    a->exponent = 1;
    a->level_faces = a->level_frames = a->last_faces = a->frames = 0;
    a->style = -1;
}

void mc_host_lod_auto_style(mc_host_lod_auto *a, int style)
{
    if (style == a->style) return;
    mc_host_lod_auto_init(a, a->target_ms);
    a->style = style;
}

mc_host_lod_plan mc_host_lod_auto_plan(const mc_host_lod_auto *a, uint32_t faces)
{
    mc_host_lod_plan p = {0, 0};
    if (!a->level_frames || faces != a->level_faces || !(a->level_ms > 0)) return p;
    if (fabs(a->level_ms - a->target_ms) <= MC_HOST_LOD_TRIGGER * a->target_ms) return p;
    const double want = faces * pow(a->target_ms / a->level_ms, 1 / a->exponent);
    p.move = 1;
    p.max_faces = want < 0 ? 0u : want > 4e9 ? 4000000000u : (uint32_t)want;
    return p;
}

void mc_host_lod_auto_frame(mc_host_lod_auto *a, uint32_t faces, double ms)
{
    if (a->frames++ == 0) return;   /* the first frame made the level's state from nothing */
    if (faces != a->level_faces || !a->level_frames) {   /* a new level: the one left is the last */
        if (a->level_frames) {
            /* the exponent between the level left and the one before it, each timed over its frames */
            if (a->last_faces && a->level_faces && a->last_ms > 0 && a->level_ms > 0) {
                const double span = log((double)a->level_faces / a->last_faces);
                if (fabs(span) >= EXPONENT_SPAN) {
                    double e = log(a->level_ms / a->last_ms) / span;
                    e = e < EXPONENT_MIN ? EXPONENT_MIN : e > EXPONENT_MAX ? EXPONENT_MAX : e;
                    a->exponent += (e - a->exponent) * EXPONENT_WEIGHT;
                }
            }
            a->last_faces = a->level_faces, a->last_ms = a->level_ms;
        }
        a->level_faces = faces, a->level_frames = 0;
    }
    a->level_ms = a->level_frames++ ? a->level_ms + (ms - a->level_ms) * LEVEL_WEIGHT : ms;
}
