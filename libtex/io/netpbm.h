/* netpbm.h - PNM (PBM, PGM, PPM), PAM and PFM read and written natively
 *
 *   tex_map *m = tex_netpbm_decode(data, len, "in.pgm");   // NULL + tex_errmsg()
 *   tex_pnm_write_fd(m, fd, 16, TEX_PNM_AUTO, "out.ppm");  // P5/P6, maxval 65535
 *   tex_pfm_write_fd(m, fd, "out.pfm");
 *
 * netpbm's formats are simple enough to need no library, so the files users
 * meet most never pay OpenImageIO's start-up.  file.h dispatches to this
 * module by magic bytes ("P1".."P7", "PF", "Pf") or by extension.
 *
 * Reading: P1..P6 (plain and raw), P7 (PAM) and PFM, the first image of a
 * file.  Samples v of maxval M (1..65535) become v/M, exactly the nearest
 * float; a sample above M is an error.  PBM's 1 (black) is 0.0, its 0 is
 * 1.0.  PAM depth is 1..4: GRAYSCALE, GRAYSCALE_ALPHA, RGB, RGB_ALPHA and
 * BLACKANDWHITE(_ALPHA) are read as stored (no premultiplication); another
 * TUPLTYPE is read by its depth.  PFM rows run bottom to top, the sign of
 * the scale gives the byte order (negative: little-endian).
 *
 * Writing: tex_pnm_write_fd writes P5 (1 channel) or P6 (3 channels), P7
 * for TEX_PNM_PAM (1, 3 or 4 channels; TUPLTYPE from the count), or P4
 * for TEX_PNM_PBM (a sample < 0.5 is black; the first channel, or the mean
 * of R, G, B).  depth is 8 (maxval 255) or 16 (maxval 65535); samples are
 * clamped to [0,1] and rounded to the nearest level, NaN is 0.  Callers
 * hand a channel count the variant holds (file.c adapts the map first).
 */
#ifndef TEX_NETPBM_H
#define TEX_NETPBM_H

#include <stddef.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

enum tex_pnm_variant { TEX_PNM_AUTO, TEX_PNM_PAM, TEX_PNM_PBM };

tex_map *tex_netpbm_decode(const void *data, size_t len, const char *name);
int tex_pnm_write_fd(const tex_map *m, int fd, int depth, enum tex_pnm_variant v,
                     const char *name);
int tex_pfm_write_fd(const tex_map *m, int fd, const char *name);

/* The same files a band of rows at a time: the header of a w x h map of nc channels, then
 * its rows from the top, each band a map of the width and some rows.  PFM's rows run
 * bottom to top: tex_pfm_write_head returns the header's length, and each band (rows y..
 * of an h-row map) lands at its place in a regular file (pwrite), after it. */
int tex_pnm_write_head(int w, int h, int nc, int fd, int depth, enum tex_pnm_variant v,
                       const char *name);
int tex_pnm_write_band(const tex_map *band, int fd, int depth, enum tex_pnm_variant v,
                       const char *name);
int tex_pfm_write_head(int w, int h, int nc, int fd, const char *name);
int tex_pfm_write_band(const tex_map *band, int y, int h, int head, int fd, const char *name);

TEX_API_END
#endif
