/* The firmware's command line: see cmdline.h. */
#include "cmdline.h"

#include <semihost.h>

unsigned mc_fw_cmdline(char *words[], unsigned max)
{
    static char cmd[160];
    if (sys_semihost_get_cmdline(cmd, (int)sizeof cmd) != 0) return 0;
    cmd[sizeof cmd - 1] = 0;
    char *p = cmd;
    unsigned n = 0;
    for (int word = 0; *p; word++) {
        while (*p == ' ') p++;
        if (!*p) break;
        char *start = p;
        while (*p && *p != ' ') p++;
        if (*p) *p++ = 0;
        if (word > 0 && n < max) words[n++] = start;   /* word 0: the program's name */
    }
    return n;
}
