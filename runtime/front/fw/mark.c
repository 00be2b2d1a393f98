/* Frame stage markers: see mark.h. */
#include "mark.h"

__attribute__((noinline, used)) void mc_fw_mark(unsigned stage)
{
    __asm__ volatile("" : : "r"(stage) : "memory");
}
