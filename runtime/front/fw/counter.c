/* Instruction counting through SysTick: see counter.h. */
#include "counter.h"

#include <stdio.h>

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define MASK 0xFFFFFFu
#define CALIBRATION_LOOPS 1000000u   /* two instructions each: 2 million instructions */

static uint32_t insn_per_tick_q16;

uint32_t mc_fw_counter_now(void) { return (MASK - SYST_CVR) & MASK; }   /* SysTick counts down */

/* Exactly 2 * n instructions (subs, bne per iteration), plus the entry and return. */
__attribute__((noinline, naked)) static void spin(uint32_t n __attribute__((unused)))
{
    __asm__ volatile("1: subs r0, r0, #1\n\tbne 1b\n\tbx lr\n");
}

void mc_fw_counter_start(void)
{
    SYST_CSR = 0;
    SYST_RVR = MASK;
    SYST_CVR = 0;
    SYST_CSR = 5u;   /* enable, processor clock, no interrupt */
    uint32_t t0 = mc_fw_counter_now();
    spin(CALIBRATION_LOOPS);
    uint32_t ticks = (mc_fw_counter_now() - t0) & MASK;
    insn_per_tick_q16 = ticks ? (uint32_t)(((uint64_t)2u * CALIBRATION_LOOPS << 16) / ticks) : 0;
}

uint32_t mc_fw_counter_insn_per_tick(void) { return insn_per_tick_q16; }

uint32_t mc_fw_counter_insns(uint32_t start, uint32_t end)
{
    uint64_t ticks = (end - start) & MASK;
    return (uint32_t)((ticks * insn_per_tick_q16 + 32768u) >> 16);
}

void mc_fw_counter_start_report(void)
{
    mc_fw_counter_start();
    const uint32_t q = mc_fw_counter_insn_per_tick();
    printf("bench: %lu.%04lu instructions per SysTick tick (calibrated)\n", (unsigned long)(q >> 16),
           (unsigned long)(((q & 0xFFFFu) * 10000u) >> 16));
}
