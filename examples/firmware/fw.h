/* fw.h - the firmware example's one entry point, shared by the host and the Cortex-M7
 * builds. The platform supplies only a way to write a NUL-terminated string. */
#ifndef FW_H
#define FW_H

#include <stdint.h>

typedef void (*fw_write_fn)(const char *text);

/* Renders the small scene once per configuration (every algorithm compiled in, k = 4
 * and 8, an area and a point light, 32 x 32) and, in a build with FW_SPOT (CMake
 * PN_FW_SCENE_C), spot at 160 x 120 with the reference and Monte Carlo shadow maps;
 * writes one "frame ..." line per frame with the FNV-1a checksums of its visibility, RGBA
 * and G-buffer bytes, and lines with each context's arena size and high-water mark; returns
 * 0, or 1 after writing what failed. The platform prints the stack's high-water mark. */
int fw_run(fw_write_fn write);

/* After fw_run: a line of text and numbers, written through fw_run's `write`. */
void fw_line_str(const char *s);
void fw_line_u32(uint32_t x);
void fw_line_end(void);

#endif
