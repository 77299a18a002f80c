/* vla_probe.c - proves -Wvla is effective with the library's flags (ctest no_vla_compiles):
 * built with PN_PROBE_VLA=1 it declares a variable length array and must be rejected;
 * with PN_PROBE_VLA=0 (no_vla_control) the same file must compile cleanly, so the
 * rejection is the VLA's doing and not some other flag's. */
#include <stddef.h>

size_t pn_probe(size_t n);

size_t pn_probe(size_t n)
{
#if PN_PROBE_VLA
    char buf[n + 1u];
#else
    char buf[16];
#endif
    buf[0] = (char)n;
    return sizeof(buf) + (size_t)buf[0];
}
