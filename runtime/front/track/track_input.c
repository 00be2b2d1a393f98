/* The tracker's input readers (track_input.h). Each format is scanned one byte at a time through
 * stdio (getc is buffered), with the position of the next byte kept alongside, so that every error
 * can name its place; values go straight to the caller's buffers.
 * Long because the four formats share one scanner, one number syntax and one way of naming a place,
 * which splitting them would repeat. */
#include "track_input.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* ---- messages ------------------------------------------------------------------------------- */

/* err = the formatted message, any line break in it (from a path, say) made a '?' so that it stays
 * one line; returns -1 */
static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen > 0) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
        if (n < 0) err[0] = '\0';
        for (char *p = err; *p; p++)
            if (*p == '\n' || *p == '\r') *p = '?';
    }
    return -1;
}

/* Input bytes shown in a message: printable ASCII as is, others as \xNN, cut at 32 bytes. */
typedef struct shown {
    char s[32 * 4 + 8];
} shown;

static shown show_bytes(const char *p, size_t n)
{
    static const char hex[] = "0123456789abcdef";
    shown o;
    size_t k = 0;
    for (size_t i = 0; i < n && i < 32; i++) {
        const unsigned char c = (unsigned char)p[i];
        if (c >= 0x20 && c < 0x7f && c != '\\') {
            o.s[k++] = (char)c;
        } else {
            o.s[k++] = '\\', o.s[k++] = 'x', o.s[k++] = hex[c >> 4], o.s[k++] = hex[c & 15];
        }
    }
    if (n > 32) o.s[k++] = '.', o.s[k++] = '.', o.s[k++] = '.';
    o.s[k] = '\0';
    return o;
}

static shown show_char(int c)
{
    if (c == EOF) {
        shown o = {"end of file"};
        return o;
    }
    const char b = (char)c;
    const shown o = show_bytes(&b, 1);   /* at most 4 bytes */
    shown q = {"'"};
    memcpy(q.s + 1, o.s, 4);
    q.s[5] = '\0';
    memcpy(q.s + strlen(q.s), "'", 2);
    return q;
}

static int is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }
static int is_digit(int c) { return c >= '0' && c <= '9'; }

/* ---- numbers -------------------------------------------------------------------------------- */

#define NUM_MAX 63

enum { NUM_OK, NUM_EMPTY, NUM_LONG, NUM_BAD, NUM_RANGE };
static const char *const num_why[] = {"", "empty", "too long (over 63 characters)", "not a decimal number",
                                      "out of range"};

/* s[0..n): a decimal number as track_input.h has it. The grammar is checked here and strtod only
 * converts: so "nan", hex and a locale's other decimal point are refused, not half read. */
static int number(const char *s, size_t n, double *out)
{
    if (n == 0) return NUM_EMPTY;
    if (n > NUM_MAX) return NUM_LONG;
    size_t i = 0, d1 = 0, d2 = 0, d3 = 0;
    if (s[i] == '+' || s[i] == '-') i++;
    while (i < n && is_digit(s[i])) i++, d1++;
    if (i < n && s[i] == '.') {
        i++;
        while (i < n && is_digit(s[i])) i++, d2++;
    }
    if (d1 + d2 == 0) return NUM_BAD;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-')) i++;
        while (i < n && is_digit(s[i])) i++, d3++;
        if (d3 == 0) return NUM_BAD;
    }
    if (i != n) return NUM_BAD;
    char buf[NUM_MAX + 1], *end;
    memcpy(buf, s, n);
    buf[n] = '\0';
    const double v = strtod(buf, &end);
    if (end != buf + n) return NUM_BAD;   /* a locale whose decimal point is not '.' */
    if (!isfinite(v)) return NUM_RANGE;
    *out = v;
    return NUM_OK;
}

/* ---- limits ---------------------------------------------------------------------------------- */

static const char *const cam_names[4] = {"px", "py", "u0", "v0"};
static const char *const pose_names[6] = {"tx", "ty", "tz", "tux", "tuy", "tuz"};

/* why value v of camera field k is refused, or NULL */
static const char *cam_limit(int k, double v)
{
    if (k < 2 && !(v > 0)) return "must be above 0";
    if (!(fabs(v) < 32768)) return "must be below 32768 in magnitude (Q16 in an int32)";
    return NULL;
}

/* why value v of pose field k is refused, or NULL */
static const char *pose_limit(int k, double v)
{
    /* below 2^28 + 1/2 um rounds (halves away from zero) to at most 2^28 um */
    if (k < 3 && !(fabs(v) * 1e6 < (double)MC_TRACK_T_MAX_UM + 0.5))
        return "is beyond the runtime's +-2^28 um (+-268.435456 m)";
    if (k >= 3 && !(fabs(v) <= MC_TRACK_TU_MAX)) return "is beyond +-1000 rad";
    return NULL;
}

/* ---- command-line lists ------------------------------------------------------------------------ */

/* text: n numbers separated by ','; what names the form in messages ("camera", "pose") */
static int parse_list(const char *text, const char *what, const char *const names[], int n, double out[],
                      const char *(*limit)(int, double), char *err, size_t errlen)
{
    if (!text) return fail(err, errlen, "%s: no text", what);
    const size_t len = strlen(text);
    const shown t = show_bytes(text, len);
    size_t i = 0;
    for (int k = 0; k < n; k++) {
        while (text[i] == ' ' || text[i] == '\t') i++;
        const size_t start = i;
        while (text[i] && text[i] != ',' && text[i] != ' ' && text[i] != '\t') i++;
        const size_t end = i;
        while (text[i] == ' ' || text[i] == '\t') i++;
        if (text[i] && text[i] != ',') {   /* "1 2": junk after the number */
            return fail(err, errlen, "%s \"%s\": character %zu (%s): %s after the number", what, t.s, i + 1,
                        names[k], show_char((unsigned char)text[i]).s);
        }
        double v = 0;
        const int r = number(text + start, end - start, &v);
        if (r != NUM_OK) {
            const shown f = show_bytes(text + start, end - start);
            return fail(err, errlen, "%s \"%s\": character %zu (%s): %s%s%s%s", what, t.s, start + 1, names[k],
                        num_why[r], r == NUM_EMPTY ? "" : " \"", r == NUM_EMPTY ? "" : f.s, r == NUM_EMPTY ? "" : "\"");
        }
        const char *why = limit(k, v);
        if (why) return fail(err, errlen, "%s \"%s\": character %zu (%s): %g %s", what, t.s, start + 1, names[k], v, why);
        out[k] = v;
        if (k < n - 1) {
            if (text[i] != ',')
                return fail(err, errlen, "%s \"%s\": character %zu: %d numbers, expected %d", what, t.s, i + 1,
                            k + 1, n);
            i++;
        } else if (text[i]) {
            return fail(err, errlen, "%s \"%s\": character %zu: more than %d numbers", what, t.s, i + 1, n);
        }
    }
    return 0;
}

int mc_track_camera_parse(const char *text, mc_track_intrinsics *cam, char *err, size_t errlen)
{
    double v[4];
    if (parse_list(text, "camera", cam_names, 4, v, cam_limit, err, errlen) != 0) return -1;
    cam->px = v[0], cam->py = v[1], cam->u0 = v[2], cam->v0 = v[3];
    return 0;
}

int mc_track_pose_parse(const char *text, double pose[6], char *err, size_t errlen)
{
    double v[6];
    if (parse_list(text, "pose", pose_names, 6, v, pose_limit, err, errlen) != 0) return -1;
    memcpy(pose, v, sizeof v);
    return 0;
}

/* ---- opening ---------------------------------------------------------------------------------- */

static FILE *open_in(const char *path, char *err, size_t errlen)
{
    if (!path) {
        fail(err, errlen, "(no file name): cannot open");
        return NULL;
    }
    errno = 0;
    FILE *f = fopen(path, "rb");
    if (!f) fail(err, errlen, "%s: cannot open: %s", path, errno ? strerror(errno) : "unknown error");
    return f;
}

/* ---- PGM ---------------------------------------------------------------------------------------- */

typedef struct pgm_in {
    FILE *f;
    const char *path;
    unsigned long long off;   /* of the next byte */
    char *err;
    size_t errlen;
} pgm_in;

static int pgm_getc(pgm_in *in)
{
    const int c = getc(in->f);
    if (c != EOF) in->off++;
    return c;
}

static void pgm_unget(pgm_in *in, int c)
{
    if (c == EOF) return;
    ungetc(c, in->f);
    in->off--;
}

/* "FILE: byte N: ..." */
static int pgm_fail(pgm_in *in, unsigned long long at, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return fail(in->err, in->errlen, "%s: byte %llu: %s", in->path, at, what);
}

/* an early end: a read error, or the end of the file */
static int pgm_end(pgm_in *in, const char *fmt, ...)
{
    char what[200];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (ferror(in->f)) return pgm_fail(in, in->off, "read error %s", what);
    return pgm_fail(in, in->off, "end of file %s", what);
}

/* skips whitespace and comments; returns the next other byte (consumed) or EOF */
static int pgm_skip(pgm_in *in)
{
    for (;;) {
        int c = pgm_getc(in);
        if (c == '#') {
            do c = pgm_getc(in);
            while (c != EOF && c != '\n' && c != '\r');
            if (c == EOF) return EOF;
            continue;
        }
        if (!is_space(c)) return c;
    }
}

/* An unsigned decimal number, after whitespace and comments, in lo..hi; name for messages. The
 * byte after it must be whitespace (consumed; returned in *term), '#' or the end (left to be
 * read). *at: its first byte's offset. */
static int pgm_number(pgm_in *in, const char *name, unsigned long lo, unsigned long hi, unsigned long *out,
                      unsigned long long *at, int *term)
{
    int c = pgm_skip(in);
    if (c == EOF) return pgm_end(in, "before the %s", name);
    *at = in->off - 1;
    if (!is_digit(c)) return pgm_fail(in, *at, "%s expected, found %s", name, show_char(c).s);
    unsigned long v = 0;
    int big = 0;
    for (; is_digit(c); c = pgm_getc(in)) {
        if (v > 10000000UL) big = 1;
        else v = v * 10 + (unsigned long)(c - '0');
    }
    if (c != EOF && !is_space(c) && c != '#')
        return pgm_fail(in, in->off - 1, "%s after the %s", show_char(c).s, name);
    if (c == '#') pgm_unget(in, c);
    if (c == EOF && ferror(in->f)) return pgm_end(in, "in the %s", name);
    if (big || v < lo || v > hi) {
        if (big) return pgm_fail(in, *at, "%s too large (%lu..%lu)", name, lo, hi);
        return pgm_fail(in, *at, "%s %lu is not in %lu..%lu", name, v, lo, hi);
    }
    *out = v;
    *term = c;
    return 0;
}

/* v (<= maxval) to 8 bits, rounded to nearest, halves up */
static uint8_t scale(unsigned long v, unsigned long maxval) { return (uint8_t)((v * 255 + maxval / 2) / maxval); }

static int pgm_raster_p5(pgm_in *in, uint8_t *buf, size_t n, unsigned long maxval)
{
    if (maxval == 255) {   /* the common case, in one read */
        const size_t got = fread(buf, 1, n, in->f);
        in->off += got;
        if (got < n) return pgm_end(in, "after %zu of %zu pixels", got, n);
        return 0;
    }
    const int wide = maxval > 255;
    for (size_t i = 0; i < n; i++) {
        const unsigned long long at = in->off;
        int c = pgm_getc(in);
        if (c == EOF) return pgm_end(in, "after %zu of %zu pixels", i, n);
        unsigned long v = (unsigned long)c;
        if (wide) {
            c = pgm_getc(in);
            if (c == EOF) return pgm_end(in, "inside pixel %zu of %zu (2 bytes each)", i, n);
            v = v << 8 | (unsigned long)c;
        }
        if (v > maxval) return pgm_fail(in, at, "pixel %zu: %lu is above the maxval %lu", i, v, maxval);
        buf[i] = scale(v, maxval);
    }
    return 0;
}

static int pgm_raster_p2(pgm_in *in, uint8_t *buf, size_t n, unsigned long maxval)
{
    for (size_t i = 0; i < n; i++) {
        int c = pgm_skip(in);
        if (c == EOF) return pgm_end(in, "after %zu of %zu samples", i, n);
        const unsigned long long at = in->off - 1;
        if (!is_digit(c)) return pgm_fail(in, at, "sample %zu: %s is not a decimal digit", i, show_char(c).s);
        unsigned long v = 0;
        for (; is_digit(c); c = pgm_getc(in))
            if (v <= 65535) v = v * 10 + (unsigned long)(c - '0');
        if (c != EOF && !is_space(c) && c != '#')
            return pgm_fail(in, in->off - 1, "sample %zu: %s after the number", i, show_char(c).s);
        if (c == '#') pgm_unget(in, c);
        if (v > maxval) {
            if (v > 65535) return pgm_fail(in, at, "sample %zu is above the maxval %lu", i, maxval);
            return pgm_fail(in, at, "sample %zu: %lu is above the maxval %lu", i, v, maxval);
        }
        buf[i] = maxval == 255 ? (uint8_t)v : scale(v, maxval);
    }
    return 0;
}

static int pgm_read(pgm_in *in, uint8_t *buf, size_t cap, uint16_t *w, uint16_t *h)
{
    int c = pgm_getc(in);
    if (c == EOF) return pgm_end(in, "(an empty file): not a PGM file");
    if (c != 'P') return pgm_fail(in, 0, "not a PGM file (it starts with %s, not P5 or P2)", show_char(c).s);
    const int kind = pgm_getc(in);
    if (kind == EOF) return pgm_end(in, "after 'P': not a PGM file");
    if (kind != '5' && kind != '2') {
        if (kind == '1' || kind == '4') return pgm_fail(in, 1, "P%c is a bitmap (PBM), not a grey-level PGM (P5 or P2)", kind);
        if (kind == '3' || kind == '6') return pgm_fail(in, 1, "P%c is a colour image (PPM), not a grey-level PGM (P5 or P2)", kind);
        return pgm_fail(in, 1, "P followed by %s: not a PGM file (P5 or P2)", show_char(kind).s);
    }
    c = pgm_getc(in);
    if (c != EOF && !is_space(c) && c != '#') return pgm_fail(in, 2, "%s after the magic number P%c", show_char(c).s, kind);
    pgm_unget(in, c);

    unsigned long width, height, maxval;
    unsigned long long wat, hat, mat;
    int term;
    if (pgm_number(in, "width", 1, MC_PGM_MAX_SIDE, &width, &wat, &term) != 0) return -1;
    if (pgm_number(in, "height", 1, MC_PGM_MAX_SIDE, &height, &hat, &term) != 0) return -1;
    *w = (uint16_t)width, *h = (uint16_t)height;
    if (pgm_number(in, "maxval", 1, 65535, &maxval, &mat, &term) != 0) return -1;
    if (!buf) return 0;
    const size_t n = (size_t)width * height;
    if (n > cap) return pgm_fail(in, wat, "%lux%lu pixels do not fit the buffer of %zu", width, height, cap);
    if (kind == '2') return pgm_raster_p2(in, buf, n, maxval);
    /* P5: the raster starts after one whitespace byte; a comment there ends with its line break */
    if (term == EOF) return pgm_end(in, "after the maxval (no raster)");
    if (term == '#') {
        do c = pgm_getc(in);
        while (c != EOF && c != '\n' && c != '\r');
        if (c == EOF) return pgm_end(in, "in a comment after the maxval (no raster)");
    }
    return pgm_raster_p5(in, buf, n, maxval);
}

int mc_pgm_read(const char *path, uint8_t *buf, size_t cap, uint16_t *w, uint16_t *h, char *err, size_t errlen)
{
    uint16_t ww = 0, hh = 0;
    FILE *f = open_in(path, err, errlen);
    int r = -1;
    if (f) {
        pgm_in in = {f, path, 0, err, errlen};
        r = pgm_read(&in, buf, cap, &ww, &hh);
        fclose(f);
    }
    if (w) *w = ww;
    if (h) *h = hh;
    return r;
}

/* ---- text files: line and column -------------------------------------------------------------- */

typedef struct txt_in {
    FILE *f;
    const char *path;
    unsigned long line, col;   /* of the next byte */
    unsigned long pline, pcol; /* before the last byte read, for txt_unget */
    char *err;
    size_t errlen;
} txt_in;

static int txt_getc(txt_in *t)
{
    const int c = getc(t->f);
    t->pline = t->line, t->pcol = t->col;
    if (c == '\n') t->line++, t->col = 1;
    else if (c != EOF) t->col++;
    return c;
}

static void txt_unget(txt_in *t, int c)
{
    if (c == EOF) return;
    ungetc(c, t->f);
    t->line = t->pline, t->col = t->pcol;
}

/* "FILE:LINE:COL: ..." */
static int txt_fail(txt_in *t, unsigned long line, unsigned long col, const char *fmt, ...)
{
    char what[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return fail(t->err, t->errlen, "%s:%lu:%lu: %s", t->path, line, col, what);
}

/* at the end of the input: a read error or the end of the file, at the current place */
static int txt_end(txt_in *t, const char *what)
{
    return txt_fail(t, t->line, t->col, "%s %s", ferror(t->f) ? "read error" : "end of file", what);
}

/* A token of the number files: bytes up to whitespace, '#' or the end (left unread). Skips
 * whitespace (and line breaks unless in_line) and comments before it. Returns 1 with the token
 * (tok, at most NUM_MAX + 1 bytes kept: more is "too long"), its length and place; 0 at the end
 * of the file (or of the line when in_line). */
static int txt_token(txt_in *t, int in_line, char tok[NUM_MAX + 2], size_t *len, unsigned long *line,
                     unsigned long *col)
{
    int c;
    for (;;) {
        c = txt_getc(t);
        if (c == '#') {
            do c = txt_getc(t);
            while (c != EOF && c != '\n');
        }
        if (c == EOF) return 0;
        if (c == '\n' && in_line) return 0;
        if (!is_space(c)) break;
    }
    *line = t->pline, *col = t->pcol;
    size_t n = 0;
    for (; c != EOF && !is_space(c) && c != '#'; c = txt_getc(t))
        if (n < NUM_MAX + 1) tok[n++] = (char)c;
    *len = n;
    txt_unget(t, c);
    return 1;
}

/* tok as a number for field name, with limit; an error names its place */
static int txt_number(txt_in *t, const char *tok, size_t len, unsigned long line, unsigned long col,
                      const char *name, int k, const char *(*limit)(int, double), double *out)
{
    double v = 0;
    const int r = number(tok, len, &v);
    if (r != NUM_OK) return txt_fail(t, line, col, "%s: %s \"%s\"", name, num_why[r], show_bytes(tok, len).s);
    const char *why = limit(k, v);
    if (why) return txt_fail(t, line, col, "%s %g %s", name, v, why);
    *out = v;
    return 0;
}

/* ---- poses ---------------------------------------------------------------------------------- */

int mc_track_pose_read(const char *path, double pose[6], char *err, size_t errlen)
{
    FILE *f = open_in(path, err, errlen);
    if (!f) return -1;
    txt_in t = {f, path, 1, 1, 1, 1, err, errlen};
    double v[6];
    char tok[NUM_MAX + 2];
    size_t len;
    unsigned long line, col;
    int r = 0;
    for (int k = 0; k < 6 && r == 0; k++) {
        if (!txt_token(&t, 0, tok, &len, &line, &col)) {
            char what[100];
            snprintf(what, sizeof what, "after %d numbers, expected 6 (tx ty tz tux tuy tuz)", k);
            r = txt_end(&t, what);
        } else {
            r = txt_number(&t, tok, len, line, col, pose_names[k], k, pose_limit, &v[k]);
        }
    }
    if (r == 0 && txt_token(&t, 0, tok, &len, &line, &col))
        r = txt_fail(&t, line, col, "more than 6 numbers (tx ty tz tux tuy tuz): \"%s\"", show_bytes(tok, len).s);
    if (r == 0 && ferror(f)) r = txt_end(&t, "");
    fclose(f);
    if (r == 0) memcpy(pose, v, sizeof v);
    return r;
}

/* Q30 of v in [-1, 1], rounded to nearest */
static int32_t q30(double v) { return (int32_t)floor(v * 1073741824.0 + 0.5); }

static void tu_to_q(const double tu[3], int32_t q[4])
{
    const double theta = sqrt(tu[0] * tu[0] + tu[1] * tu[1] + tu[2] * tu[2]);
    if (!isfinite(theta) || theta == 0) {
        q[0] = 1 << 30, q[1] = q[2] = q[3] = 0;
        return;
    }
    /* sin(theta / 2) / theta without the cancellation of a tiny theta */
    const double s = theta < 1e-4 ? 0.5 - theta * theta / 48 : sin(theta / 2) / theta;
    q[0] = q30(cos(theta / 2));
    for (int k = 0; k < 3; k++) q[k + 1] = q30(s * tu[k]);
}

void mc_track_pose_to_fixed(const double pose[6], int32_t q[4], int32_t t_um[3])
{
    for (int k = 0; k < 3; k++) {
        double um = pose[k] * 1e6;
        um = um >= 0 ? floor(um + 0.5) : -floor(-um + 0.5);
        if (!(um >= -(double)MC_TRACK_T_MAX_UM)) um = um != um ? 0 : -(double)MC_TRACK_T_MAX_UM;   /* NaN: 0 */
        if (um > (double)MC_TRACK_T_MAX_UM) um = (double)MC_TRACK_T_MAX_UM;
        t_um[k] = (int32_t)um;
    }
    tu_to_q(pose + 3, q);
}

void mc_track_pose_from_fixed(const int32_t q[4], const int32_t t_um[3], double pose[6])
{
    /* q and -q are one rotation: w >= 0 puts theta in [0, pi] */
    const double sg = q[0] < 0 ? -1.0 : 1.0;
    const double w = sg * q[0], x = sg * q[1], y = sg * q[2], z = sg * q[3];
    const double n = sqrt(x * x + y * y + z * z);
    /* theta / n stays accurate as n goes to 0: atan2 is accurate relative to its result */
    const double f = n > 0 ? 2 * atan2(n, w) / n : 0;
    for (int k = 0; k < 3; k++) pose[k] = t_um[k] / 1e6;
    pose[3] = f * x, pose[4] = f * y, pose[5] = f * z;
}

/* ---- orientations ----------------------------------------------------------------------------- */

int mc_track_orient_open(mc_track_orient_reader *r, const char *path, char *err, size_t errlen)
{
    r->path = path, r->line = 0, r->frames = 0, r->failed = 0;
    r->next_line = 1, r->next_col = 1;
    r->f = open_in(path, err, errlen);
    if (!r->f) {
        r->failed = 1;
        return -1;
    }
    return 0;
}

int mc_track_orient_next(mc_track_orient_reader *r, int32_t q[4], double tu[3], char *err, size_t errlen)
{
    if (r->failed || !r->f)
        return fail(err, errlen, "%s: the orientation file failed already", r->path ? r->path : "(no file name)");
    txt_in t = {r->f, r->path, r->next_line, r->next_col, r->next_line, r->next_col, err, errlen};
    static const char *const names[3] = {"tux", "tuy", "tuz"};
    char tok[NUM_MAX + 2];
    size_t len;
    unsigned long line, col, first = 0, end_line = 0, end_col = 0;
    double v[3];
    int k = 0, res = 0;
    for (;;) {   /* each token of the next line that has one */
        if (!txt_token(&t, 1, tok, &len, &line, &col)) {
            if (ferror(r->f)) {
                res = txt_end(&t, "");
                break;
            }
            if (k == 0 && !feof(r->f)) continue;   /* a line without a number */
            if (k == 0) return 0;                  /* the end */
            if (k < 3) res = txt_fail(&t, end_line, end_col, "%d numbers, expected 3 (tux tuy tuz)", k);
            break;
        }
        if (k == 0) first = line;
        if (k == 3) {
            res = txt_fail(&t, line, col, "more than 3 numbers (tux tuy tuz): \"%s\"", show_bytes(tok, len).s);
            break;
        }
        if (txt_number(&t, tok, len, line, col, names[k], 3 + k, pose_limit, &v[k]) != 0) {
            res = -1;
            break;
        }
        k++;
        end_line = t.line, end_col = t.col;   /* just after the number */
    }
    if (res != 0) {
        r->failed = 1;
        return res;
    }
    r->next_line = t.line, r->next_col = t.col;
    r->line = first;
    r->frames++;
    tu_to_q(v, q);
    if (tu) tu[0] = v[0], tu[1] = v[1], tu[2] = v[2];
    return 1;
}

void mc_track_orient_close(mc_track_orient_reader *r)
{
    if (r->f) fclose(r->f);
    r->f = NULL;
}

/* ---- the camera in ViSP's XML ----------------------------------------------------------------- */

/* Reads up to and including "end" (a 2- or 3-byte closer: "-->", "?>"), or to '>' if end is NULL,
 * stepping over quoted attribute values. Returns 0, or -1 at the end of the file. Sets *selfclose
 * when the tag ended "/>". */
static int xml_skip_to(txt_in *t, const char *end, int *selfclose)
{
    int c, prev = 0, prev2 = 0, quote = 0;
    const size_t n = end ? strlen(end) : 0;
    while ((c = txt_getc(t)) != EOF) {
        if (!end) {
            if (quote) {
                if (c == quote) quote = 0;
            } else if (c == '"' || c == '\'') {
                quote = c;
            } else if (c == '>') {
                if (selfclose) *selfclose = prev == '/';
                return 0;
            }
        } else if (c == end[n - 1] && (n < 2 || prev == end[n - 2]) && (n < 3 || prev2 == end[n - 3])) {
            return 0;
        }
        prev2 = prev, prev = c;
    }
    return -1;
}

static int is_name(int c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || is_digit(c) || c == '_' || c == '-' || c == '.' ||
           c == ':';
}

enum { TAG_OPEN, TAG_CLOSE, TAG_OTHER };

/* After '<': the tag's kind and name (cut to 15 bytes: the names sought are short), the rest of the
 * tag read. Returns -1 at the end of the file (message set). */
static int xml_tag(txt_in *t, int *kind, char name[16], int *selfclose)
{
    const unsigned long line = t->pline, col = t->pcol;
    int c = txt_getc(t);
    *selfclose = 0;
    name[0] = '\0';
    if (c == '!' || c == '?') {
        *kind = TAG_OTHER;
        int r;
        if (c == '?') {
            r = xml_skip_to(t, "?>", NULL);
        } else {
            const int c1 = txt_getc(t);
            const int c2 = c1 == '-' ? txt_getc(t) : 0;
            if (c1 == '-' && c2 == '-') r = xml_skip_to(t, "-->", NULL);
            else if (c1 == EOF || c2 == EOF) r = -1;
            else if (c1 == '>' || c2 == '>') r = 0;   /* "<!>", "<!->": already over */
            else r = xml_skip_to(t, NULL, NULL);   /* <!DOCTYPE ...> */
        }
        if (r != 0) return txt_fail(t, line, col, "end of file inside this %s", c == '?' ? "<?...?>" : "<!...>");
        return 0;
    }
    *kind = TAG_OPEN;
    if (c == '/') *kind = TAG_CLOSE, c = txt_getc(t);
    size_t n = 0;
    for (; c != EOF && is_name(c); c = txt_getc(t))
        if (n < 15) name[n++] = (char)c;
    name[n] = '\0';
    txt_unget(t, c);
    if (xml_skip_to(t, NULL, selfclose) != 0) return txt_fail(t, line, col, "end of file inside this tag");
    return 0;
}

static int xml_camera(txt_in *t, mc_track_intrinsics *cam)
{
    double v[4];
    int have[4] = {0, 0, 0, 0}, in_camera = 0, c, kind, selfclose;
    unsigned long cam_line = 0, cam_col = 0;
    char name[16];
    while ((c = txt_getc(t)) != EOF) {
        if (c != '<') continue;
        const unsigned long tline = t->pline, tcol = t->pcol;
        if (xml_tag(t, &kind, name, &selfclose) != 0) return -1;
        if (!in_camera) {
            if (kind == TAG_OPEN && strcmp(name, "camera") == 0) {
                in_camera = 1, cam_line = tline, cam_col = tcol;
                if (selfclose) return txt_fail(t, tline, tcol, "<camera/> is empty: no <px>");
            }
            continue;
        }
        if (kind == TAG_CLOSE && strcmp(name, "camera") == 0) {
            for (int k = 0; k < 4; k++)
                if (!have[k])
                    return txt_fail(t, tline, tcol, "the <camera> of line %lu has no <%s>", cam_line, cam_names[k]);
            cam->px = v[0], cam->py = v[1], cam->u0 = v[2], cam->v0 = v[3];
            return 0;
        }
        int k = 0;
        while (k < 4 && strcmp(name, cam_names[k]) != 0) k++;
        if (kind != TAG_OPEN || k == 4 || have[k]) continue;   /* others, and a field's later copies */
        if (selfclose) return txt_fail(t, tline, tcol, "<%s/> is empty: a number expected", name);
        /* the text up to the next '<', trimmed; the place of its first byte */
        char tok[NUM_MAX + 1];
        size_t len = 0;
        int overflow = 0;
        unsigned long nline = t->line, ncol = t->col;
        while ((c = txt_getc(t)) != EOF && c != '<') {
            if (len == 0 && is_space(c)) {
                nline = t->line, ncol = t->col;
                continue;
            }
            if (len < sizeof tok) tok[len++] = (char)c;
            else if (!is_space(c)) overflow = 1;
        }
        if (c == EOF) {
            char what[40];
            snprintf(what, sizeof what, "inside <%s>", name);
            return txt_end(t, what);
        }
        while (len > 0 && is_space((unsigned char)tok[len - 1])) len--;
        const unsigned long eline = t->pline, ecol = t->pcol;
        int ekind, esc;
        char ename[16];
        if (xml_tag(t, &ekind, ename, &esc) != 0) return -1;
        if (ekind != TAG_CLOSE || strcmp(ename, name) != 0)
            return txt_fail(t, eline, ecol, "<%s> holds more than a number (no </%s> here)", name, name);
        double x = 0;
        const int r = overflow ? NUM_LONG : number(tok, len, &x);
        if (r != NUM_OK)
            return txt_fail(t, nline, ncol, "<%s>: %s \"%s\"", name, num_why[r], show_bytes(tok, len).s);
        const char *why = cam_limit(k, x);
        if (why) return txt_fail(t, nline, ncol, "<%s> %g %s", name, x, why);
        v[k] = x, have[k] = 1;
    }
    if (ferror(t->f)) return txt_end(t, "");
    if (in_camera)
        return txt_fail(t, t->line, t->col, "end of file inside the <camera> of line %lu, column %lu", cam_line, cam_col);
    return fail(t->err, t->errlen, "%s: no <camera> element", t->path);
}

int mc_track_camera_read_xml(const char *path, mc_track_intrinsics *cam, char *err, size_t errlen)
{
    FILE *f = open_in(path, err, errlen);
    if (!f) return -1;
    txt_in t = {f, path, 1, 1, 1, 1, err, errlen};
    const int r = xml_camera(&t, cam);
    fclose(f);
    return r;
}
