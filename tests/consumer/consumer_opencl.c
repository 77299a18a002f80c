/* consumer_opencl.c - links penumbra::opencl from an installed tree (needs no device). */
#include <stdio.h>
#include <penumbra/opencl.h>

int main(void)
{
    pn_opencl_options opt;
    pn_opencl_options_default(&opt);
    printf("consumer_opencl: penumbra::opencl links\n");
    return 0;
}
