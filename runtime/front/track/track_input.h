/* The tracker's outside data, read on the host (runtime/front/track/, the NAME-track front end):
 * camera frames (PGM), the camera's intrinsics (ViSP's tracker settings XML, or "px,py,u0,v0"),
 * poses (ViSP's vpPoseVector .pos files, or "tx,ty,tz,tux,tuy,tuz") and one orientation a frame
 * (a text file of rotation vectors: the 3-DOF mode's IMU).
 *
 * Promise: each reader either fills its outputs and returns 0 (mc_track_orient_next: 1 for a
 * frame, 0 at the end), or returns -1 with err holding exactly one line (no newline; cut to
 * errlen - 1 bytes) that names the file or the text and the exact place of the first fault. No
 * input crashes a reader, makes it read or write outside the caller's buffers, or takes more than
 * one pass over it; nothing here calls the heap (the tracker links with --wrap=malloc; stdio's own
 * buffers are libc's business). err may be NULL or errlen 0 when the caller wants no message.
 *
 * Places in messages:
 *   PGM                 "FILE: byte N: ..."      N the offset (from 0, as xxd shows it) of the first
 *                                                byte at fault, or the file's length at an early
 *                                                end; the same for P2 (text) as for P5
 *   XML, .pos, orient   "FILE:LINE:COL: ..."    from 1, COL in bytes
 *   command-line forms  "camera \"TEXT\": character N (NAME): ..."   N from 1
 *   a file not opened   "FILE: cannot open: <strerror>"
 *
 * Numbers (every text form): decimal only, [+-]digits[.digits][(e|E)[+-]digits] (".5" and "5."
 * too), at most 63 characters, read as in the C locale whatever locale is set; "nan", "inf", hex,
 * empty fields, a finite text that overflows a double and trailing junk are errors.
 *
 * Units: as ViSP writes them. Intrinsics in pixels in ViSP's convention (u = u0 + px x / z,
 * v = v0 + py y / z; the caller converts to Q16 for mc_camera_init). A pose: translation in metres,
 * rotation as the theta-u vector in radians, mapping object points to camera space, c = R p + t
 * (modelc/camera.h's mc_pose, whose mc_pose_set takes mc_track_pose_to_fixed's output).
 */
#ifndef MODELC_TRACK_INPUT_H
#define MODELC_TRACK_INPUT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* ---- frames: PGM ----------------------------------------------------------------------------
 * Binary P5 and plain P2, '#' comments (to the end of the line) anywhere in the header (and in P2,
 * between samples); width and height 1..MC_PGM_MAX_SIDE each; maxval 1..65535. Samples go to buf
 * as 8 bits, row by row: maxval 255 as they are, any other maxval scaled to 0..255 rounded to
 * nearest (halves up), v * 255 / maxval; P5 with maxval over 255 has 16-bit big-endian samples. A
 * sample above maxval is an error (P2 and P5 alike), as are a short raster, junk where a number
 * belongs, and w * h > cap. P5's raster starts after the single whitespace byte that ends maxval;
 * bytes after the raster are ignored (Netpbm allows several images in a file: this reads the
 * first).
 * buf NULL: the header only (w, h, cap ignored, the raster not read), so the caller can size its
 * buffer. On an error, *w and *h hold the header's values if it was read that far, else 0. */
#define MC_PGM_MAX_SIDE 4096
int mc_pgm_read(const char *path, uint8_t *buf, size_t cap, uint16_t *w, uint16_t *h, char *err, size_t errlen);

/* ---- the camera --------------------------------------------------------------------------------
 * Every value finite, px and py > 0, each below 32768 in magnitude (so that Q16 fits an int32). */
typedef struct mc_track_intrinsics {
    double px, py, u0, v0;   /* pixels */
} mc_track_intrinsics;

/* The command-line form "px,py,u0,v0" (spaces and tabs around a number allowed). */
int mc_track_camera_parse(const char *text, mc_track_intrinsics *cam, char *err, size_t errlen);

/* The <camera> element of a ViSP tracker settings file (mbt/cube.xml): its <px>, <py>, <u0> and
 * <v0>, in any order and at any depth inside it, among any other elements, comments and
 * processing instructions; the first <camera> in the file, and in it the first of each (ViSP's
 * camera files list the model without distortion first). Not a full XML parser: no entities, no
 * CDATA in the four values. A missing <camera> or field: one line naming it. */
int mc_track_camera_read_xml(const char *path, mc_track_intrinsics *cam, char *err, size_t errlen);

/* ---- poses ----------------------------------------------------------------------------------
 * pose = {tx, ty, tz (metres), tux, tuy, tuz (radians)}. Limits, checked by the readers: each
 * translation within the runtime's +-2^28 um (+-268.435456 m) once rounded to the micrometre;
 * each rotation component within +-MC_TRACK_TU_MAX rad (a rotation vector's angle matters modulo
 * 2 pi: anything that large is a mistake). */
#define MC_TRACK_T_MAX_UM (1L << 28)
#define MC_TRACK_TU_MAX 1000.0

/* A ViSP vpPoseVector file: six numbers separated by whitespace and newlines, '#' comments to the
 * end of a line. */
int mc_track_pose_read(const char *path, double pose[6], char *err, size_t errlen);

/* The command-line form "tx,ty,tz,tux,tuy,tuz" (spaces and tabs around a number allowed). */
int mc_track_pose_parse(const char *text, double pose[6], char *err, size_t errlen);

/* To mc_pose_set's form: q the unit quaternion (w, x, y, z) in Q30, w = cos(theta / 2),
 * (x, y, z) = sin(theta / 2) u for theta u the rotation vector (theta = 0: (2^30, 0, 0, 0)), each
 * component rounded to nearest; t_um the translation in micrometres rounded to nearest (halves
 * away from zero). Outside the readers' limits: the translation clamped to +-2^28 um, and a
 * rotation vector that is not finite taken as no rotation. */
void mc_track_pose_to_fixed(const double pose[6], int32_t q[4], int32_t t_um[3]);

/* The inverse, for writing poses back in ViSP's convention: q any non-zero quaternion (not
 * necessarily unit; q and -q give the same vector, theta in [0, pi]), q = 0 taken as no rotation. */
void mc_track_pose_from_fixed(const int32_t q[4], const int32_t t_um[3], double pose[6]);

/* ---- orientations (the 3-DOF mode) -----------------------------------------------------------
 * A text file with one line per frame holding three numbers, the rotation vector theta u (radians,
 * as the pose's), separated by spaces or tabs; '#' comments to the end of a line; lines with no
 * number are not frames. Read one frame at a time. */
typedef struct mc_track_orient_reader {
    FILE *f;
    const char *path;      /* as given to open, kept for messages */
    unsigned long line;    /* the line of the last frame returned */
    unsigned long frames;  /* frames returned so far */
    int failed;            /* after an error every call fails again */
    unsigned long next_line, next_col;   /* the place of the next byte (the reader's own) */
} mc_track_orient_reader;

int mc_track_orient_open(mc_track_orient_reader *r, const char *path, char *err, size_t errlen);
/* The next frame: 1 with q (Q30, as mc_track_pose_to_fixed's) and, when tu is not NULL, the
 * vector; 0 at the end of the file; -1 with the line and column of the fault. */
int mc_track_orient_next(mc_track_orient_reader *r, int32_t q[4], double tu[3], char *err, size_t errlen);
void mc_track_orient_close(mc_track_orient_reader *r);

#endif
