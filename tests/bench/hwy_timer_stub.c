/* Preloaded into ViSP's tracker under callgrind only (tests/bench/track_seq.sh), never into a timed run.
 *
 * ViSP's libraries pull in libhwy (Highway: libvisp_io -> libopencv_videoio -> libavcodec -> libjxl),
 * whose start-up code calls hwy::platform::TimerResolution(), which executes RDTSCP. Valgrind 3.19
 * does not decode RDTSCP on this CPU and stops the program before main, so ViSP's instructions could
 * not be counted. The call goes through libhwy's PLT, so a definition preloaded ahead of libhwy answers
 * it. Nothing of ViSP's tracking calls the timer; the count is taken in vpMbGenericTracker::track alone.
 */
#include <stdint.h>

/* hwy::platform::TimerResolution() (libhwy 1.0: uint64_t, ticks), mangled */
uint64_t _ZN3hwy8platform15TimerResolutionEv(void);
uint64_t _ZN3hwy8platform15TimerResolutionEv(void) { return 1; }
