/* Long because every reader's error table shares the helpers that check one message and its place.
 * The tracker's input readers (runtime/front/track/track_input.h):
 *   - PGM: P5 8-bit and 16-bit, P2, comments anywhere in the header, maxval scaling (rounded to
 *     nearest, halves up), the header-only form; every error kind with its exact message and byte
 *     offset (empty, bad magic, junk, truncated header, zero and huge sizes, maxval, short raster,
 *     a sample above maxval, over the buffer); ViSP's mbt/cube/image0000.pgm (640x480) against its
 *     raw bytes;
 *   - the camera: "px,py,u0,v0" and its errors; ViSP's mbt/cube.xml, hand-made variants (any
 *     order, comments, attributes, a camera file's nested <model>) and broken ones, each error
 *     naming its line, column and the missing element;
 *   - poses: mbt/cube.0.pos, .pos variants and errors, the command-line form, the translation and
 *     rotation limits; theta-u to a Q30 quaternion and back on random rotations against double
 *     precision (within 1e-8 rad), known values, tiny angles, q and -q;
 *   - the orientation file: frames, comments, blank lines, errors with their line;
 *   - every fuzzer finding in tests/fuzz/regress/track_input/ replayed through every reader
 *     (tests/fuzz/fuzz_track_input.c's check): no crash, success or one error line.
 * The ViSP files come from Debian's visp-images-data; a test that needs an absent one is skipped
 * (reported as a skip, not a pass). Random numbers: PCG32 (modelc/rng.h) with fixed seeds.
 */
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include <modelc/rng.h>
#include "../../runtime/front/track/track_input.h"

int mc_fuzz_track_input_check(const char *path, const uint8_t *text, size_t n, char *why, size_t whylen);

#define VISP "/usr/share/visp-images-data/ViSP-images/mbt"
#define PI 3.14159265358979323846

static char dir[64];

static int setup(void **state)
{
    (void)state;
    strcpy(dir, "/tmp/modelc-track-input.XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char p[512];
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue;
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            remove(p);
        }
        closedir(d);
    }
    rmdir(dir);
    return 0;
}

/* writes n bytes to dir/name; returns the path (a static buffer: one at a time) */
static const char *put(const char *name, const void *bytes, size_t n)
{
    static char p[256];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
    return p;
}
static const char *puts_(const char *name, const char *text) { return put(name, text, strlen(text)); }

static int exists(const char *p)
{
    FILE *f = fopen(p, "rb");
    if (f) fclose(f);
    return f != NULL;
}

/* r must be -1 and err exactly PATH ": " want (or PREFIX want when path is NULL), one line */
static void want_error(int r, const char *err, const char *path, const char *want)
{
    char full[1024];
    snprintf(full, sizeof full, "%s%s%s", path ? path : "", path ? ": " : "", want);
    if (r != -1) fail_msg("returned %d, expected the error \"%s\"", r, full);
    assert_null(strchr(err, '\n'));
    if (strcmp(err, full) != 0) fail_msg("message \"%s\", expected \"%s\"", err, full);
}

/* r must be -1 and err start with PATH ":" and contain want */
static void want_error_has(int r, const char *err, const char *path, const char *want)
{
    if (r != -1) fail_msg("returned %d, expected an error with \"%s\"", r, want);
    assert_null(strchr(err, '\n'));
    if (strncmp(err, path, strlen(path)) != 0 || err[strlen(path)] != ':' || !strstr(err, want))
        fail_msg("message \"%s\", expected \"%s: ...%s...\"", err, path, want);
}

/* ---- PGM ------------------------------------------------------------------------------------- */

static void test_pgm_p5(void **state)
{
    (void)state;
    /* comments everywhere in the header, a comment right after the magic number and the maxval */
    static const char f[] = "P5#magic\n# a comment\n 3 #w\n\t2\n#\n255#comment ends with the line\n\x01\x02\x03\xfd\xfe\xff";
    const char *p = put("a.pgm", f, sizeof f - 1);
    uint8_t buf[6] = {0};
    uint16_t w = 0, h = 0;
    char err[256] = "";
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(w, 3);
    assert_int_equal(h, 2);
    static const uint8_t want[6] = {1, 2, 3, 253, 254, 255};
    assert_memory_equal(buf, want, 6);
    /* header only */
    w = h = 0;
    assert_int_equal(mc_pgm_read(p, NULL, 0, &w, &h, err, sizeof err), 0);
    assert_int_equal(w, 3);
    assert_int_equal(h, 2);
    /* bytes after the raster: another image, ignored */
    static const char g[] = "P5 2 1 255\n\x10\x20P5 1 1 255\n\x30";
    p = put("b.pgm", g, sizeof g - 1);
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(w * 10 + h, 21);
    assert_int_equal(buf[0], 0x10);
    assert_int_equal(buf[1], 0x20);
    /* the single whitespace after maxval: the '\r' of "\r\n", the '\n' then the first pixel */
    static const char c[] = "P5 2 1 255\r\n\x05";
    p = put("c.pgm", c, sizeof c - 1);
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(buf[0], '\n');
    assert_int_equal(buf[1], 5);
}

static uint8_t scaled(unsigned v, unsigned maxval) { return (uint8_t)floor(v * 255.0 / maxval + 0.5); }

static void test_pgm_maxval(void **state)
{
    (void)state;
    static uint8_t f[64 + 256 * 2], buf[256];
    uint16_t w, h;
    char err[256];
    /* 8-bit maxvals: every value 0..maxval, against v * 255 / maxval rounded (halves up) */
    static const unsigned maxvals8[] = {1, 2, 3, 15, 100, 127, 128, 200, 254, 255};
    for (size_t m = 0; m < sizeof maxvals8 / sizeof maxvals8[0]; m++) {
        const unsigned mv = maxvals8[m];
        int n = snprintf((char *)f, 64, "P5\n%u 1\n%u\n", mv + 1, mv);
        for (unsigned v = 0; v <= mv; v++) f[n + v] = (uint8_t)v;
        const char *p = put("m.pgm", f, (size_t)n + mv + 1);
        assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
        for (unsigned v = 0; v <= mv; v++)
            if (buf[v] != scaled(v, mv)) fail_msg("maxval %u: %u read as %u, expected %u", mv, v, buf[v], scaled(v, mv));
    }
    assert_int_equal(scaled(1, 2), 128);   /* 127.5: halves up */
    /* 16-bit maxvals, big-endian samples */
    static const unsigned maxvals16[] = {256, 1000, 4095, 65535};
    for (size_t m = 0; m < sizeof maxvals16 / sizeof maxvals16[0]; m++) {
        const unsigned mv = maxvals16[m];
        unsigned vals[256];
        for (unsigned i = 0; i < 256; i++) vals[i] = i == 255 ? mv : (unsigned)((unsigned long)i * 257 % (mv + 1));
        vals[1] = mv / 2, vals[2] = (mv + 1) / 2, vals[3] = mv - 1;
        int n = snprintf((char *)f, 64, "P5 256 1 %u\n", mv);
        for (unsigned i = 0; i < 256; i++) f[n + 2 * i] = (uint8_t)(vals[i] >> 8), f[n + 2 * i + 1] = (uint8_t)vals[i];
        const char *p = put("m16.pgm", f, (size_t)n + 512);
        assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
        for (unsigned i = 0; i < 256; i++)
            if (buf[i] != scaled(vals[i], mv))
                fail_msg("maxval %u: %u read as %u, expected %u", mv, vals[i], buf[i], scaled(vals[i], mv));
    }
    /* 65535: the rounding edge 128 -> 0, 129 -> 1 (128.5 / 257) */
    static const char e[] = "P5 2 1 65535\n\x00\x80\x00\x81";
    const char *p = put("e.pgm", e, sizeof e - 1);
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(buf[0], 0);
    assert_int_equal(buf[1], 1);
}

static void test_pgm_p2(void **state)
{
    (void)state;
    static const char f[] = "P2\n# plain\n4 2 # size\n10\n0 5 10\n# between samples\n 7\r\n1\t2 3#c\n4";
    const char *p = puts_("a.pgm", f);
    uint8_t buf[8];
    uint16_t w, h;
    char err[256];
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(w, 4);
    assert_int_equal(h, 2);
    static const uint8_t want[8] = {0, 128, 255, 179, 26, 51, 77, 102};
    assert_memory_equal(buf, want, 8);
    /* maxval 255 as is, 16-bit maxvals scaled */
    p = puts_("b.pgm", "P2 3 1 255 0 128 255\n");
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(buf[1], 128);
    p = puts_("c.pgm", "P2 3 1 65535 0 32896 65535");
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), 0);
    assert_int_equal(buf[0], 0);
    assert_int_equal(buf[1], 128);
    assert_int_equal(buf[2], 255);
}

typedef struct pgm_case {
    const char *bytes;
    size_t n;   /* 0: strlen */
    size_t cap;
    const char *want;   /* after "PATH: " */
} pgm_case;

static void test_pgm_errors(void **state)
{
    (void)state;
    static const pgm_case cases[] = {
        {"", 0, 64, "byte 0: end of file (an empty file): not a PGM file"},
        {"P", 0, 64, "byte 1: end of file after 'P': not a PGM file"},
        {"X5\n1 1\n255\n\x01", 0, 64, "byte 0: not a PGM file (it starts with 'X', not P5 or P2)"},
        {"\x89PNG", 0, 64, "byte 0: not a PGM file (it starts with '\\x89', not P5 or P2)"},
        {"P6\n1 1\n255\n\x01\x02\x03", 0, 64, "byte 1: P6 is a colour image (PPM), not a grey-level PGM (P5 or P2)"},
        {"P4\n8 1\n\x01", 0, 64, "byte 1: P4 is a bitmap (PBM), not a grey-level PGM (P5 or P2)"},
        {"P7\n", 0, 64, "byte 1: P followed by '7': not a PGM file (P5 or P2)"},
        {"P55 1 1 255\n\x01", 0, 64, "byte 2: '5' after the magic number P5"},
        /* truncated headers */
        {"P5\n", 0, 64, "byte 3: end of file before the width"},
        {"P5\n3 2", 0, 64, "byte 6: end of file before the maxval"},
        {"P5\n3 2 # comment with no end", 0, 64, "byte 28: end of file before the maxval"},
        {"P5\n3", 0, 64, "byte 4: end of file before the height"},
        /* junk in the header */
        {"P5\n3x2\n255\n", 0, 64, "byte 4: 'x' after the width"},
        {"P5\n3 -2\n255\n", 0, 64, "byte 5: height expected, found '-'"},
        {"P5\n3 2\n25.5\n", 0, 64, "byte 9: '.' after the maxval"},
        {"P5\n3 2\nmax\n", 0, 64, "byte 7: maxval expected, found 'm'"},
        {"P5 \x00 1 255\n", 4, 64, "byte 3: width expected, found '\\x00'"},
        /* sizes */
        {"P5\n0 1\n255\n", 0, 64, "byte 3: width 0 is not in 1..4096"},
        {"P5\n1 0\n255\n", 0, 64, "byte 5: height 0 is not in 1..4096"},
        {"P5\n4097 1\n255\n", 0, 64, "byte 3: width 4097 is not in 1..4096"},
        {"P5\n1 99999999999999999999\n255\n", 0, 64, "byte 5: height too large (1..4096)"},
        {"P5\n1 1\n0\n\x00", 0, 64, "byte 7: maxval 0 is not in 1..65535"},
        {"P5\n1 1\n65536\n\x00\x00", 0, 64, "byte 7: maxval 65536 is not in 1..65535"},
        {"P5\n100 100\n255\n", 0, 9999, "byte 3: 100x100 pixels do not fit the buffer of 9999"},
        {"P2\n4096 4096\n255\n", 0, 1 << 20, "byte 3: 4096x4096 pixels do not fit the buffer of 1048576"},
        /* short rasters */
        {"P5\n1 1\n255", 0, 64, "byte 10: end of file after the maxval (no raster)"},
        {"P5\n1 1\n255#c", 0, 64, "byte 12: end of file in a comment after the maxval (no raster)"},
        {"P5\n2 2\n255\n\x01\x02\x03", 0, 64, "byte 14: end of file after 3 of 4 pixels"},
        {"P5\n2 2\n100\n\x01\x02", 0, 64, "byte 13: end of file after 2 of 4 pixels"},
        {"P5\n2 1\n65535\n\x00\x01\x00", 16, 64, "byte 16: end of file inside pixel 1 of 2 (2 bytes each)"},
        {"P2\n2 1\n10\n3", 0, 64, "byte 11: end of file after 1 of 2 samples"},
        {"P2\n2 1\n10\n3 # and no more\n", 0, 64, "byte 26: end of file after 1 of 2 samples"},
        /* samples above maxval, junk in the raster */
        {"P5\n2 1\n100\n\x01\x80", 0, 64, "byte 12: pixel 1: 128 is above the maxval 100"},
        {"P5\n1 1\n1000\n\x03\xe9", 0, 64, "byte 12: pixel 0: 1001 is above the maxval 1000"},
        {"P2\n2 1\n10\n3 11\n", 0, 64, "byte 12: sample 1: 11 is above the maxval 10"},
        {"P2\n2 1\n10\n3 99999999999\n", 0, 64, "byte 12: sample 1 is above the maxval 10"},
        {"P2\n2 1\n255\n1 a\n", 0, 64, "byte 13: sample 1: 'a' is not a decimal digit"},
        {"P2\n2 1\n255\n1 -2\n", 0, 64, "byte 13: sample 1: '-' is not a decimal digit"},
        {"P2\n2 1\n255\n1 2x\n", 0, 64, "byte 14: sample 1: 'x' after the number"},
        {"P2\n2 1\n255\n1,2\n", 0, 64, "byte 12: sample 0: ',' after the number"},
    };
    uint8_t buf[64];
    uint16_t w, h;
    char err[256];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const pgm_case *c = &cases[i];
        const char *p = put("e.pgm", c->bytes, c->n ? c->n : strlen(c->bytes));
        static uint8_t big[1 << 20];
        uint8_t *b = c->cap <= sizeof buf ? buf : big;
        char full[600];
        snprintf(full, sizeof full, "%s: %s", p, c->want);
        const int r = mc_pgm_read(p, b, c->cap, &w, &h, err, sizeof err);
        if (r != -1 || strcmp(err, full) != 0) fail_msg("case %zu: %d \"%s\", expected \"%s\"", i, r, err, full);
    }
    /* a missing file; the size when the header was read, 0 before */
    want_error_has(mc_pgm_read("/nonexistent/x.pgm", buf, sizeof buf, &w, &h, err, sizeof err), err,
                   "/nonexistent/x.pgm", "cannot open: No such file or directory");
    assert_int_equal(w + h, 0);
    const char *p = puts_("s.pgm", "P5 3 2 255\n\x01");
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err), -1);
    assert_int_equal(w * 10 + h, 32);
    /* a short message buffer: cut and terminated; no buffer at all */
    char small[12];
    memset(small, 'x', sizeof small);
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, small, sizeof small), -1);
    assert_int_equal(strlen(small), sizeof small - 1);
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, &w, &h, NULL, 0), -1);
    assert_int_equal(mc_pgm_read(p, buf, sizeof buf, NULL, NULL, NULL, 0), -1);
}

static void test_pgm_real(void **state)
{
    (void)state;
    const char *p = VISP "/cube/image0000.pgm";
    if (!exists(p)) {
        print_message("%s is absent (Debian package visp-images-data)\n", p);
        skip();
    }
    static uint8_t buf[640 * 480], raw[640 * 480 + 64];
    uint16_t w = 0, h = 0;
    char err[256] = "";
    if (mc_pgm_read(p, NULL, 0, &w, &h, err, sizeof err) != 0) fail_msg("%s", err);
    assert_int_equal(w, 640);
    assert_int_equal(h, 480);
    if (mc_pgm_read(p, buf, sizeof buf, &w, &h, err, sizeof err) != 0) fail_msg("%s", err);
    /* against the raw bytes after its 15-byte header "P5\n640 480\n255\n" */
    FILE *f = fopen(p, "rb");
    assert_non_null(f);
    const size_t n = fread(raw, 1, sizeof raw, f);
    fclose(f);
    assert_int_equal(n, 15 + 640 * 480);
    assert_memory_equal(raw, "P5\n640 480\n255\n", 15);
    assert_memory_equal(buf, raw + 15, 640 * 480);
    /* one pixel too many for the buffer */
    want_error(mc_pgm_read(p, buf, 640 * 480 - 1, &w, &h, err, sizeof err), err, p,
               "byte 3: 640x480 pixels do not fit the buffer of 307199");
    /* every frame of the sequence reads */
    char q[256];
    int frames = 0;
    for (int i = 0;; i++) {
        snprintf(q, sizeof q, VISP "/cube/image%04d.pgm", i);
        if (!exists(q)) break;
        if (mc_pgm_read(q, buf, sizeof buf, &w, &h, err, sizeof err) != 0) fail_msg("%s", err);
        frames++;
    }
    print_message("%d frames of mbt/cube read\n", frames);
    assert_true(frames > 1);
}

/* ---- the camera ----------------------------------------------------------------------------- */

static void test_camera_parse(void **state)
{
    (void)state;
    mc_track_intrinsics c;
    char err[256];
    assert_int_equal(mc_track_camera_parse("547.7367575,542.0744058,338.7036994,234.5083345", &c, err, sizeof err), 0);
    assert_true(c.px == 547.7367575 && c.py == 542.0744058 && c.u0 == 338.7036994 && c.v0 == 234.5083345);
    assert_int_equal(mc_track_camera_parse(" 1e3 ,\t2.,.5 , -4 ", &c, err, sizeof err), 0);
    assert_true(c.px == 1000 && c.py == 2 && c.u0 == 0.5 && c.v0 == -4);
    static const struct {
        const char *text, *want;
    } bad[] = {
        {"1,2,3", "camera \"1,2,3\": character 6: 3 numbers, expected 4"},
        {"1,2,3,4,5", "camera \"1,2,3,4,5\": character 8: more than 4 numbers"},
        {"", "camera \"\": character 1 (px): empty"},
        {"1,,3,4", "camera \"1,,3,4\": character 3 (py): empty"},
        {"0,1,2,3", "camera \"0,1,2,3\": character 1 (px): 0 must be above 0"},
        {"1,-1,2,3", "camera \"1,-1,2,3\": character 3 (py): -1 must be above 0"},
        {"40000,1,2,3", "camera \"40000,1,2,3\": character 1 (px): 40000 must be below 32768 in magnitude (Q16 in an int32)"},
        {"1,2,-32768,3", "camera \"1,2,-32768,3\": character 5 (u0): -32768 must be below 32768 in magnitude (Q16 in an int32)"},
        {"1,nan,2,3", "camera \"1,nan,2,3\": character 3 (py): not a decimal number \"nan\""},
        {"1,2,inf,3", "camera \"1,2,inf,3\": character 5 (u0): not a decimal number \"inf\""},
        {"1,2,3,0x10", "camera \"1,2,3,0x10\": character 7 (v0): not a decimal number \"0x10\""},
        {"1,2,3,4x", "camera \"1,2,3,4x\": character 7 (v0): not a decimal number \"4x\""},
        {"1,2,3,4 x", "camera \"1,2,3,4 x\": character 9 (v0): 'x' after the number"},
        {"1,2,3,1e999", "camera \"1,2,3,1e999\": character 7 (v0): out of range \"1e999\""},
        {"1,2,3,4,", "camera \"1,2,3,4,\": character 8: more than 4 numbers"},
        {"1;2;3;4", "camera \"1;2;3;4\": character 1 (px): not a decimal number \"1;2;3;4\""},
        {"1,2,3,\x01", "camera \"1,2,3,\\x01\": character 7 (v0): not a decimal number \"\\x01\""},
        {"1,2,3,1.5e", "camera \"1,2,3,1.5e\": character 7 (v0): not a decimal number \"1.5e\""},
        {"1,2,3,.", "camera \"1,2,3,.\": character 7 (v0): not a decimal number \".\""},
        {"1,2,3,0000000000000000000000000000000000000000000000000000000000000001",
         "camera \"1,2,3,00000000000000000000000000...\": character 7 (v0): too long (over 63 characters) "
         "\"00000000000000000000000000000000...\""},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        want_error(mc_track_camera_parse(bad[i].text, &c, err, sizeof err), err, NULL, bad[i].want);
    want_error(mc_track_camera_parse(NULL, &c, err, sizeof err), err, NULL, "camera: no text");
}

static void test_camera_xml(void **state)
{
    (void)state;
    mc_track_intrinsics c;
    char err[256];
    const char *p = VISP "/cube.xml";
    if (exists(p)) {
        if (mc_track_camera_read_xml(p, &c, err, sizeof err) != 0) fail_msg("%s", err);
        assert_true(c.px == 547.7367575 && c.py == 542.0744058 && c.u0 == 338.7036994 && c.v0 == 234.5083345);
    } else {
        print_message("%s is absent (Debian package visp-images-data): hand-made files only\n", p);
    }
    /* any order, attributes, comments (one hiding a camera), a declaration, CRLF, other elements */
    p = puts_("a.xml", "<?xml version=\"1.0\"?>\r\n<!DOCTYPE conf>\r\n<conf>\r\n<!-- <camera><px>9</px></camera> -->\r\n"
                      "<camera id='a>b'>\r\n  <v0>4</v0> <note>x < y</note>\r\n<u0>\n 3 \n</u0><py>2</py>\t<px>1.5</px>\r\n"
                      "</camera>\r\n<camera><px>7</px></camera>\r\n</conf>\r\n");
    if (mc_track_camera_read_xml(p, &c, err, sizeof err) != 0) fail_msg("%s", err);
    assert_true(c.px == 1.5 && c.py == 2 && c.u0 == 3 && c.v0 == 4);
    /* a ViSP camera file: the fields inside <model>, the one without distortion first */
    p = puts_("b.xml", "<root><camera><name>Camera</name><image_width>640</image_width><model>"
                      "<type>perspectiveProjWithoutDistortion</type><px>600</px><py>601</py><u0>320</u0><v0>240</v0>"
                      "</model><model><type>perspectiveProjWithDistortion</type><px>1</px><py>2</py><u0>3</u0>"
                      "<v0>4</v0><kud>0.1</kud></model></camera></root>");
    if (mc_track_camera_read_xml(p, &c, err, sizeof err) != 0) fail_msg("%s", err);
    assert_true(c.px == 600 && c.py == 601 && c.u0 == 320 && c.v0 == 240);
    static const struct {
        const char *text, *want;
    } bad[] = {
        {"<conf><face></face></conf>\n", "no <camera> element"},
        {"", "no <camera> element"},
        {"<camera>\n<px>1</px>\n<u0>3</u0><v0>4</v0>\n</camera>", "4:1: the <camera> of line 1 has no <py>"},
        {"<a>\n  <camera><px>1</px><py>1</py>\n<u0>3</u0></camera>", "3:11: the <camera> of line 2 has no <v0>"},
        {"<camera/>", "1:1: <camera/> is empty: no <px>"},
        {"<camera><px/><py>1</py><u0>3</u0><v0>4</v0></camera>", "1:9: <px/> is empty: a number expected"},
        {"<camera>\n<px>  abc </px><py>1</py><u0>3</u0><v0>4</v0></camera>", "2:7: <px>: not a decimal number \"abc\""},
        {"<camera><px></px><py>1</py><u0>3</u0><v0>4</v0></camera>", "1:13: <px>: empty \"\""},
        {"<camera><px>1</px><py>0</py><u0>3</u0><v0>4</v0></camera>", "1:23: <py> 0 must be above 0"},
        {"<camera><px>1</px><py>1</py><u0>nan</u0><v0>4</v0></camera>", "1:33: <u0>: not a decimal number \"nan\""},
        {"<camera><px>1</px><py>1</py><u0>1 2</u0><v0>4</v0></camera>", "1:33: <u0>: not a decimal number \"1 2\""},
        {"<camera><px><b>1</b></px></camera>", "1:13: <px> holds more than a number (no </px> here)"},
        {"<camera><px>1</py></camera>", "1:14: <px> holds more than a number (no </px> here)"},
        {"<camera>\n<px>1</px>", "2:11: end of file inside the <camera> of line 1, column 1"},
        {"<camera><px>1", "1:14: end of file inside <px>"},
        {"<camera><px>1</px", "1:14: end of file inside this tag"},
        {"<conf>\n<!-- <camera>", "2:1: end of file inside this <!...>"},
        {"<?xml version=\"1.0\"", "1:1: end of file inside this <?...?>"},
        {"<camera id=\"a>", "1:1: end of file inside this tag"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        p = puts_("e.xml", bad[i].text);
        char full[600];   /* "FILE: no <camera> element", else "FILE:LINE:COL: ..." */
        snprintf(full, sizeof full, "%s%s%s", p, bad[i].want[0] == 'n' ? ": " : ":", bad[i].want);
        const int r = mc_track_camera_read_xml(p, &c, err, sizeof err);
        if (r != -1 || strcmp(err, full) != 0) fail_msg("case %zu: %d \"%s\", expected \"%s\"", i, r, err, full);
    }
    want_error_has(mc_track_camera_read_xml("/nonexistent.xml", &c, err, sizeof err), err, "/nonexistent.xml",
                   "cannot open");
}

/* ---- poses ------------------------------------------------------------------------------------ */

static void test_pose_read(void **state)
{
    (void)state;
    double pose[6];
    char err[256];
    const char *p = VISP "/cube.0.pos";
    if (exists(p)) {
        if (mc_track_pose_read(p, pose, err, sizeof err) != 0) fail_msg("%s", err);
        static const double want[6] = {0.02231950571, 0.1071368004, 0.5071128378, 2.100485509, 1.146812236,
                                       -0.4560126437};
        for (int k = 0; k < 6; k++) assert_true(pose[k] == want[k]);
    } else {
        print_message("%s is absent (Debian package visp-images-data): hand-made files only\n", p);
    }
    p = puts_("a.pos", "# a pose\n0.1 0.2\n\n0.3   # tz\r\n 0 -1e-3\t+2.5e+0\n# end");
    if (mc_track_pose_read(p, pose, err, sizeof err) != 0) fail_msg("%s", err);
    static const double want[6] = {0.1, 0.2, 0.3, 0, -1e-3, 2.5};
    for (int k = 0; k < 6; k++) assert_true(pose[k] == want[k]);
    static const struct {
        const char *text, *want;
    } bad[] = {
        {"1\n2\n3\n4\n5\n", "6:1: end of file after 5 numbers, expected 6 (tx ty tz tux tuy tuz)"},
        {"", "1:1: end of file after 0 numbers, expected 6 (tx ty tz tux tuy tuz)"},
        {"1 2 3 4 5 6 7", "1:13: more than 6 numbers (tx ty tz tux tuy tuz): \"7\""},
        {"1\n2\n3\n4\n5\n6\nx", "7:1: more than 6 numbers (tx ty tz tux tuy tuz): \"x\""},
        {"1 2\n  3.0.0 4 5 6", "2:3: tz: not a decimal number \"3.0.0\""},
        {"1 2 3 nan 5 6", "1:7: tux: not a decimal number \"nan\""},
        {"1 2 3 4 5 -inf", "1:11: tuz: not a decimal number \"-inf\""},
        {"1,2,3,4,5,6", "1:1: tx: not a decimal number \"1,2,3,4,5,6\""},
        {"300 0 0 0 0 0", "1:1: tx 300 is beyond the runtime's +-2^28 um (+-268.435456 m)"},
        {"0 0 -268.4354565 0 0 0", "1:5: tz -268.435 is beyond the runtime's +-2^28 um (+-268.435456 m)"},
        {"0 0 1 0 1000.5 0", "1:9: tuy 1000.5 is beyond +-1000 rad"},
        {"0 0 1 0 0 1e400", "1:11: tuz: out of range \"1e400\""},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        p = puts_("e.pos", bad[i].text);
        char full[600];
        snprintf(full, sizeof full, "%s:%s", p, bad[i].want);
        const int r = mc_track_pose_read(p, pose, err, sizeof err);
        if (r != -1 || strcmp(err, full) != 0) fail_msg("case %zu: %d \"%s\", expected \"%s\"", i, r, err, full);
    }
    want_error_has(mc_track_pose_read("/nonexistent.pos", pose, err, sizeof err), err, "/nonexistent.pos",
                   "cannot open");
}

static void test_pose_parse_limits(void **state)
{
    (void)state;
    double pose[6];
    int32_t q[4], t[3];
    char err[256];
    assert_int_equal(mc_track_pose_parse("0.02231950571,0.1071368004,0.5071128378,2.100485509,1.146812236,-0.4560126437",
                                         pose, err, sizeof err), 0);
    assert_true(pose[2] == 0.5071128378 && pose[5] == -0.4560126437);
    /* the translation limit: 2^28 um once rounded */
    assert_int_equal(mc_track_pose_parse("268.435456,-268.435456,268.4354564,0,0,0", pose, err, sizeof err), 0);
    mc_track_pose_to_fixed(pose, q, t);
    assert_int_equal(t[0], 1 << 28);
    assert_int_equal(t[1], -(1 << 28));
    assert_int_equal(t[2], 1 << 28);
    want_error(mc_track_pose_parse("268.4354565,0,0,0,0,0", pose, err, sizeof err), err, NULL,
               "pose \"268.4354565,0,0,0,0,0\": character 1 (tx): 268.435 is beyond the runtime's +-2^28 um (+-268.435456 m)");
    want_error(mc_track_pose_parse("0,-1e9,0,0,0,0", pose, err, sizeof err), err, NULL,
               "pose \"0,-1e9,0,0,0,0\": character 3 (ty): -1e+09 is beyond the runtime's +-2^28 um (+-268.435456 m)");
    assert_int_equal(mc_track_pose_parse("0,0,0,-1000,1000,0", pose, err, sizeof err), 0);
    want_error(mc_track_pose_parse("0,0,0,0,0,-1000.001", pose, err, sizeof err), err, NULL,
               "pose \"0,0,0,0,0,-1000.001\": character 11 (tuz): -1000 is beyond +-1000 rad");
    want_error(mc_track_pose_parse("0,0,0,0,0", pose, err, sizeof err), err, NULL,
               "pose \"0,0,0,0,0\": character 10: 5 numbers, expected 6");
    /* translations: to the micrometre, halves away from zero; outside the limits clamped */
    const double tr[6] = {0.0000005, -0.0000005, 0.0000004999, 0, 0, 0};
    mc_track_pose_to_fixed(tr, q, t);
    assert_int_equal(t[0], 1);
    assert_int_equal(t[1], -1);
    assert_int_equal(t[2], 0);
    const double far[6] = {1e30, -1e30, NAN, INFINITY, 0, 0};
    mc_track_pose_to_fixed(far, q, t);
    assert_int_equal(t[0], 1 << 28);
    assert_int_equal(t[1], -(1 << 28));
    assert_int_equal(t[2], 0);
    assert_int_equal(q[0], 1 << 30);   /* a rotation vector that is not finite: none */
    assert_int_equal(q[1] | q[2] | q[3], 0);
}

static void test_pose_known(void **state)
{
    (void)state;
    int32_t q[4], t[3];
    const double q30 = 1073741824.0;
    /* theta = pi/2 about x */
    const double a[6] = {0.1, -0.2, 0.5, PI / 2, 0, 0};
    mc_track_pose_to_fixed(a, q, t);
    assert_true(fabs(q[0] - cos(PI / 4) * q30) <= 1 && fabs(q[1] - sin(PI / 4) * q30) <= 1);
    assert_int_equal(q[2], 0);
    assert_int_equal(q[3], 0);
    assert_int_equal(t[0], 100000);
    assert_int_equal(t[1], -200000);
    assert_int_equal(t[2], 500000);
    /* theta = 0, and pi about z */
    const double z[6] = {0, 0, 0, 0, 0, 0}, b[6] = {0, 0, 0, 0, 0, PI};
    mc_track_pose_to_fixed(z, q, t);
    assert_int_equal(q[0], 1 << 30);
    assert_int_equal(q[1] | q[2] | q[3] | t[0] | t[1] | t[2], 0);
    mc_track_pose_to_fixed(b, q, t);
    assert_true(abs(q[0]) <= 1 && q[1] == 0 && q[2] == 0 && q[3] == 1 << 30);
    /* back: q = (2^30, 0, 0, 0) and q = 0 are no rotation; q and -q and 5 q are one rotation */
    double p[6];
    const int32_t id[4] = {1 << 30, 0, 0, 0}, zero[4] = {0, 0, 0, 0}, tt[3] = {1, -2, 268435456};
    mc_track_pose_from_fixed(id, tt, p);
    assert_true(p[0] == 1e-6 && p[1] == -2e-6 && p[2] == 268.435456 && p[3] == 0 && p[4] == 0 && p[5] == 0);
    mc_track_pose_from_fixed(zero, tt, p);
    assert_true(p[3] == 0 && p[4] == 0 && p[5] == 0);
    const int32_t qx[4] = {759250125, 759250125, 0, 0}, nqx[4] = {-759250125, -759250125, 0, 0},
                  sqx[4] = {151850025, 151850025, 0, 0};
    double p1[6], p2[6];
    mc_track_pose_from_fixed(qx, tt, p);
    mc_track_pose_from_fixed(nqx, tt, p1);
    mc_track_pose_from_fixed(sqx, tt, p2);
    assert_true(fabs(p[3] - PI / 2) < 1e-15 && p[4] == 0 && p[5] == 0);
    for (int k = 3; k < 6; k++) assert_true(p1[k] == p[k] && fabs(p2[k] - p[k]) < 1e-15);
    /* w = 0: theta = pi */
    const int32_t qpi[4] = {0, 0, -(1 << 30), 0};
    mc_track_pose_from_fixed(qpi, tt, p);
    assert_true(p[3] == 0 && fabs(p[4] + PI) < 1e-15 && p[5] == 0);
}

static double uniform(mc_rng *r) { return mc_rng_next(r) / 4294967296.0; }

static void test_pose_round_trip(void **state)
{
    (void)state;
    mc_rng r;
    mc_rng_seed(&r, 0x7ac4, 3);
    double worst = 0, worst_q = 0;
    for (int i = 0; i < 200000; i++) {
        /* a random axis (uniform on the sphere), theta in [0, pi), a tenth of them tiny */
        const double zc = 2 * uniform(&r) - 1, phi = 2 * PI * uniform(&r), s = sqrt(1 - zc * zc);
        double theta = PI * uniform(&r);
        if (i % 10 == 0) theta = pow(10, -12 + 9 * uniform(&r));
        if (i == 1) theta = 0;
        const double u[3] = {s * cos(phi), s * sin(phi), zc};
        double pose[6], back[6];
        for (int k = 0; k < 3; k++) pose[k] = (uniform(&r) - 0.5) * 500, pose[3 + k] = theta * u[k];
        int32_t q[4], t[3];
        mc_track_pose_to_fixed(pose, q, t);
        /* the quaternion: each component the double one rounded */
        const double qd[4] = {cos(theta / 2), sin(theta / 2) * u[0], sin(theta / 2) * u[1], sin(theta / 2) * u[2]};
        for (int k = 0; k < 4; k++) {
            const double e = fabs(q[k] - qd[k] * 1073741824.0);
            if (e > worst_q) worst_q = e;
            if (e > 0.5 + 1e-6) fail_msg("rotation %d: q[%d] = %d, exact %.3f", i, k, q[k], qd[k] * 1073741824.0);
        }
        mc_track_pose_from_fixed(q, t, back);
        for (int k = 0; k < 3; k++) {
            const double e = fabs(back[3 + k] - pose[3 + k]);
            if (e > worst) worst = e;
            if (e > 1e-8) fail_msg("rotation %d (theta %.17g): component %d back %.17g, was %.17g", i, theta, k,
                                   back[3 + k], pose[3 + k]);
            if (fabs(back[k] - pose[k]) > 0.5e-6 + 1e-12) fail_msg("translation %d: %.9f back %.9f", i, pose[k], back[k]);
        }
    }
    print_message("theta-u round trip: worst %.3g rad; quaternion within %.4f of Q30's exact value\n", worst, worst_q);
}

/* ---- orientations ----------------------------------------------------------------------------- */

static void test_orient(void **state)
{
    (void)state;
    const char *p = puts_("o.txt", "# theta u per frame\n\n0 0 0\n1.5707963267948966 0 0 # pi/2 about x\n   \n"
                                   "\t0\t0\t3.141592653589793\r\n# end\n0 0.001 0");
    mc_track_orient_reader o;
    char err[256];
    int32_t q[4];
    double tu[3];
    assert_int_equal(mc_track_orient_open(&o, p, err, sizeof err), 0);
    assert_int_equal(mc_track_orient_next(&o, q, tu, err, sizeof err), 1);
    assert_int_equal(o.line, 3);
    assert_true(q[0] == 1 << 30 && q[1] == 0 && q[2] == 0 && q[3] == 0);
    assert_int_equal(mc_track_orient_next(&o, q, NULL, err, sizeof err), 1);
    assert_int_equal(o.line, 4);
    assert_true(abs(q[0] - 759250125) <= 1 && abs(q[1] - 759250125) <= 1 && q[2] == 0 && q[3] == 0);
    assert_int_equal(mc_track_orient_next(&o, q, tu, err, sizeof err), 1);
    assert_int_equal(o.line, 6);
    assert_true(tu[2] == 3.141592653589793 && abs(q[0]) <= 1 && q[3] == 1 << 30);
    assert_int_equal(mc_track_orient_next(&o, q, tu, err, sizeof err), 1);
    assert_int_equal(o.line, 8);
    assert_true(tu[1] == 0.001);
    assert_int_equal(mc_track_orient_next(&o, q, tu, err, sizeof err), 0);
    assert_int_equal(mc_track_orient_next(&o, q, tu, err, sizeof err), 0);
    assert_int_equal(o.frames, 4);
    mc_track_orient_close(&o);
    static const struct {
        const char *text, *want;
        int good;   /* frames before the error */
    } bad[] = {
        {"0 0 0\n# c\n1 2\n", "3:4: 2 numbers, expected 3 (tux tuy tuz)", 1},
        {"0 0 0\n1 2 # c\n0 0 0\n", "2:4: 2 numbers, expected 3 (tux tuy tuz)", 1},
        {"1 2", "1:4: 2 numbers, expected 3 (tux tuy tuz)", 0},
        {"0 0 0\n0 0 0\n\n1 2 3 4\n", "4:7: more than 3 numbers (tux tuy tuz): \"4\"", 2},
        {"0 0 0\n0 x 0\n", "2:3: tuy: not a decimal number \"x\"", 1},
        {"0 0 0\n0 0 1,\n", "2:5: tuz: not a decimal number \"1,\"", 1},
        {"0 0 1001\n", "1:5: tuz 1001 is beyond +-1000 rad", 0},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        p = puts_("e.txt", bad[i].text);
        assert_int_equal(mc_track_orient_open(&o, p, err, sizeof err), 0);
        for (int k = 0; k < bad[i].good; k++) assert_int_equal(mc_track_orient_next(&o, q, tu, err, sizeof err), 1);
        char full[600];
        snprintf(full, sizeof full, "%s:%s", p, bad[i].want);
        int r = mc_track_orient_next(&o, q, tu, err, sizeof err);
        if (r != -1 || strcmp(err, full) != 0) fail_msg("case %zu: %d \"%s\", expected \"%s\"", i, r, err, full);
        r = mc_track_orient_next(&o, q, tu, err, sizeof err);   /* and again */
        want_error(r, err, p, "the orientation file failed already");
        mc_track_orient_close(&o);
    }
    want_error_has(mc_track_orient_open(&o, "/nonexistent.txt", err, sizeof err), err, "/nonexistent.txt",
                   "cannot open");
    want_error(mc_track_orient_next(&o, q, tu, err, sizeof err), err, "/nonexistent.txt",
               "the orientation file failed already");
    mc_track_orient_close(&o);
}

/* ---- the fuzzer's findings -------------------------------------------------------------------- */

static void test_fuzz_regress(void **state)
{
    (void)state;
    static const char *const rdir = "tests/fuzz/regress/track_input";
    static uint8_t bytes[1 << 16];
    char why[1024], p[512];
    int n = 0;
    DIR *d = opendir(rdir);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue;
            snprintf(p, sizeof p, "%s/%s", rdir, e->d_name);
            FILE *f = fopen(p, "rb");
            if (!f) continue;
            const size_t len = fread(bytes, 1, sizeof bytes, f);
            fclose(f);
            if (mc_fuzz_track_input_check(p, bytes, len, why, sizeof why) != 0) fail_msg("%s: %s", p, why);
            n++;
        }
        closedir(d);
    }
    print_message("%d finding(s) of the track_input fuzzer replayed\n", n);
    /* and a few inputs of every kind through the same check */
    static const char *const inputs[] = {"P5 1 1 255\n\x01", "P2 2 1 3 1 9", "<camera><px>1</px></camera>",
                                         "1 2 3 4 5 6 7", "0 0 0\n1 2\n", "547,542,338,234", "", "#"};
    for (size_t i = 0; i < sizeof inputs / sizeof inputs[0]; i++) {
        const char *q = puts_("f.in", inputs[i]);
        if (mc_fuzz_track_input_check(q, (const uint8_t *)inputs[i], strlen(inputs[i]), why, sizeof why) != 0)
            fail_msg("\"%s\": %s", inputs[i], why);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pgm_p5),
        cmocka_unit_test(test_pgm_maxval),
        cmocka_unit_test(test_pgm_p2),
        cmocka_unit_test(test_pgm_errors),
        cmocka_unit_test(test_pgm_real),
        cmocka_unit_test(test_camera_parse),
        cmocka_unit_test(test_camera_xml),
        cmocka_unit_test(test_pose_read),
        cmocka_unit_test(test_pose_parse_limits),
        cmocka_unit_test(test_pose_known),
        cmocka_unit_test(test_pose_round_trip),
        cmocka_unit_test(test_orient),
        cmocka_unit_test(test_fuzz_regress),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
