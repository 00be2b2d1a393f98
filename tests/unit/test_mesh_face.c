/* mesh_face.h against double precision: a face's shade, its normal's 15 leading bits, the crease
 * test, and mc_mesh_face_bits on hand-made meshes laid out as the generator lays them out.
 *   - shade: mc_mesh_shade_of of random triangles (every size from a unit step to the whole cube,
 *     degenerate ones too) equals mc_mesh_shade_normal15 of their mc_mesh_normal15 normal, whatever
 *     the corners' order, and is the nearest k to 31 |n.z| / |n| in doubles, either neighbour within
 *     1/100 of a step of the rounding point (mesh_face.h);
 *   - crease: mc_mesh_crease_normals of random faces' normals is "the angle between them exceeds the
 *     crease angle" in doubles, at several crease angles, except within 1/1000 of the cosine;
 *   - face bits: a cube of twelve triangles, closed and with two faces left out (a border), in chunks
 *     of two records, with 2- and 4-byte index and half-edge fields: each face's shade (31 facing +-z, 0 otherwise), every cube edge a crease at 60
 *     degrees, no diagonal and no border edge one; the bits written over whatever the buffer held.
 * PCG32 with fixed seeds: runs are deterministic.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include <modelc/chunk.h>
#include <modelc/mesh_face.h>
#include <modelc/pmesh.h>
#include <modelc/rng.h>

/* a coordinate in -32768 .. 32767 around c, at most r away */
static int32_t near(mc_rng *g, int32_t c, uint32_t r)
{
    int64_t v = (int64_t)c + (int64_t)(mc_rng_next(g) % (2u * r + 1u)) - (int64_t)r;
    return (int32_t)(v < -32768 ? -32768 : v > 32767 ? 32767 : v);
}

/* a random triangle: corners within r of a random centre; now and then two corners equal or the
 * three in a line (no area) */
static void random_face(mc_rng *g, int32_t p[3][3])
{
    static const uint32_t radius[] = {1, 2, 7, 40, 300, 4000, 32768};
    const uint32_t r = radius[mc_rng_next(g) % 7u];
    int32_t c[3];
    for (int i = 0; i < 3; i++) c[i] = near(g, 0, 32768);
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) p[k][i] = near(g, c[i], r);
    const uint32_t kind = mc_rng_next(g) % 16u;
    if (kind == 0) memcpy(p[2], p[0], sizeof p[0]);
    if (kind == 1)   /* p2 = 2 p1 - p0, when inside the cube */
        for (int i = 0; i < 3; i++) {
            const int32_t v = 2 * p[1][i] - p[0][i];
            p[2][i] = v < -32768 || v > 32767 ? p[1][i] : v;
        }
}

static void normal_double(const int32_t p[3][3], double n[3])
{
    double a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = (double)p[1][i] - p[0][i], b[i] = (double)p[2][i] - p[0][i];
    n[0] = a[1] * b[2] - a[2] * b[1], n[1] = a[2] * b[0] - a[0] * b[2], n[2] = a[0] * b[1] - a[1] * b[0];
}

static void test_shade(void **state)
{
    (void)state;
    mc_rng g;
    mc_rng_seed(&g, 7, 1);
    unsigned ambiguous = 0;
    for (int t = 0; t < 200000; t++) {
        int32_t p[3][3], q[3][3], n[3];
        random_face(&g, p);
        const unsigned s = mc_mesh_shade_of(p[0], p[1], p[2]);
        mc_mesh_normal15((const int32_t(*)[3])p, n);
        assert_int_equal(mc_mesh_shade_normal15(n), s);
        assert_true(s < MC_MESH_SHADES);
        /* the corners' order does not matter: turned and mirrored */
        memcpy(q[0], p[1], sizeof q[0]), memcpy(q[1], p[2], sizeof q[1]), memcpy(q[2], p[0], sizeof q[2]);
        assert_int_equal(mc_mesh_shade_of(q[0], q[1], q[2]), s);
        assert_int_equal(mc_mesh_shade_of(p[1], p[0], p[2]), s);
        double d[3];
        normal_double((const int32_t(*)[3])p, d);
        const double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (len == 0) {
            assert_int_equal(s, MC_MESH_SHADES / 2);
            continue;
        }
        const double x = fabs(d[2]) / len * (MC_MESH_SHADES - 1);
        const unsigned k = (unsigned)floor(x + 0.5);
        if (s != k) {
            const double frac = x - floor(x);
            if (fabs(frac - 0.5) >= 0.01 || (s != k - 1u && s != k + 1u))
                fail_msg("shade %u, |n.z| / |n| * 31 = %.6f (face %d,%d,%d %d,%d,%d %d,%d,%d)", s, x, p[0][0], p[0][1],
                         p[0][2], p[1][0], p[1][1], p[1][2], p[2][0], p[2][1], p[2][2]);
            ambiguous++;
        }
    }
    print_message("# %u of 200000 faces within 1/100 of a step of a rounding point took the other shade\n", ambiguous);
}

static void test_crease(void **state)
{
    (void)state;
    static const double degrees[] = {0, 30, 60, 90, 120, 179};
    mc_rng g;
    mc_rng_seed(&g, 8, 1);
    for (unsigned c = 0; c < sizeof degrees / sizeof degrees[0]; c++) {
        const int32_t cc = (int32_t)lround(cos(degrees[c] * M_PI / 180) * 16384);
        const double limit = cc / 16384.0;
        unsigned creases = 0, close = 0;
        for (int t = 0; t < 50000; t++) {
            int32_t p[3][3], q[3][3], n[3], m[3];
            random_face(&g, p);
            if (t & 1) {   /* a neighbour sharing p's edge 0-1 (the usual case), else any face */
                memcpy(q[0], p[1], sizeof q[0]), memcpy(q[1], p[0], sizeof q[1]);
                for (int i = 0; i < 3; i++) q[2][i] = near(&g, p[2][i], 1u + mc_rng_next(&g) % 4000u);
            } else {
                random_face(&g, q);
            }
            mc_mesh_normal15((const int32_t(*)[3])p, n);
            mc_mesh_normal15((const int32_t(*)[3])q, m);
            const int got = mc_mesh_crease_normals(n, m, cc);
            assert_int_equal(mc_mesh_crease_normals(m, n, cc), got);
            double a[3], b[3];
            normal_double((const int32_t(*)[3])p, a);
            normal_double((const int32_t(*)[3])q, b);
            const double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            if (la == 0 || lb == 0) {
                assert_int_equal(got, 0);
                continue;
            }
            const double cosine = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
            if (fabs(cosine - limit) < 1e-3) {
                close++;
                continue;
            }
            if (got != (cosine < limit))
                fail_msg("crease angle %.0f: got %d, cosine %.6f against %.6f", degrees[c], got, cosine, limit);
            creases += (unsigned)got;
        }
        /* both answers came up (the test is not one-sided) */
        assert_true(degrees[c] >= 179 || creases > 0);
        assert_true(creases < 50000u - close);
        print_message("# crease angle %.0f degrees: %u creases of 50000 pairs, %u within 1/1000 of the cosine\n", degrees[c],
                      creases, close);
    }
}

/* ---- mc_mesh_face_bits on a cube ------------------------------------------------------------ */

/* The cube's corners (Q16 unit cube, +-16384) and twelve outward counter-clockwise triangles: two
 * a side, split along a diagonal. */
static const int32_t cube_v[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                     {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
static const uint32_t cube_f[12][3] = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                       {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};

static void put_le(uint8_t *p, uint32_t v, unsigned bytes)
{
    for (unsigned k = 0; k < bytes; k++) p[k] = (uint8_t)(v >> (8 * k));
}

/* Records of `size` bytes in chunks of two records (record_shift 1), each chunk its own allocation. */
static mc_chunk *chunks(const uint8_t *bytes, uint32_t records, uint32_t size)
{
    const uint32_t n = (records + 1u) / 2u;
    mc_chunk *c = calloc(n, sizeof *c);
    assert_non_null(c);
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t r = records - 2u * i < 2u ? records - 2u * i : 2u;
        uint8_t *d = malloc(r * size);
        assert_non_null(d);
        memcpy(d, bytes + 2u * i * size, r * size);
        c[i].data = d, c[i].size = r * size;
    }
    return c;
}

static void free_chunks(mc_chunk *c, uint32_t records)
{
    for (uint32_t i = 0; i < (records + 1u) / 2u; i++) free((void *)c[i].data);
    free(c);
}

/* The cube with faces [0, F) (F 12: closed; 10: the last two, the -x side, left out, whose edges
 * become borders), with index and half-edge fields ib and hb bytes wide, its bits checked. */
static void cube(uint32_t F, unsigned ib, unsigned hb)
{
    uint8_t pos[8 * 6], cor[12 * 12], opp[12 * 12];
    const uint32_t none = hb == 2 ? 0xFFFFu : 0xFFFFFFFFu;
    for (uint32_t v = 0; v < 8; v++)
        for (int i = 0; i < 3; i++) put_le(pos + 6 * v + 2 * i, (uint32_t)(32768 + 16384 * cube_v[v][i]), 2);
    uint32_t edges = 0;
    for (uint32_t f = 0; f < F; f++)
        for (uint32_t k = 0; k < 3; k++) {
            put_le(cor + 3 * ib * f + ib * k, cube_f[f][k], ib);
            /* across edge k (a to b): the face with edge b to a */
            const uint32_t a = cube_f[f][k], b = cube_f[f][(k + 1) % 3];
            uint32_t o = none;
            for (uint32_t g = 0; g < F; g++)
                for (uint32_t j = 0; j < 3; j++)
                    if (cube_f[g][j] == b && cube_f[g][(j + 1) % 3] == a) o = MC_HALF_EDGE(g, j);
            put_le(opp + 3 * hb * f + hb * k, o, hb);
            edges += o == none || MC_HALF_FACE(o) > f;
        }
    mc_pmesh pm;
    memset(&pm, 0, sizeof pm);
    pm.vertices = pm.base_vertices = 8, pm.faces = pm.base_faces = F, pm.edges = edges;
    pm.index_bytes = (uint8_t)ib, pm.half_bytes = (uint8_t)hb, pm.record_shift = 1, pm.closed = F == 12;
    pm.crease_cos = 8192;   /* 60 degrees */
    pm.positions = chunks(pos, 8, 6), pm.corners = chunks(cor, F, 3 * ib), pm.opposite = chunks(opp, F, 3 * hb);
    uint8_t bits[12];
    memset(bits, 0xFF, sizeof bits);
    mc_mesh_face_bits(&pm, bits);
    for (uint32_t f = 0; f < F; f++) {
        /* the side's normal: the one axis all three corners share */
        int axis = -1;
        for (int i = 0; i < 3; i++)
            if (cube_v[cube_f[f][0]][i] == cube_v[cube_f[f][1]][i] && cube_v[cube_f[f][0]][i] == cube_v[cube_f[f][2]][i]) axis = i;
        assert_true(axis >= 0);
        assert_int_equal(MC_FACE_BITS_SHADE(bits[f]), axis == 2 ? MC_MESH_SHADES - 1 : 0);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t a = cube_f[f][k], b = cube_f[f][(k + 1) % 3];
            int differ = 0;   /* a cube edge: its ends differ in one coordinate; a diagonal: in two */
            for (int i = 0; i < 3; i++) differ += cube_v[a][i] != cube_v[b][i];
            const uint32_t o = mc_le_index(opp + 3 * hb * f + hb * k, hb);
            const unsigned want = o != none && differ == 1;
            if (MC_FACE_BITS_CREASE(bits[f], k) != want)
                fail_msg("%u faces, widths %u/%u: face %u edge %u (%u-%u) crease bit %u, want %u", F, ib, hb, f, k, a, b,
                         MC_FACE_BITS_CREASE(bits[f], k), want);
        }
    }
    free_chunks((mc_chunk *)pm.positions, 8), free_chunks((mc_chunk *)pm.corners, F), free_chunks((mc_chunk *)pm.opposite, F);
}

/* both field widths (pmesh.h: 4-byte indices past 65,535 vertices, 4-byte half-edges past 16,383 faces) */
static void test_face_bits_closed(void **state) { (void)state; cube(12, 2, 2), cube(12, 4, 4), cube(12, 2, 4); }
static void test_face_bits_border(void **state) { (void)state; cube(10, 2, 2), cube(10, 4, 4), cube(10, 2, 4); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shade),
        cmocka_unit_test(test_crease),
        cmocka_unit_test(test_face_bits_closed),
        cmocka_unit_test(test_face_bits_border),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
