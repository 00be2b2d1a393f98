/* Instruction counting through SysTick, for make bench-firmware under QEMU -icount.
 *
 * Promise: mc_fw_counter_start runs the Cortex-M SysTick timer free (24 bits, processor clock, no
 * interrupt) and measures how many instructions one tick is, with a calibration loop of known
 * length; mc_fw_counter_now reads it as an increasing tick count (valid across one wrap, about 16.7
 * million ticks). Under `qemu-system-arm -icount shift=0` QEMU advances its virtual clock by exactly
 * one nanosecond per executed instruction, so ticks times mc_fw_counter_insn_per_tick() (Q16) are
 * instructions, exact to one tick. Without -icount the timer follows the host's clock and the
 * numbers mean nothing: the firmware prints them only when asked (main.c, "bench").
 */
#ifndef MODELC_FW_COUNTER_H
#define MODELC_FW_COUNTER_H

#include <stdint.h>

void mc_fw_counter_start(void);
uint32_t mc_fw_counter_now(void);
/* Instructions per tick, Q16, from the calibration. */
uint32_t mc_fw_counter_insn_per_tick(void);
/* Instructions in a span of ticks (end - start, modulo 2^24), rounded. */
uint32_t mc_fw_counter_insns(uint32_t start, uint32_t end);
/* mc_fw_counter_start, then the line "bench: N.NNNN instructions per SysTick tick (calibrated)" on
 * standard output, which both firmware mains print first when asked to bench. */
void mc_fw_counter_start_report(void);

#endif
