/* host_main.c - the firmware example as a host program: the same fw_run, printing to
 * stdout. The only file of the example that includes <stdio.h>. */
#include <stdio.h>

#include "fw.h"

static void write_stdout(const char *text)
{
    fputs(text, stdout);
}

int main(void)
{
    int rc = fw_run(write_stdout);
    /* The Cortex-M7 build paints its stack and prints how deep it went (m7/startup.c); a
     * hosted stack is not ours to paint. */
    fputs("stack high water n/a (host)\n", stdout);
    fflush(stdout);
    return rc;
}
