/* Measured stack use: see stack.h. */
#include "stack.h"

#define PATTERN 0xC5A5C5A5u

extern uint32_t __end[];     /* picolibc.ld: end of .bss, start of the free area */
extern uint32_t __stack[];   /* picolibc.ld: top of the stack (end of RAM) */

static uint32_t *current_sp(void)
{
    uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    return sp;
}

__attribute__((noinline)) void mc_fw_stack_paint(void)
{
    uint32_t *limit = current_sp() - 16;   /* stay clear of this function's own frame */
    for (volatile uint32_t *p = __end; p < limit; p++) *p = PATTERN;
}

uint32_t mc_fw_stack_used(void)
{
    const uint32_t *p = __end;
    while (p < __stack && *p == PATTERN) p++;
    return (uint32_t)((const char *)__stack - (const char *)p);
}

uint32_t mc_fw_stack_room(void) { return (uint32_t)((const char *)__stack - (const char *)__end); }
