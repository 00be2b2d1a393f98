/* The stream receiver firmware: the model arrives over UART0 as a streamed bake (modelc --emit
 * stream, modelc/stream.h) and is drawn level by level while the rest arrives, on a Cortex-M under
 * QEMU (-serial fed from a file, pipe or socket) or on a board.
 *
 * Promise: no model arrays are linked. The bake's NAME.h gives only sizes (make firmware-stream
 * passes MC_FW_STREAM_HEADER and the names of its defines): the receive buffer of
 * MC_NAME_STREAM_BYTES and the frame buffers of the bake's screen are this file's static arrays.
 * Every byte from the UART goes to mc_stream_feed, one at a time, so each level is seen as it
 * completes: then one line "level D drawable after N bytes" and the checksum lines of frames.h's
 * first F frames (all of them unless the command line says frames=F) at depth D, exactly as the host
 * viewer's --checksums --depth D prints them for the same bake. The input ends when the reader reads
 * the end record (complete), finds an error (it stops at once: the rest cannot help), or when no
 * byte has come for idle=MS milliseconds of SysTick time (default 2000; a UART has no end of file,
 * and the header's total is only known once it has come). Before the first byte the wait is
 * wait=MS (default 10000, 0: forever). Then the final line: "stream complete: depth D, N bytes", or
 * "stream error NAME at byte B after N bytes; keeping depth D" (D 0: nothing was drawable), and the
 * stack high-water mark, "done". Exits (semihosting) 0 when the stream was complete and every
 * render MC_OK, else 1. Whatever the bytes, the reader refuses them before the renderer sees them:
 * no fault on a truncated, corrupted, foreign or oversized stream.
 *
 * Built with MC_FW_STREAM_MESH (make firmware-stream FW_MESH=1: a bake --as both), the receiver also
 * keeps the level-of-detail memory of the bake's mesh part (MC_FW_STREAM_PMESH_*: its ancestor map,
 * line memory, vertex cache and sparse depth bits, static), and draws the mesh as it comes: each
 * time a mesh record raises the level that has come, one line "mesh level L of V drawable after N
 * bytes" and the mesh frames of mesh_frames.h within it (mc_front_mesh_check_to: levels up to L,
 * the line styles shaded, the adjacency coming last); when the adjacency has come, "mesh complete
 * after N bytes" and the mesh frames, the line styles too. Each checksum line as the host viewer's
 * --stream --checksums prints it on the same bytes, and the complete mesh's as its --checksums of
 * the bake: the arrays the reader fills are the bake's, byte for byte (stream.h). A stream whose
 * mesh is larger than those buffers (not this bake's) is refused: "stream error mesh-size at byte B"
 * (the byte where its mesh header ends), its points kept.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/modelc.h>
#include <modelc/stream.h>

#include MC_FW_STREAM_HEADER   /* the bake's NAME.h: its defines only */
#include "../common/frames.h"
#if MC_FW_STREAM_MESH
#include "../common/mesh_frames.h"
#endif
#include "cmdline.h"
#include "stack.h"
#include "uart.h"

#ifndef MC_FW_CLOCK_HZ
#error "MC_FW_CLOCK_HZ: the SysTick clock of the board (boards/B.mk)"
#endif

#define SCREEN_W MC_FW_STREAM_WIDTH
#define SCREEN_H MC_FW_STREAM_HEIGHT
#define TICK_MS 10u
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)   /* bit 16 COUNTFLAG: wrapped since last read */
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SCB_ICSR (*(volatile uint32_t *)0xE000ED04u)   /* bit 25 PENDSTCLR */

static uint8_t stream_buf[MC_FW_STREAM_BYTES];
static uint8_t color_buf[SCREEN_W * SCREEN_H];
static uint16_t depth_buf[SCREEN_W * SCREEN_H];
static mc_stream reader;

#if MC_FW_STREAM_MESH
/* the bake's mesh part's memory, as its app binding declares it (the words keep it aligned) */
static uint32_t pmesh_anc[(MC_FW_STREAM_PMESH_LOD_BYTES + 3u) / 4u];
static uint32_t pmesh_facing[(MC_FW_STREAM_PMESH_FACING_BYTES + 3u) / 4u];
static mc_xvertex pmesh_cache[MC_FW_STREAM_PMESH_VERTICES];
static uint32_t pmesh_sdepth[MC_SDEPTH_WORDS(SCREEN_W, SCREEN_H)];

/* The mesh frames within the levels that have come (up to level; the line styles when lines);
 * returns 1 if a frame failed. */
static int draw_mesh(const mc_pmesh *pm, uint32_t level, int lines, const mc_target *t)
{
    int status = 0;
    static mc_pmesh_lod lod;   /* (its level carries over: a level's state is the same bytes however reached) */
    if (lod.pm != pm) mc_pmesh_lod_init(&lod, pm, pmesh_anc);
    if (lines) printf("mesh complete after %lu bytes\n", (unsigned long)reader.len);
    else printf("mesh level %lu of %lu drawable after %lu bytes\n", (unsigned long)level, (unsigned long)pm->vertices,
                (unsigned long)reader.len);
    for (unsigned i = 0; i < MC_FRONT_VIEW_COUNT; i++) {
        mc_front_mesh_result r =
            mc_front_mesh_check_to(&lod, (uint8_t *)pmesh_facing, pmesh_cache, pmesh_sdepth, i, t, level, lines);
        printf(MC_FRONT_MESH_LINE, MC_FRONT_MESH_ARGS(i, pm, t, r));
        if (r.rc != MC_OK) status = 1;
    }
    return status;
}
#endif

static uint32_t idle_ms = 2000, wait_ms = 10000;
static unsigned frames = MC_FRONT_FRAME_COUNT;

static uint32_t number(const char *s, uint32_t fallback)
{
    char *end;
    const unsigned long v = strtoul(s, &end, 10);
    return *s && !*end && v <= 3600000ul ? (uint32_t)v : fallback;
}

static void read_cmdline(void)
{
    char *w[4];
    const unsigned n = mc_fw_cmdline(w, 4);
    for (unsigned i = 0; i < n; i++) {
        if (!strncmp(w[i], "idle=", 5)) idle_ms = number(w[i] + 5, idle_ms);
        else if (!strncmp(w[i], "wait=", 5)) wait_ms = number(w[i] + 5, wait_ms);
        else if (!strncmp(w[i], "frames=", 7)) frames = number(w[i] + 7, frames);
    }
    if (frames > MC_FRONT_FRAME_COUNT) frames = MC_FRONT_FRAME_COUNT;
}

/* The idle clock: SysTick wraps every TICK_MS. Interrupts stay masked (PRIMASK) and no handler
 * runs: the wrap's pending SysTick exception and the UART's pending receive interrupt only wake WFI
 * (uart.h), so the core sleeps while it waits instead of racing the emulator for the bytes. */
static void ticks_start(void)
{
    __asm__ volatile("cpsid i" ::: "memory");
    SYST_CSR = 0;
    SYST_RVR = MC_FW_CLOCK_HZ / (1000u / TICK_MS) - 1u;
    SYST_CVR = 0;
    SYST_CSR = 7u;   /* enable, exception pended at each wrap, processor clock */
}

/* 1 if a tick has passed since the last call. Several passed while the core was busy (or the
 * emulator stalled) count as one: a wait only ever comes out longer, never shorter. */
static int tick(void)
{
    if (!(SYST_CSR & (1u << 16))) return 0;
    SCB_ICSR = 1u << 25;
    return 1;
}

/* The frames at depth d of what has arrived; returns 1 if a render failed. */
static int draw_level(unsigned d, const mc_target *t)
{
    const mc_octree *octree = mc_stream_octree(&reader);
    int status = 0;
    printf("level %u drawable after %lu bytes\n", d, (unsigned long)reader.len);
    for (unsigned i = 0; i < frames; i++) {
        mc_front_result r = mc_front_frame(octree, i, d, t);
        printf(MC_FRONT_FRAME_LINE, MC_FRONT_FRAME_ARGS(i, d, t, r));
        if (r.rc != MC_OK) status = 1;
    }
    return status;
}

int main(void)
{
    mc_fw_stack_paint();
    read_cmdline();
    ticks_start();
    mc_fw_uart_init();
    mc_stream_init(&reader, stream_buf, sizeof stream_buf);
    const mc_target t = {color_buf, depth_buf, SCREEN_W, SCREEN_H};
    printf("modelc stream firmware: buffer %lu bytes (depth %u bake) size %ux%u frames %u a level, "
           "UART0 at 0x%08lx, idle %lu ms\n",
           (unsigned long)sizeof stream_buf, (unsigned)MC_FW_STREAM_DEPTH, (unsigned)t.width, (unsigned)t.height,
           frames, mc_fw_uart_base(), (unsigned long)idle_ms);

    int status = 0, timed_out = 0, mesh_refused = 0;
#if MC_FW_STREAM_MESH
    uint32_t mesh_level = 0;   /* the level drawn last */
    int mesh_lines = 0;        /* the complete mesh drawn */
#endif
    unsigned drawn = 0;
    uint32_t idle = 0;   /* ticks without a byte */
    for (;;) {
        const int c = mc_fw_uart_getc();
        if (c < 0) {
            idle += (uint32_t)tick();
            const uint32_t limit = reader.len ? idle_ms : wait_ms;
            if (limit && idle >= (limit + TICK_MS - 1u) / TICK_MS) {
                timed_out = 1;
                break;
            }
            mc_fw_uart_wait();
            continue;
        }
        const uint8_t b = (uint8_t)c;
        const int rc = mc_stream_feed(&reader, &b, 1);
        const unsigned d = mc_stream_depth(&reader);
        if (d > drawn) {
            if (draw_level(d, &t)) status = 1;
            drawn = d;
        }
#if MC_FW_STREAM_MESH
        const mc_pmesh *pm = mc_stream_pmesh(&reader);
        if (pm && !mesh_lines) {
            if (!mc_front_mesh_fits(pm, MC_FW_STREAM_PMESH_VERTICES, MC_FW_STREAM_PMESH_LOD_BYTES,
                                    MC_FW_STREAM_PMESH_FACING_BYTES)) {
                mesh_refused = 1;
                break;
            }
            const uint32_t level = mc_stream_mesh_level(&reader);
            const int lines = pm->opposite != 0 && level == pm->vertices;
            if (level > mesh_level || lines) {
                if (draw_mesh(pm, level, lines, &t)) status = 1;
                mesh_level = level, mesh_lines = lines;
            }
        }
#endif
        if (rc != MC_STREAM_OK || reader.ended) break;
        idle = 0;
        (void)tick();   /* a tick spent drawing is not idle */
    }

    const int rc = mc_stream_end(&reader);
    if (mesh_refused) {
        status = 1;
        printf("stream error mesh-size at byte %lu after %lu bytes; keeping depth %u%s\n", (unsigned long)reader.len,
               (unsigned long)reader.len, drawn, drawn ? "" : " (nothing drawable)");
    } else if (rc == MC_STREAM_OK) {
        printf("stream complete: depth %u, %lu bytes\n", drawn, (unsigned long)reader.len);
    } else {
        status = 1;
        printf("stream error %s at byte %lu after %lu bytes", mc_stream_error_name(rc), (unsigned long)reader.error_at,
               (unsigned long)reader.len);
        if (timed_out) printf(" (no byte for %lu ms)", (unsigned long)(reader.len ? idle_ms : wait_ms));
        printf("; keeping depth %u%s\n", drawn, drawn ? "" : " (nothing drawable)");
    }
    printf("stack used %lu of %lu bytes free for it\n", (unsigned long)mc_fw_stack_used(),
           (unsigned long)mc_fw_stack_room());
    printf("done\n");
    return status;
}
