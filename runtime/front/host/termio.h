/* Terminal I/O for the interactive viewer: raw keys in, one composed frame out.
 *
 * Promise: mc_tio_enter puts the terminal in raw mode (bytes as typed, no echo, Ctrl-C as byte 3,
 * reads never block), catches SIGINT, SIGTERM, SIGHUP (quit) and SIGWINCH (resize) without
 * restarting system calls, and switches to the alternate screen with the cursor hidden;
 * mc_tio_leave undoes all of it, dropping keys not yet read. Output is composed in one static
 * buffer (mc_tio_put_*) and sent whole by mc_tio_flush, so the terminal never shows half a frame;
 * a frame longer than MC_TERM_OUT_BYTES is cut, never overrun. mc_tio_read_keys turns the bytes
 * waiting on stdin into characters and arrow keys, keeping an escape sequence cut between two reads
 * for the next call. No heap. POSIX terminals only.
 */
#ifndef MODELC_HOST_TERMIO_H
#define MODELC_HOST_TERMIO_H

#include <stddef.h>
#include <stdint.h>

/* MC_TERM_OUT_BYTES: the frame buffer. 8 MiB holds 200 000 cells, more than a 640x480 model on a
 * 640-column terminal; larger terminals get a shorter frame. Untouched pages cost no RAM. */
#ifndef MC_TERM_OUT_BYTES
#define MC_TERM_OUT_BYTES (8u << 20)
#endif

enum { MC_TIO_LEFT, MC_TIO_RIGHT, MC_TIO_UP, MC_TIO_DOWN };

/* 0, or -1 (errno set) when stdin is not a terminal; then nothing was changed. */
int mc_tio_enter(void);
void mc_tio_leave(void);

/* The number of the signal that asked to quit, 0 if none. */
int mc_tio_quit_signal(void);
/* Whether the terminal was resized since the last call (clears the flag). */
int mc_tio_resized(void);
/* Whether a key, a resize or a quit signal is waiting: cheap enough for a renderer's abort poll. */
int mc_tio_input_waiting(void);

/* The terminal's size in cells (80x24 when it cannot be asked). */
void mc_tio_size(int *cols, int *rows);

/* Composing a frame: start it, add to it, send it. */
void mc_tio_begin(void);
void mc_tio_put(const char *s, size_t n);
void mc_tio_put_str(const char *s);
void mc_tio_put_uint(unsigned v);
void mc_tio_put_move(int row, int col);   /* cursor to a 0-based cell */
void mc_tio_put_rgb(uint32_t rgb);         /* 0xRRGGBB as "R;G;B" */
/* 0, or -1 when the terminal is gone. */
int mc_tio_flush(void);
/* Writes n bytes now, outside the frame buffer. */
int mc_tio_write(const char *p, size_t n);

/* Reads every byte waiting on stdin without blocking: on_char for each plain byte, on_arrow with
 * MC_TIO_* for each arrow key (other escape sequences are dropped). Returns the number of bytes
 * read, or -1 at end of input. */
int mc_tio_read_keys(void (*on_char)(void *user, unsigned char c), void (*on_arrow)(void *user, int key), void *user);

/* Sleeps until a key arrives, a signal, or timeout_ms passes (-1: no timeout). */
void mc_tio_wait(int timeout_ms);

#endif
