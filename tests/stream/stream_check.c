/* Checks the stream reader (runtime/src/stream.c) against the bake it was written from: linked with
 * a bake made with --emit stream (its mc_app_model) and given that bake's NAME.mcs.
 *
 *   stream_check prefixes FILE.mcs N SEED   N random cuts (and every level's end, and one byte either
 *       side): the prefix fed in random pieces draws exactly the level the bytes allow (from the
 *       records' ends, computed here from the file), and its frames at that level equal the baked
 *       octree's at the same depth, colour and depth buffers byte for byte, at four views
 *   stream_check corrupt FILE.mcs N SEED    N damaged streams (cut short, a byte changed, a byte
 *       inserted or dropped, the version changed with a valid header CRC, the total enlarged, bytes
 *       after the end): the reader reports an error (or, for a cut, mc_stream_end does), never
 *       crashes (run under ASan + UBSan), never draws a level the damage reached, and what it still
 *       draws equals the baked octree's frame at that depth (every 8th case, at one view)
 *   stream_check forged FILE.mcs N SEED     N streams with a byte changed and every CRC made valid
 *       again (what CRCs cannot catch): each is refused by a check of what the renderer relies on, or
 *       taken and drawn at every depth it offers (a mesh also coarsened) without a fault (ASan +
 *       UBSan); prints how many each check refused. A version-2 stream also with its first split's
 *       first face made to start at the split vertex twice: refused in that record
 *   stream_check mesh FILE.mcs N SEED       (a version-2 or -3 stream, bake --as both) N random cuts in its
 *       mesh part, and every mesh record's end and a byte either side: the prefix draws exactly the
 *       mesh level the bytes allow, and its frames equal the baked mesh's at that level (--lod):
 *       shaded at two views, and once the adjacency is in, lines at one
 *   stream_check arrays FILE.mcs            (a version-2 or -3 stream) the whole stream read: the mesh
 *       arrays it fills (positions, tree, splits, split faces, corners, adjacency) and the face bits it works out
 *       equal the bake's byte for byte;
 *       prints the base's and splits' bytes per split
 *   stream_check first FILE.mcs             prints the bytes before the first drawable level and each
 *       further level, as shares of the stream (and the mesh's first level and lines, if any)
 * With a mesh part, the corrupt and forged modes check the mesh level as the octree's depth: never
 * one the damage reached, equal to the bake's; whatever a forged stream offers drawn without a fault.
 * Prints one "ok ..." or "FAIL ..." line per mode; exits non-zero on a failure.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/app.h>
#include <modelc/modelc.h>
#include <modelc/stream.h>
#include "forge.h"
#include "mesh_arrays.h"
#include "../../runtime/front/common/mesh_frame.h"

#define W 160
#define H 120
static uint8_t fb_a[W * H], fb_b[W * H];
static uint16_t zb_a[W * H], zb_b[W * H];
static uint8_t *file;
static uint32_t file_len;
static uint8_t *work;   /* a damaged copy */
static uint8_t *buf;    /* the reader's buffer */
static uint32_t level_end[MC_MAX_DEPTH + 2];   /* level_end[d]: bytes that make depth d drawable */
static unsigned depth_max;
static int views_all = 1;
/* the mesh part's records that raise its drawable level: where each ends, and the level */
static uint32_t mesh_end[256], mesh_level_at[256], lines_end;
static unsigned mesh_records;
static uint64_t level_bytes;   /* the mesh's base and split records: what its levels of detail take */
static void *anc_stream, *anc_bake;   /* ancestor maps of the stream's mesh and the bake's */
static uint8_t *facing_stream, *facing_bake;   /* check_drawn: all four views, or one at random (the corrupt mode's many cases) */

static uint64_t rng = 1;
static uint32_t rnd(uint32_t n)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return n ? (uint32_t)((rng >> 33) % n) : 0;
}

static uint32_t le32(const uint8_t *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }

/* The records' ends, walked here independently of the reader. */
static int index_file(void)
{
    if (file_len < MC_STREAM_HEADER_BYTES) return -1;
    depth_max = file[6];
    uint32_t at = MC_STREAM_HEADER_BYTES, base = 0;
    while (at + 8 <= file_len) {
        const unsigned kind = file[at], level = file[at + 1];
        const uint8_t *p = file + at + 8;
        at += 12 + le32(file + at + 4);
        if (at > file_len) break;
        if (kind == 2 && level <= MC_MAX_DEPTH) level_end[level] = at;
        if (kind == 4) base = le32(p + 4);
        if ((kind == 5 || kind == 6 || kind == 8) && mesh_records < 256) {
            mesh_end[mesh_records] = at;
            mesh_level_at[mesh_records++] = base + (kind != 5 ? le32(p) + le32(p + 4) : 0);
        }
        if (kind == 5 || kind == 6 || kind == 8) level_bytes += 12u + le32(p - 4);   /* the record, framing and all */
        if (kind == 7 || kind == 9) lines_end = at;
    }
    return at == file_len ? 0 : -1;
}

static unsigned expected_depth(uint32_t cut)
{
    unsigned d = 0;
    for (unsigned l = 1; l <= depth_max; l++)
        if (level_end[l] && level_end[l] <= cut) d = l;
    return d;
}

static uint32_t expected_mesh_level(uint32_t cut)
{
    uint32_t level = 0;
    for (unsigned i = 0; i < mesh_records; i++)
        if (mesh_end[i] <= cut) level = mesh_level_at[i];
    return level;
}

static int feed_pieces(mc_stream *s, const uint8_t *p, uint32_t n)
{
    int rc = MC_STREAM_OK;
    while (n > 0 && rc == MC_STREAM_OK) {
        uint32_t k = rnd(4) == 0 ? 1 + rnd(16) : 1 + rnd(n < 70000 ? n : 70000);
        if (k > n) k = n;
        rc = mc_stream_feed(s, p, k);
        p += k;
        n -= k;
    }
    return rc;
}

/* The stream's octree and the bake's at depth d, drawn at one view: equal? */
static int frames_equal(const mc_octree *o, unsigned d, int view)
{
    mc_view v = mc_view_default();
    v.yaw = view * 1100;
    v.pitch = view * 300 - 400;
    v.zoom = 65536 + view * 20000;
    const mc_target a = {fb_a, zb_a, W, H}, b = {fb_b, zb_b, W, H};
    mc_clear(&a);
    mc_clear(&b);
    const int ra = mc_octree_render(o, &v, d, NULL, &a, NULL, NULL, NULL);
    const int rb = mc_octree_render(mc_app_model.model->octree, &v, d, NULL, &b, NULL, NULL, NULL);
    return ra == rb && !memcmp(fb_a, fb_b, sizeof fb_a) && !memcmp(zb_a, zb_b, sizeof zb_a);
}

static mc_view mesh_view(int view)
{
    mc_view v = mc_view_default();
    v.yaw = view * 1500 + 200;
    v.pitch = view * 500 - 300;
    v.zoom = 65536 + view * 12000;
    v.projection = view & 1 ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    return v;
}

/* The stream's mesh and the bake's at level `level`, drawn in a style at one view: equal? */
static int mesh_equal(const mc_pmesh *pm, uint32_t level, mc_front_style style, int view)
{
    const mc_pmesh *bake = mc_app_model.model->pmesh;
    mc_pmesh_lod a, b;
    mc_pmesh_lod_init(&a, pm, anc_stream);
    mc_pmesh_lod_init(&b, bake, anc_bake);
    if (mc_pmesh_lod_set(&a, level) != level || mc_pmesh_lod_set(&b, level) != level || a.faces != b.faces) return 0;
    const mc_view v = mesh_view(view);
    const mc_target ta = {fb_a, zb_a, W, H}, tb = {fb_b, zb_b, W, H};
    memset(facing_stream, 0, MC_MESH_LINES_BYTES(bake->faces));
    memset(facing_bake, 0, MC_MESH_LINES_BYTES(bake->faces));
    const int ra = mc_front_mesh_frame(&a, facing_stream, NULL, NULL, &v, style, &ta, NULL);
    const int rb = mc_front_mesh_frame(&b, facing_bake, NULL, NULL, &v, style, &tb, NULL);
    return ra == MC_OK && rb == MC_OK && !memcmp(fb_a, fb_b, sizeof fb_a) && !memcmp(zb_a, zb_b, sizeof zb_a);
}

/* The stream's mesh part against the bake: its level, its adjacency, its frames. */
static int check_mesh(const mc_stream *s, const char *what, uint32_t arg, int views)
{
    const uint32_t level = mc_stream_mesh_level(s);
    const mc_pmesh *pm = mc_stream_pmesh(s);
    if (!level) return pm ? printf("FAIL %s %u: a mesh descriptor before its base\n", what, arg), -1 : 0;
    const mc_pmesh *bake = mc_app_model.model->pmesh;
    if (!pm || pm->vertices != bake->vertices || pm->base_vertices != bake->base_vertices || pm->faces != bake->faces ||
        pm->closed != bake->closed || pm->palette_size != bake->palette_size ||
        memcmp(pm->palette, bake->palette, 3u * pm->palette_size) || pm->crease_cos != bake->crease_cos) {
        printf("FAIL %s %u: the mesh descriptor at level %u is not the bake's\n", what, arg, level);
        return -1;
    }
    for (int view = 0; view < views; view++) {
        const int lines = pm->opposite && view == views - 1;
        if (!mesh_equal(pm, level, lines ? MC_FRONT_LINES : MC_FRONT_SHADED, views == 1 ? (int)rnd(3) : view)) {
            printf("FAIL %s %u: mesh level %u %s differs from the bake's\n", what, arg, level, lines ? "lines" : "shaded");
            return -1;
        }
    }
    return 0;
}

static int check_drawn(const mc_stream *s, const char *what, uint32_t arg)
{
    if (mc_app_model.model->pmesh && check_mesh(s, what, arg, views_all ? 2 : 1)) return -1;
    const unsigned d = mc_stream_depth(s);
    if (!d) return 0;
    const mc_octree *o = mc_stream_octree(s);
    if (!o || o->depth != d || o->palette_size != mc_app_model.model->octree->palette_size ||
        memcmp(o->palette, mc_app_model.model->octree->palette, 3u * o->palette_size)) {
        printf("FAIL %s %u: the descriptor at depth %u is not the bake's\n", what, arg, d);
        return -1;
    }
    for (int view = 0; view < 4; view++)
        if ((views_all || view == (int)rnd(4)) && !frames_equal(o, d, view)) {
            printf("FAIL %s %u: depth %u view %d differs from the bake's frame\n", what, arg, d, view);
            return -1;
        }
    return 0;
}

static int prefixes(int n)
{
    uint32_t cuts[4 * MC_MAX_DEPTH + 8];
    int nc = 0;
    for (unsigned l = 1; l <= depth_max; l++) {
        cuts[nc++] = level_end[l] - 1;
        cuts[nc++] = level_end[l];
        if (level_end[l] < file_len) cuts[nc++] = level_end[l] + 1;
    }
    int checked = 0;
    for (int i = 0; i < nc + n; i++) {
        const uint32_t cut = i < nc ? cuts[i] : rnd(file_len + 1);
        mc_stream s;
        mc_stream_init(&s, buf, mc_app_model.stream_cap);
        const int rc = feed_pieces(&s, file, cut);
        const int end = mc_stream_end(&s);
        if (rc != MC_STREAM_OK || (cut == file_len) != (end == MC_STREAM_OK) ||
            (cut < file_len && end != MC_STREAM_ERR_TRUNCATED)) {
            printf("FAIL prefix %u: feed %s, end %s\n", cut, mc_stream_error_name(rc), mc_stream_error_name(end));
            return -1;
        }
        if (mc_stream_depth(&s) != expected_depth(cut)) {
            printf("FAIL prefix %u: draws depth %u, the bytes allow %u\n", cut, mc_stream_depth(&s), expected_depth(cut));
            return -1;
        }
        if (check_drawn(&s, "prefix", cut)) return -1;
        checked++;
    }
    printf("ok prefixes: %d cuts (every level's end and a byte either side, then random), each the depth its bytes allow, frames equal the bake's at 4 views\n",
           checked);
    return 0;
}

static int mesh_prefixes(int n)
{
    if (!mesh_records || !mc_app_model.model->pmesh) {
        printf("FAIL mesh: the stream or the bake has no mesh part\n");
        return -1;
    }
    uint32_t cuts[3 * 256 + 3];
    int nc = 0;
    for (unsigned r = 0; r < mesh_records; r++) cuts[nc++] = mesh_end[r] - 1, cuts[nc++] = mesh_end[r], cuts[nc++] = mesh_end[r] + 1;
    cuts[nc++] = lines_end - 1, cuts[nc++] = lines_end;
    const uint32_t from = mesh_end[0] - 1;
    for (int i = 0; i < nc + n; i++) {
        const uint32_t cut = i < nc ? cuts[i] : from + rnd(file_len - from + 1);
        mc_stream s;
        mc_stream_init(&s, buf, mc_app_model.stream_cap);
        const int rc = feed_pieces(&s, file, cut);
        if (rc != MC_STREAM_OK) {
            printf("FAIL mesh prefix %u: feed %s at byte %u\n", cut, mc_stream_error_name(rc), s.error_at);
            return -1;
        }
        if (mc_stream_mesh_level(&s) != expected_mesh_level(cut) || (mc_stream_pmesh(&s) && (mc_stream_pmesh(&s)->opposite != 0) != (cut >= lines_end))) {
            printf("FAIL mesh prefix %u: mesh level %u, the bytes allow %u\n", cut, mc_stream_mesh_level(&s), expected_mesh_level(cut));
            return -1;
        }
        if (check_mesh(&s, "mesh prefix", cut, 2)) return -1;
    }
    printf("ok mesh: %d cuts (every mesh record's end and a byte either side, then random in the mesh part), each the mesh level its bytes allow (%u records, levels %u to %u), frames equal the bake's at that level: shaded at 2 views, lines at 1 once the adjacency is in\n",
           nc + n, mesh_records, mesh_level_at[0], mesh_level_at[mesh_records - 1]);
    return 0;
}

static int corrupt(int n)
{
    views_all = 0;
    int kinds[7] = {0};
    for (int i = 0; i < n; i++) {
        uint32_t len = file_len, first_bad;   /* the first byte that differs from the good stream */
        memcpy(work, file, file_len);
        const int kind = (int)rnd(7);
        kinds[kind]++;
        switch (kind) {
        case 0:   /* cut short */
            len = rnd(file_len);
            first_bad = len;
            break;
        case 1: { /* one byte changed */
            first_bad = rnd(file_len);
            work[first_bad] ^= (uint8_t)(1 + rnd(255));
            break;
        }
        case 2:   /* one byte inserted */
            first_bad = rnd(file_len);
            memmove(work + first_bad + 1, work + first_bad, file_len - first_bad);
            work[first_bad] = (uint8_t)rnd(256);
            len = file_len + 1;
            break;
        case 3:   /* one byte dropped */
            first_bad = rnd(file_len);
            memmove(work + first_bad, work + first_bad + 1, file_len - first_bad - 1);
            len = file_len - 1;
            break;
        case 4: { /* another version, the header's CRC made valid */
            do work[4] = (uint8_t)(1 + rnd(200)); while (work[4] == file[4]);
            const uint32_t c = mc_stream_crc32(0, work, 16);
            work[16] = (uint8_t)c; work[17] = (uint8_t)(c >> 8); work[18] = (uint8_t)(c >> 16); work[19] = (uint8_t)(c >> 24);
            first_bad = 4;
            break;
        }
        case 5: { /* the total enlarged, the header's CRC made valid */
            const uint32_t t = file_len + 1 + rnd(1000);
            work[12] = (uint8_t)t; work[13] = (uint8_t)(t >> 8); work[14] = (uint8_t)(t >> 16); work[15] = (uint8_t)(t >> 24);
            const uint32_t c = mc_stream_crc32(0, work, 16);
            work[16] = (uint8_t)c; work[17] = (uint8_t)(c >> 8); work[18] = (uint8_t)(c >> 16); work[19] = (uint8_t)(c >> 24);
            first_bad = file_len - MC_STREAM_RECORD_BYTES;   /* the end record is then not where the total says */
            break;
        }
        default:  /* bytes after the end */
            len = file_len + 1 + rnd(100);
            for (uint32_t k = file_len; k < len; k++) work[k] = (uint8_t)rnd(256);
            first_bad = file_len;
            break;
        }
        mc_stream s;
        mc_stream_init(&s, buf, mc_app_model.stream_cap + 2000);
        const int rc = feed_pieces(&s, work, len);
        const int end = mc_stream_end(&s);
        if (end == MC_STREAM_OK) {
            printf("FAIL corrupt case %d (kind %d at byte %u): the damaged stream was taken as complete\n", i, kind, first_bad);
            return -1;
        }
        (void)rc;
        /* nothing the damage reached may be drawn: the deepest level drawn ends before it */
        const unsigned d = mc_stream_depth(&s);
        if (d && level_end[d] > first_bad) {
            printf("FAIL corrupt case %d (kind %d at byte %u): draws depth %u, whose bytes end at %u\n", i, kind, first_bad, d,
                   level_end[d]);
            return -1;
        }
        const uint32_t ml = mc_stream_mesh_level(&s);
        for (unsigned r = 0; ml && r < mesh_records; r++)
            if (mesh_level_at[r] == ml && mesh_end[r] > first_bad) {
                printf("FAIL corrupt case %d (kind %d at byte %u): draws mesh level %u, whose bytes end at %u\n", i, kind,
                       first_bad, ml, mesh_end[r]);
                return -1;
            }
        if (mc_stream_pmesh(&s) && mc_stream_pmesh(&s)->opposite && lines_end > first_bad) {
            printf("FAIL corrupt case %d (kind %d at byte %u): took the adjacency, which ends at %u\n", i, kind, first_bad, lines_end);
            return -1;
        }
        if (i % 8 == 0 && check_drawn(&s, "corrupt case", (uint32_t)i)) return -1;
    }
    printf("ok corrupt: %d damaged streams (cut %d, byte changed %d, inserted %d, dropped %d, version %d, total %d, "
           "trailing %d): each refused, none drew a level the damage reached, the levels before it equal the bake's (every 8th case, one of 4 views)\n",
           n, kinds[0], kinds[1], kinds[2], kinds[3], kinds[4], kinds[5], kinds[6]);
    return 0;
}

/* A version-2 stream whose first split's first face has its vertex as corners 0 and 1, CRCs made
 * valid: refused (MC_STREAM_ERR_MESH, in that record), for a collapse reads the parent from them.
 * 1: so refused; 0: not a version-2 stream; -1: taken (printed). */
static int forged_first_face(void)
{
    if (file[4] != 2) return 0;
    unsigned ib = 0;
    for (uint32_t at = MC_STREAM_HEADER_BYTES; at + 8 <= file_len; at += 12 + le32(file + at + 4)) {
        const uint8_t *p = file + at + 8;
        if (file[at] == 4) ib = p[20];
        if (file[at] != 6 || !ib) continue;
        memcpy(work, file, file_len);
        uint8_t *split = work + at + 8 + 8, *face = split + 3u * ib + 7u;
        memcpy(face, split, ib);
        memcpy(face + ib, split, ib);
        forge_crcs(work, file_len);
        mc_stream s;
        mc_stream_init(&s, buf, mc_app_model.stream_cap + 2000);
        feed_pieces(&s, work, file_len);
        if (mc_stream_end(&s) != MC_STREAM_ERR_MESH || s.error_at < at || s.error_at >= at + 12 + le32(file + at + 4)) {
            printf("FAIL forged: a split whose first face does not start with its vertex and its parent taken (%s at %u, "
                   "its record at %u)\n", mc_stream_error_name(mc_stream_end(&s)), s.error_at, at);
            return -1;
        }
        return 1;
    }
    printf("FAIL forged: no split record in a version-2 stream\n");
    return -1;
}

static int forged(int n)
{
    int refused[16] = {0}, taken = 0;
    const int first_face = forged_first_face();
    if (first_face < 0) return -1;
    for (int i = 0; i < n; i++) {
        memcpy(work, file, file_len);
        const uint32_t at = rnd(file_len);
        work[at] = (uint8_t)(rnd(4) == 0 ? 0 : work[at] ^ (1u << rnd(8)));
        forge_crcs(work, file_len);
        mc_stream s;
        mc_stream_init(&s, buf, mc_app_model.stream_cap + 2000);
        feed_pieces(&s, work, file_len);
        const int end = mc_stream_end(&s);
        if (end == MC_STREAM_OK) taken++;
        else refused[-end & 15]++;
        const mc_pmesh *pm = mc_stream_pmesh(&s);
        if (pm) {   /* its mesh at the level it offers, shaded and (with the adjacency) in lines */
            mc_pmesh_lod lod;
            mc_pmesh_lod_init(&lod, pm, anc_stream);
            mc_pmesh_lod_set(&lod, mc_stream_mesh_level(&s));
            const mc_view v = mesh_view((int)rnd(3));
            const mc_target t = {fb_a, zb_a, W, H};
            memset(facing_stream, 0, MC_MESH_LINES_BYTES(pm->faces));
            for (int style = 1; style <= (pm->opposite ? 3 : 1); style++)
                if (mc_front_mesh_frame(&lod, facing_stream, NULL, NULL, &v, (mc_front_style)style, &t, NULL) != MC_OK) {
                    printf("FAIL forged case %d (byte %u): its mesh does not render in style %d\n", i, at, style);
                    return -1;
                }
            /* and coarsened (each collapse reads its parent through the map, pmesh.h), drawn again */
            mc_pmesh_lod_set(&lod, pm->base_vertices + rnd(lod.level - pm->base_vertices + 1u));
            if (mc_front_mesh_frame(&lod, facing_stream, NULL, NULL, &v, MC_FRONT_SHADED, &t, NULL) != MC_OK) {
                printf("FAIL forged case %d (byte %u): its mesh coarsened does not render\n", i, at);
                return -1;
            }
        }
        const mc_octree *o = mc_stream_octree(&s);
        for (unsigned d = 1; o && d <= o->depth; d++) {   /* whatever was taken draws without a fault */
            mc_view v = mc_view_default();
            v.yaw = (int32_t)rnd(4096);
            const mc_target t = {fb_a, zb_a, W, H};
            mc_clear(&t);
            if (mc_octree_render(o, &v, d, NULL, &t, NULL, NULL, NULL) != MC_OK) {
                printf("FAIL forged case %d (byte %u): depth %u of a taken stream does not render\n", i, at, d);
                return -1;
            }
        }
    }
    printf("ok forged: %d streams with a byte changed and valid CRCs: %d taken (a colour, cone axis, vertex position or "
           "corner changed, or the change undone) and drawn at every depth (and a mesh part at its level in every style it offers, and coarsened) without a fault; refused:", n, taken);
    for (int e = 1; e < 16; e++)
        if (refused[e]) printf(" %s %d", mc_stream_error_name(-e), refused[e]);
    if (first_face) printf("; and a split whose first face does not start at its vertex and its parent, refused in its record");
    printf("\n");
    return 0;
}

/* The whole stream fed at once: the mesh arrays the reader fills equal the bake's byte for byte. */
static int arrays(void)
{
    const mc_pmesh *bake = mc_app_model.model->pmesh;
    mc_stream s;
    mc_stream_init(&s, buf, mc_app_model.stream_cap);
    if (!bake || mc_stream_feed(&s, file, file_len) != MC_STREAM_OK || mc_stream_end(&s) != MC_STREAM_OK || !mc_stream_pmesh(&s)) {
        printf("FAIL arrays: the stream (%s at byte %u) or the bake has no complete mesh part\n", mc_stream_error_name(s.error), s.error_at);
        return -1;
    }
    const mc_pmesh *pm = mc_stream_pmesh(&s);
    const uint32_t S = bake->vertices - bake->base_vertices;
    if (pm->vertices != bake->vertices || pm->base_vertices != bake->base_vertices || pm->faces != bake->faces ||
        pm->edges != bake->edges || pm->index_bytes != bake->index_bytes || pm->half_bytes != bake->half_bytes) {
        printf("FAIL arrays: the stream's mesh counts or widths are not the bake's\n");
        return -1;
    }
    uint32_t record;
    uint64_t bytes;
    const char *differs = mesh_arrays_differ(pm, bake, &record, &bytes);
    if (differs) {
        printf("FAIL arrays: %s record %u differs from the bake's\n", differs, record);
        return -1;
    }
    printf("ok arrays: version %u, the reader's mesh arrays (positions, tree, splits, corners, opposites, edge order, face bits: "
           "%llu bytes) equal the bake's; base and splits %.2f bytes per split in the stream (%llu bytes, %u splits)\n",
           file[4], (unsigned long long)bytes, S ? (double)level_bytes / S : 0.0, (unsigned long long)level_bytes, S);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s prefixes|corrupt|first FILE.mcs [N SEED]\n", argv[0]);
        return 2;
    }
    FILE *f = fopen(argv[2], "rb");
    if (!f) { perror(argv[2]); return 2; }
    fseek(f, 0, SEEK_END);
    file_len = (uint32_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    file = malloc(file_len + 1);
    const uint32_t cap = (mc_app_model.stream_cap > file_len ? mc_app_model.stream_cap : file_len) + 2000;
    work = malloc(file_len + 2000);
    buf = malloc(cap);
    if (mc_app_model.model->pmesh) {
        const mc_pmesh *pm = mc_app_model.model->pmesh;
        anc_stream = malloc(MC_PMESH_LOD_BYTES(pm->vertices, 4));
        anc_bake = malloc(MC_PMESH_LOD_BYTES(pm->vertices, 4));
        facing_stream = malloc(MC_MESH_LINES_BYTES(pm->faces));
        facing_bake = malloc(MC_MESH_LINES_BYTES(pm->faces));
    }
    if (!file || !work || !buf || fread(file, 1, file_len, f) != file_len) { fprintf(stderr, "cannot read %s\n", argv[2]); return 2; }
    fclose(f);
    if (index_file()) { printf("FAIL %s: its records do not end at its end\n", argv[2]); return 1; }
    const int n = argc > 3 ? atoi(argv[3]) : 100;
    rng = argc > 4 ? strtoull(argv[4], NULL, 10) : 1;
    if (!strcmp(argv[1], "prefixes")) return prefixes(n) ? 1 : 0;
    if (!strcmp(argv[1], "corrupt")) return corrupt(n) ? 1 : 0;
    if (!strcmp(argv[1], "forged")) return forged(n) ? 1 : 0;
    if (!strcmp(argv[1], "mesh")) return mesh_prefixes(n) ? 1 : 0;
    if (!strcmp(argv[1], "arrays")) return arrays() ? 1 : 0;
    if (!strcmp(argv[1], "first")) {
        printf("bytes %u", file_len);
        for (unsigned l = 1; l <= depth_max; l++) printf(" depth%u %u %.2f%%", l, level_end[l], 100.0 * level_end[l] / file_len);
        if (mesh_records)
            printf(" mesh%u %u %.2f%% lines %u %.2f%%", mesh_level_at[0], mesh_end[0], 100.0 * mesh_end[0] / file_len, lines_end,
                   100.0 * lines_end / file_len);
        printf("\n");
        return 0;
    }
    fprintf(stderr, "unknown mode %s\n", argv[1]);
    return 2;
}
