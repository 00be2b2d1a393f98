/* Frame stage markers for counting instructions under QEMU.
 *
 * Promise: mc_fw_mark is a real, never inlined function (symbol mc_fw_mark) that the firmware calls
 * between the stages of every frame (../common/frames.h: clear, render, finish, done). It records the SysTick
 * count (counter.h) of each stage boundary in mc_fw_marks[stage], so that under QEMU -icount the
 * instructions of a stage are mc_fw_counter_insns(mc_fw_marks[s], mc_fw_marks[s + 1]); and its entry
 * address appears once per call in QEMU's one-instruction-per-block execution trace
 * (-singlestep -d exec,nochain), so the trace's line numbers between entries count the same
 * instructions exactly (tests/fw/bench.sh cross-checks the two). About ten instructions per mark.
 */
#ifndef MODELC_FW_MARK_H
#define MODELC_FW_MARK_H

#include <stdint.h>

extern uint32_t mc_fw_marks[4];
void mc_fw_mark(unsigned stage);

#define MC_FRONT_MARK(stage) mc_fw_mark(stage)

#endif
