/* The firmware's command line, from the semihosting host (qemu-system-arm -semihosting-config
 * ...,arg=A,arg=B): both firmware mains read their options from it.
 *
 * Promise: mc_fw_cmdline splits the command line at spaces into at most max words, after the
 * program name, and returns how many; the words point into a static buffer of 160 bytes (a longer
 * line is cut), valid until the next call. No command line (no debugger, no semihosting): 0. */
#ifndef MODELC_FW_CMDLINE_H
#define MODELC_FW_CMDLINE_H

unsigned mc_fw_cmdline(char *words[], unsigned max);

#endif
