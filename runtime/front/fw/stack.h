/* Measured stack use: the high-water mark, to set beside the static bound from -fstack-usage.
 *
 * Promise: mc_fw_stack_paint fills the free RAM between the end of .bss (picolibc's linker script
 * symbol __end) and a little below the current stack pointer with a pattern; mc_fw_stack_used
 * returns how many bytes below the stack's top (__stack) have been written since, i.e. the deepest
 * the stack has reached (exact to 4 bytes, assuming nothing wrote the pattern value itself at the
 * deepest word). Call paint first thing in main. No heap: the painted area is the one the linker
 * leaves between the static data and the stack.
 */
#ifndef MODELC_FW_STACK_H
#define MODELC_FW_STACK_H

#include <stdint.h>

void mc_fw_stack_paint(void);
uint32_t mc_fw_stack_used(void);
/* Bytes between the end of .bss and the top of the stack: what the stack may grow into. */
uint32_t mc_fw_stack_room(void);

#endif
