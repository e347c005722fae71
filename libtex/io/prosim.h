/* prosim.h - ProSim's texture files, as the thesis's texture module wrote them
 *
 *   tex_map *m = tex_prosim_read("leo.r");    // leo.r, leo.g, leo.b: an RGB map
 *   tex_prosim_write(m, "out.r", 0, "out.r"); // out.r, out.g, out.b
 *
 * A texture map is three files NAME.r, NAME.g and NAME.b (thesis 5.2 and 5.3.1), one byte
 * per pixel each, "in binary format", rows from the top, with no header; naming any of the
 * three names the triple.  A primitive's raw values, before a palette maps their range
 * (5.2.2), are NAME.pic: the thesis fixes no layout, so here one channel of 32-bit
 * little-endian IEEE floats, rows from the top, no header.
 *
 * The size is in neither: a square map's side is the square root of its pixel count, and
 * any other size is written in the name before the extension, NAME_WxH.r (leo_640x480.r).
 * The writer refuses a map whose size the name would not give back.  Bytes are v/255 read,
 * and written clamped to [0,1] and rounded to the nearest of 8 bits (NaN is 0), as the
 * other 8-bit formats.  Reads are bounded by the input limit (limit.h).  file.h dispatches
 * here by extension: .r, .g, .b and .pic.
 */
#ifndef TEX_PROSIM_H
#define TEX_PROSIM_H

#include <stddef.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

/* The w x h of a headerless file of npix pixels named path: from "_WxH" before the
 * extension, else the square; -1 with the error set if neither gives npix. */
int tex_prosim_size(const char *path, size_t npix, int *w, int *h);
/* One channel from a file image in memory: bytes (pic 0) or floats (pic 1). */
tex_map *tex_prosim_decode(const void *data, size_t len, int pic, const char *path);
/* A map from NAME.r/.g/.b (three channels) or NAME.pic (one). */
tex_map *tex_prosim_read(const char *path);
/* m (3 channels for .r/.g/.b, 1 for .pic) to its files, each replaced atomically
 * (file.h's tex_out); name is for messages. */
int tex_prosim_write(const tex_map *m, const char *path, int pic, const char *name);

TEX_API_END
#endif
