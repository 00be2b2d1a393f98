/* The host viewer's stream input: a streamed bake (modelc --emit stream) arriving from standard
 * input, a file or FIFO, or a TCP connection, fed to the runtime's reader (modelc/stream.h).
 *
 * Promise: mc_host_stream_open opens a source named "-" (standard input), "tcp:HOST:PORT" (connects;
 * the stream is what the peer sends until it closes) or any other path; it never blocks on a read
 * after that: mc_host_stream_pump takes what has arrived, feeds it into the app binding's stream
 * buffer (app.h stream_buf, sized at bake time) and says whether a deeper level became drawable.
 * When the source ends or the reader refuses the stream, the source is closed and `done` set;
 * mc_host_stream_octree stays the deepest level that was complete and checked before, so a front
 * end keeps its last good frame. A version-2 stream's mesh part (mc_host_stream_pmesh) likewise
 * stays at the finest level that had come; one larger than the app binding's mesh buffers (the
 * bake's vertices, faces and index width) stops the stream instead. mc_host_stream_status
 * describes where the stream is in one line ("depth 5 of 8, mesh 1088 of 37706 vertices after
 * 10234 of 401233 bytes", or the error and the byte where it was found).
 */
#ifndef MODELC_HOST_STREAM_IN_H
#define MODELC_HOST_STREAM_IN_H

#include <stddef.h>
#include <stdint.h>
#include <modelc/app.h>
#include <modelc/stream.h>

typedef struct mc_host_stream {
    mc_stream reader;
    int fd;              /* -1 once closed */
    int done;            /* the source ended or the reader stopped */
    int error;           /* MC_STREAM_OK, the reader's MC_STREAM_ERR_*, 1: the source failed (errno_at_fail),
                            or 2: the stream's mesh does not fit the app's buffers */
    int errno_at_fail;
    unsigned depth;      /* mc_stream_depth when last pumped */
    uint32_t mesh_level; /* mc_stream_mesh_level when last pumped */
    int mesh_lines;      /* the mesh's adjacency had come then */
    const mc_app *app;
} mc_host_stream;

/* Opens src for app's stream buffer. Returns 0, or -1 with a one-line reason in why (why_n bytes):
 * the bake has no stream buffer, the source cannot be opened or connected. */
int mc_host_stream_open(mc_host_stream *s, const mc_app *app, const char *src, char *why, size_t why_n);

/* Reads what has arrived without waiting (block: wait for at least one byte or the end). Returns 1
 * when the drawable depth, the mesh level or the mesh's line styles grew, else 0. */
int mc_host_stream_pump(mc_host_stream *s, int block);

/* Pumps until the source ends or the reader stops. */
void mc_host_stream_drain(mc_host_stream *s);

/* The deepest drawable level (NULL: none yet). */
const mc_octree *mc_host_stream_octree(const mc_host_stream *s);

/* The mesh part (NULL: none yet, or none that fits); levels up to s->mesh_level have come. */
const mc_pmesh *mc_host_stream_pmesh(const mc_host_stream *s);

/* One line on where the stream is, for a status line or stderr. */
void mc_host_stream_status(const mc_host_stream *s, char *line, size_t n);

/* Whether the stream ended complete and valid. */
int mc_host_stream_ok(const mc_host_stream *s);

#endif
