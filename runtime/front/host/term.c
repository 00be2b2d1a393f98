/* Placeholder replaced by the interactive terminal front end. */
#include <stdio.h>
#include "term.h"

int mc_host_interactive(const mc_app *app, mc_view start)
{
    (void)app;
    (void)start;
    fprintf(stderr, "interactive mode not built yet\n");
    return 2;
}
