/* assemble.h - windows of a map put back together, a band of rows at a time
 *
 * A generator's --window and t_apply's --region write a window of a larger
 * map as an EXR whose data window sits inside the full map's display window
 * (map.h: x0, y0, full_w, full_h).  tex_assemble reads the headers of the
 * window files, checks that they tile the full map (same full size and
 * channels, no overlap, no gap), and writes the full map from the top,
 * loading each window when the rows reach it and freeing it once they have
 * passed it: memory holds one band of windows and one chunk of rows, never
 * the whole map.  EXR output only (a file, with compression, scanlines or
 * tiles, or the stream).
 *
 *   const char *parts[] = {"a.exr", "b.exr"};
 *   tex_assemble(parts, 2, fd, "out.exr", 0, TEX_COMPRESS_ZIP, "t_assemble a.exr b.exr");
 */
#ifndef TEX_ASSEMBLE_H
#define TEX_ASSEMBLE_H

#include "../base/api.h"
#include "stream.h"

TEX_API_BEGIN

/* Assemble the n window files into fd (a regular file or a pipe), in
 * tile x tile tiles when tile > 0 (a file only); name is for messages; history (may be NULL) is appended to the first window's.
 * 0, or -1 with the error set (a usage error when the windows do not fit). */
int tex_assemble(const char *const *paths, int n, int fd, const char *name, int tile,
                 enum tex_compression c, const char *history);

TEX_API_END
#endif
