/* Between the stream reader's two files (not part of the runtime's interface): stream.c frames the
 * records and reads the octree's, and hands a version-2 stream's mesh records to stream_mesh.c. */
#ifndef MODELC_STREAM_MESH_H
#define MODELC_STREAM_MESH_H

#include "modelc/stream.h"

#define MC_STREAM_KIND_PALETTE 1
#define MC_STREAM_KIND_LEVEL 2
#define MC_STREAM_KIND_END 3
#define MC_STREAM_KIND_MESH 4
#define MC_STREAM_KIND_BASE 5
#define MC_STREAM_KIND_SPLITS 6
#define MC_STREAM_KIND_ADJACENCY 7

/* Records the first error (and where it was found); returns the stream's error. Inline here, so
 * that stream_mesh.c needs nothing of stream.c: the calls go one way, stream.c to stream_mesh.c. */
static inline int mc_stream_fail(mc_stream *s, int error, uint32_t at)
{
    if (s->error == MC_STREAM_OK) {
        s->error = error;
        s->error_at = at;
    }
    return s->error;
}

/* A checked record of a mesh kind (payload of n bytes at offset at in buf; the record at at_record):
 * MC_STREAM_OK, or the error, recorded. */
int mc_stream_mesh_record(mc_stream *s, unsigned kind, uint32_t at, uint32_t n, uint32_t at_record);

#endif
