/* fw.h - the firmware example's one entry point, shared by the host and the Cortex-M7
 * builds. The platform supplies only a way to write a NUL-terminated string. */
#ifndef FW_H
#define FW_H

typedef void (*fw_write_fn)(const char *text);

/* Renders the example scene once per configuration (every algorithm compiled in, k = 4
 * and 8, an area and a point light), writes one line per frame with the FNV-1a checksums
 * of its visibility and RGBA bytes, and returns 0, or 1 after writing what failed. */
int fw_run(fw_write_fn write);

#endif
