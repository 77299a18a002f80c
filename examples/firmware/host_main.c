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
    fflush(stdout);
    return rc;
}
