/* pn_image.h - image and buffer output for the host tools (PNG, PFM, raw triangle ids).
 *
 * Every function returns 0 on success and non-zero with a message in err (if err != NULL,
 * truncated to err_size) on failure: NULL data, zero or oversized dimensions, or an I/O
 * error (the message carries strerror). Pixel arrays are row-major with the top row first.
 * Nothing is retained after a call returns. */
#ifndef PN_TOOLS_IMAGE_H
#define PN_TOOLS_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes w x h RGBA8 pixels (4 bytes each, w * 4 bytes per row) as a PNG. */
int pn_write_png(const char *path, const uint8_t *rgba, uint32_t w, uint32_t h, char *err,
                 size_t err_size);

/* Writes w x h floats as a grayscale PFM: header "Pf\n<w> <h>\n-1.0\n" (negative scale =
 * little endian), then the rows bottom to top as the format requires, each float as 4
 * little-endian bytes whatever the host's byte order. */
int pn_write_pfm(const char *path, const float *gray, uint32_t w, uint32_t h, char *err,
                 size_t err_size);

/* Reads a grayscale PFM ("Pf", either byte order) into a malloc'd array of w*h floats, top
 * row first (release with free()). Colour PFM ("PF") is refused. On failure *out is NULL and
 * *w, *h are 0. */
int pn_read_pfm(const char *path, float **out, uint32_t *w, uint32_t *h, char *err,
                size_t err_size);

/* Writes w x h uint32 values (e.g. triangle ids per pixel) as raw little-endian bytes, top row
 * first, no header: the file is exactly w * h * 4 bytes. */
int pn_write_ids(const char *path, const uint32_t *ids, uint32_t w, uint32_t h, char *err,
                 size_t err_size);

/* Visibility in [0, 1] (clamped) as opaque gray RGBA8, n pixels. */
void pn_vis_to_rgba(const float *vis, size_t n, uint8_t *rgba);

/* |vis - ref| as an opaque heat map, n pixels: black where equal, then dark red up to
 * yellow; the error is scaled x4, so 0.25 and above is full scale. */
void pn_err_to_rgba(const float *vis, const float *ref, size_t n, uint8_t *rgba);

/* Copies a w x h RGBA8 image into a sheet sheet_w pixels wide at (ox, oy); the caller
 * guarantees it fits. */
void pn_blit_rgba(uint8_t *sheet, uint32_t sheet_w, const uint8_t *img, uint32_t w, uint32_t h,
                  uint32_t ox, uint32_t oy);

/* mkdir -p: creates every missing directory of path (mode 0777 before umask).
 * Returns 0 if the directory exists afterwards. */
int pn_mkdir_p(const char *path);

#ifdef __cplusplus
}
#endif
#endif
