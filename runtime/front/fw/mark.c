/* Frame stage markers: see mark.h. */
#include "mark.h"
#include "counter.h"

uint32_t mc_fw_marks[4];

__attribute__((noinline, used)) void mc_fw_mark(unsigned stage)
{
    mc_fw_marks[stage & 3u] = mc_fw_counter_now();
}
