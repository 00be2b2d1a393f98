/* The host viewer's stream input: see stream_in.h. */
#define _POSIX_C_SOURCE 200809L
#include "stream_in.h"

#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

/* "tcp:HOST:PORT" -> a connected socket, or -1 with why. */
static int connect_tcp(const char *spec, char *why, size_t why_n)
{
    char host[256];
    const char *colon = strrchr(spec, ':');
    size_t hn = colon ? (size_t)(colon - spec) : 0;
    if (!colon || hn == 0 || hn >= sizeof host || !colon[1]) {
        snprintf(why, why_n, "--stream tcp: expects tcp:HOST:PORT: tcp:%s", spec);
        return -1;
    }
    memcpy(host, spec, hn);
    host[hn] = 0;
    struct addrinfo hints, *res = NULL;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    int rc = getaddrinfo(host, colon + 1, &hints, &res);
    if (rc) {
        snprintf(why, why_n, "cannot resolve tcp:%s: %s", spec, gai_strerror(rc));
        return -1;
    }
    int fd = -1, err = 0;
    for (struct addrinfo *a = res; a; a = a->ai_next) {
        fd = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
        if (fd < 0) { err = errno; continue; }
        if (connect(fd, a->ai_addr, a->ai_addrlen) == 0) break;
        err = errno;
        close(fd);
        fd = -1;
    }
    freeaddrinfo(res);
    if (fd < 0) snprintf(why, why_n, "cannot connect to tcp:%s: %s", spec, strerror(err));
    return fd;
}

int mc_host_stream_open(mc_host_stream *s, const mc_app *app, const char *src, char *why, size_t why_n)
{
    memset(s, 0, sizeof *s);
    s->fd = -1;
    if (!app->stream_buf || !app->stream_cap) {
        snprintf(why, why_n, "--stream needs a bake with a stream buffer (modelc --emit stream): %s", src);
        return -1;
    }
    mc_stream_init(&s->reader, app->stream_buf, app->stream_cap);
    s->app = app;
    int fd;
    if (!strcmp(src, "-")) fd = STDIN_FILENO;
    else if (!strncmp(src, "tcp:", 4)) fd = connect_tcp(src + 4, why, why_n);
    else {
        /* blocking open: a FIFO waits here for its writer, so an empty read later means the end */
        fd = open(src, O_RDONLY);
        if (fd < 0) snprintf(why, why_n, "%s: %s", src, strerror(errno));
    }
    if (fd < 0) return -1;
    int fl = fcntl(fd, F_GETFL);
    if (fl >= 0) fcntl(fd, F_SETFL, fl | O_NONBLOCK);
    s->fd = fd;
    return 0;
}

static void finish(mc_host_stream *s, int error, int err_no)
{
    s->done = 1;
    s->error = error;
    s->errno_at_fail = err_no;
    if (s->fd > STDIN_FILENO) close(s->fd);
    s->fd = -1;
}

int mc_host_stream_pump(mc_host_stream *s, int block)
{
    static uint8_t piece[65536];
    const unsigned before = s->depth;
    while (!s->done) {
        ssize_t n = read(s->fd, piece, sizeof piece);
        if (n > 0) {
            int rc = mc_stream_feed(&s->reader, piece, (uint32_t)n);
            if (rc != MC_STREAM_OK) finish(s, rc, 0);
            block = 0;
        } else if (n == 0) {
            finish(s, mc_stream_end(&s->reader), 0);
        } else if (errno == EINTR) {
            continue;
        } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
            if (!block) break;
            struct pollfd p = {s->fd, POLLIN, 0};
            if (poll(&p, 1, -1) < 0 && errno != EINTR) finish(s, 1, errno);
        } else {
            finish(s, 1, errno);
        }
    }
    s->depth = mc_stream_depth(&s->reader);
    const uint32_t level_before = s->mesh_level;
    const int lines_before = s->mesh_lines;
    const mc_pmesh *pm = mc_stream_pmesh(&s->reader), *bake = s->app->model->pmesh;
    if (pm && s->error != 2) {
        /* the app binding's mesh memory is sized for the bake's mesh (app.h) */
        if (!bake || !s->app->pmesh_anc || !s->app->pmesh_facing || pm->vertices > bake->vertices ||
            pm->faces > bake->faces || pm->index_bytes > bake->index_bytes) {
            if (!s->done) finish(s, 2, 0);
            else s->error = 2;
        } else {
            s->mesh_level = mc_stream_mesh_level(&s->reader);
            s->mesh_lines = pm->opposite != 0;
        }
    }
    return s->depth > before || s->mesh_level > level_before || s->mesh_lines > lines_before;
}

void mc_host_stream_drain(mc_host_stream *s)
{
    while (!s->done) mc_host_stream_pump(s, 1);
}

const mc_octree *mc_host_stream_octree(const mc_host_stream *s) { return mc_stream_octree(&s->reader); }

const mc_pmesh *mc_host_stream_pmesh(const mc_host_stream *s)
{
    return s->mesh_level ? mc_stream_pmesh(&s->reader) : NULL;
}

int mc_host_stream_ok(const mc_host_stream *s) { return s->done && s->error == MC_STREAM_OK; }

void mc_host_stream_status(const mc_host_stream *s, char *line, size_t n)
{
    const mc_stream *r = &s->reader;
    char kept[128], mesh[64] = "";
    if (s->depth) snprintf(kept, sizeof kept, "drawing depth %u, the last complete level", s->depth);
    else snprintf(kept, sizeof kept, "nothing was drawable");
    if (s->mesh_level) {
        const size_t k = strlen(kept);
        snprintf(kept + k, sizeof kept - k, ", mesh level %lu", (unsigned long)s->mesh_level);
        snprintf(mesh, sizeof mesh, ", mesh %lu of %lu vertices%s", (unsigned long)s->mesh_level,
                 (unsigned long)r->pmesh.vertices, s->mesh_lines ? "" : " (no lines yet)");
    }
    if (s->error == 2)
        snprintf(line, n, "stream: its mesh (%lu vertices, %lu faces) is larger than this viewer's mesh buffers; %s",
                 (unsigned long)r->pmesh.vertices, (unsigned long)r->pmesh.faces, kept);
    else if (s->error == 1)
        snprintf(line, n, "stream: read failed after %lu bytes: %s; %s", (unsigned long)r->len,
                 strerror(s->errno_at_fail), kept);
    else if (s->error)
        snprintf(line, n, "stream: %s at byte %lu; %s", mc_stream_error_name(s->error), (unsigned long)r->error_at,
                 kept);
    else if (s->done)
        snprintf(line, n, "stream: complete, depth %u%s, %lu bytes", s->depth, mesh, (unsigned long)r->len);
    else
        snprintf(line, n, "stream: depth %u of %u%s after %lu of %lu bytes", s->depth, (unsigned)r->depth, mesh,
                 (unsigned long)r->len, (unsigned long)r->total);
}
