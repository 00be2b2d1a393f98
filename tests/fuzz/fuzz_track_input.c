/* libFuzzer target: the tracker's input readers (runtime/front/track/track_input.c) on any bytes.
 * The bytes go to a file, which every reader then reads: mc_pgm_read (header only, and into a
 * 1 MiB buffer), the ViSP XML camera, the .pos pose, the orientation file to its end; and, as text,
 * the command-line camera and pose forms. A crash, a sanitizer report, or an error that is not
 * exactly one non-empty line naming its file is a finding (abort).
 *
 * The unit test (tests/unit/test_track_input.c) links this file too and replays
 * tests/fuzz/regress/track_input/ through mc_fuzz_track_input_check, so that make test runs every
 * finding again. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../runtime/front/track/track_input.h"

int mc_fuzz_track_input_check(const char *path, const uint8_t *text, size_t n, char *why, size_t whylen);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* why err (after a reader returned r) breaks the promise, or NULL; prefix: what it must start with */
static const char *bad_message(int r, int want_fail, const char *err, const char *prefix)
{
    if (r != -1 && want_fail) return "returned other than -1";
    if (r != -1) return NULL;
    if (err[0] == '\0') return "an empty message";
    if (strchr(err, '\n') || strchr(err, '\r')) return "a message of more than one line";
    if (strncmp(err, prefix, strlen(prefix)) != 0) return "a message that does not start with its file or form";
    return NULL;
}

/* Every reader on the file at path, and on text[0..n) (any bytes; a NUL ends the text forms).
 * Returns 0, or -1 with why set. */
int mc_fuzz_track_input_check(const char *path, const uint8_t *text, size_t n, char *why, size_t whylen)
{
    static uint8_t frame[1 << 20];
    static char str[8192];
    char err[512];
    const char *bad;
    uint16_t w = 0, h = 0;
    int r;
#define CHECK(what, prefix, want_fail)                                                            \
    do {                                                                                            \
        if ((bad = bad_message(r, want_fail, err, prefix)) != NULL) {                               \
            snprintf(why, whylen, "%s: %s: \"%s\"", what, bad, err);                                \
            return -1;                                                                              \
        }                                                                                           \
    } while (0)
    err[0] = '\0';
    r = mc_pgm_read(path, NULL, 0, &w, &h, err, sizeof err);
    CHECK("mc_pgm_read (header)", path, 0);
    if (r == 0 && (w < 1 || h < 1 || w > MC_PGM_MAX_SIDE || h > MC_PGM_MAX_SIDE)) {
        snprintf(why, whylen, "mc_pgm_read (header): %ux%u accepted", w, h);
        return -1;
    }
    err[0] = '\0';
    r = mc_pgm_read(path, frame, sizeof frame, &w, &h, err, sizeof err);
    CHECK("mc_pgm_read", path, 0);
    /* a short error buffer: cut, still one terminated line */
    r = mc_pgm_read(path, frame, 64, &w, &h, err, 12);
    if (r == -1 && strlen(err) > 11) {
        snprintf(why, whylen, "mc_pgm_read: message longer than its buffer");
        return -1;
    }
    mc_track_intrinsics cam;
    err[0] = '\0';
    r = mc_track_camera_read_xml(path, &cam, err, sizeof err);
    CHECK("mc_track_camera_read_xml", path, 0);
    if (r == 0 && !(cam.px > 0 && cam.py > 0 && cam.px < 32768 && cam.py < 32768 && cam.u0 > -32768 &&
                    cam.u0 < 32768 && cam.v0 > -32768 && cam.v0 < 32768)) {
        snprintf(why, whylen, "mc_track_camera_read_xml: a value outside the limits accepted");
        return -1;
    }
    double pose[6], back[6];
    int32_t q[4], t[3];
    err[0] = '\0';
    r = mc_track_pose_read(path, pose, err, sizeof err);
    CHECK("mc_track_pose_read", path, 0);
    if (r == 0) {
        mc_track_pose_to_fixed(pose, q, t);
        mc_track_pose_from_fixed(q, t, back);
    }
    mc_track_orient_reader o;
    err[0] = '\0';
    r = mc_track_orient_open(&o, path, err, sizeof err);
    CHECK("mc_track_orient_open", path, 0);
    if (r == 0) {
        double tu[3];
        for (;;) {
            err[0] = '\0';
            r = mc_track_orient_next(&o, q, tu, err, sizeof err);
            if (r == 1) continue;
            if (r == -1) {
                CHECK("mc_track_orient_next", path, 1);
                r = mc_track_orient_next(&o, q, tu, err, sizeof err);   /* fails again */
                CHECK("mc_track_orient_next after an error", path, 1);
            }
            break;
        }
        mc_track_orient_close(&o);
    }
    /* the command-line forms on the bytes as a string */
    const size_t m = n < sizeof str - 1 ? n : sizeof str - 1;
    memcpy(str, text, m);
    str[m] = '\0';
    err[0] = '\0';
    r = mc_track_camera_parse(str, &cam, err, sizeof err);
    CHECK("mc_track_camera_parse", "camera \"", 0);
    err[0] = '\0';
    r = mc_track_pose_parse(str, pose, err, sizeof err);
    CHECK("mc_track_pose_parse", "pose \"", 0);
#undef CHECK
    return 0;
}

static char path[64];
static void remove_path(void) { remove(path); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!path[0]) {
        snprintf(path, sizeof path, "/tmp/fuzz-track_input-%ld.in", (long)getpid());   /* one per worker */
        atexit(remove_path);
    }
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    if (fclose(f) != 0) abort();
    char why[1024];
    if (mc_fuzz_track_input_check(path, data, size, why, sizeof why) != 0) {
        fprintf(stderr, "fuzz_track_input: %s\n", why);
        abort();
    }
    return 0;
}
