/* Frame stage markers for counting instructions under QEMU.
 *
 * Promise: mc_fw_mark is a real, never inlined function (symbol mc_fw_mark) that the firmware calls
 * between the stages of every frame (frames.h: clear, render, finish, done). It does nothing; its
 * entry address appears once per call in QEMU's one-instruction-per-block execution trace, so the
 * trace's line numbers between two entries are the instructions a stage executed
 * (tests/fw/bench.sh, make bench-firmware). Costs a call and a return per mark.
 */
#ifndef MODELC_FW_MARK_H
#define MODELC_FW_MARK_H

void mc_fw_mark(unsigned stage);

#define MC_FW_MARK(stage) mc_fw_mark(stage)

#endif
