/* file.h - reading and writing texture maps as files and pipes
 *
 *   tex_map *m = tex_map_read("-");            // standard input, any format
 *   struct tex_write_opts o = TEX_WRITE_DEFAULTS;
 *   tex_map_write(m, "out.png", &o);           // atomic; "-" or NULL: stdout
 *
 * Reading: the format is recognised by its magic bytes (EXR, PNG, TIFF,
 * PNM/PAM/PFM, BMP, TGA, HDR, JPEG, GIF, WebP, DPX).  EXR is decoded by the
 * stream module, PNM, PAM and PFM natively (netpbm.h), PNG, JPEG and TIFF
 * through small bridges to libpng, libjpeg-turbo and libtiff
 * (textura-png.so, textura-jpeg.so, textura-tiff.so), every other format
 * through OpenImageIO's bridge (textura-oiio.so), which also takes the
 * variants a codec bridge declines (CMYK JPEG).  Each bridge is loaded with
 * dlopen the first time it is needed, so a tool pays only for the codec of
 * the files it meets.  Values are read as stored: PNG's gAMA, sRGB and iCCP
 * chunks are ignored.  A file with more than four channels keeps the first
 * four, with a warning (error.h).
 *
 * Writing: a file's format follows a "FMT:" prefix, o.format, or its extension;
 * standard output and other streams carry the uncompressed EXR stream unless
 * one of the first two names another (tex_output_format).  Files are
 * written to a temporary name in the same folder and renamed on success,
 * so a failure or a signal leaves no partial file (tex_out below); a FIFO
 * or character device is written straight.  Image data is never written to a
 * terminal.  Integer formats are quantised with clamping to o.depth bits
 * (8 or 16; 0 picks the format's usual depth); depth 32 asks for float.
 * Values are written as they are: no transfer function is applied.
 *
 * The bridges are found in the textura/ folder of the install's LIBDIR,
 * resolved at run time (paths.h); $TEXTURA_OIIO_BRIDGE may name the
 * OpenImageIO one.
 */
#ifndef TEX_FILE_H
#define TEX_FILE_H

#include "../base/api.h"
#include "../base/map.h"
#include "stream.h"

TEX_API_BEGIN

enum tex_format {
    TEX_FMT_UNKNOWN, TEX_FMT_EXR, TEX_FMT_PNG, TEX_FMT_TIFF, TEX_FMT_PNM, TEX_FMT_PFM,
    TEX_FMT_BMP, TEX_FMT_TGA, TEX_FMT_HDR, TEX_FMT_JPEG, TEX_FMT_GIF, TEX_FMT_WEBP, TEX_FMT_DPX,
    TEX_FMT_PAM, TEX_FMT_PBM, TEX_FMT_PPM, TEX_FMT_PGM, TEX_FMT_PROSIM, TEX_FMT_PIC,
    TEX_FMT_COUNT
};

/* The format of a file image from its first bytes (at least 18 wanted). */
enum tex_format tex_format_sniff(const void *head, size_t n);
/* The format of a file name from its extension; TEX_FMT_UNKNOWN if none.  .pnm lets
 * the map choose PGM or PPM by its channels; .ppm is always P6, .pgm always P5, as
 * ImageMagick writes them. */
enum tex_format tex_format_from_name(const char *path);
/* Where an output name sends a map (textura(5), OUTPUT): "FMT:NAME" names the format
 * as ImageMagick's prefixes do ("png:-", "exr:out.dat"); else format (--format, an
 * extension word); else the name's extension; else, for standard output (NULL, "-",
 * /dev/stdout) and anything that is not a regular file (a FIFO, /dev/fd/N), the EXR
 * stream.  *file is the name without its prefix, NULL for standard output.
 * TEX_FMT_UNKNOWN with the error set: a usage error, or a runtime one for a folder. */
enum tex_format tex_output_format(const char *name, const char *format, const char **file);
const char *tex_format_name(enum tex_format f); /* "exr", "png", ... */
/* Every extension that names the format, space-separated: " tif tiff ". */
const char *tex_format_exts(enum tex_format f);

struct tex_write_opts {
    int depth;                        /* 0, 8, 16 or 32 */
    enum tex_compression compression; /* EXR files on disk */
    const char *format;               /* an extension word naming the format, or NULL */
    int tiled, mipmap;                /* EXR only: 64 x 64 tiles; with mip-map levels */
};
#define TEX_WRITE_DEFAULTS {0, TEX_COMPRESS_ZIP, NULL, 0, 0}
#define TEX_EXR_TILE 64 /* the tile side of --exr-tiles and --mipmap files (maketx's) */

/* What reading does with NaN and infinite samples, for the whole process
 * (textura(5), the tools' --nonfinite): refuse the map, naming the first
 * such pixel (the default), keep them, or replace each by a value. */
enum tex_nonfinite { TEX_NONFINITE_REFUSE, TEX_NONFINITE_KEEP, TEX_NONFINITE_REPLACE };
void tex_map_set_nonfinite(enum tex_nonfinite policy, float value);

/* Read a map from a path, or standard input for NULL or "-" (refused, a
 * usage error, when it is a terminal).  Non-finite samples follow the
 * policy above.  ProSim's headerless files (prosim.h: NAME.r/.g/.b, NAME.pic) are
 * read by their name. */
tex_map *tex_map_read(const char *path);
/* Read a map file with its mip levels, when it is an EXR file that has
 * them (written with --mipmap, or by maketx): an array of *n maps, the full
 * resolution first, each level half the one above (rounded down); any
 * other file or standard input gives one level.  Free each map, then the
 * array; NULL with the error set. */
tex_map **tex_map_read_levels(const char *path, int *n);
/* Open a map to be read a band of rows at a time (stream.h, tex_rows_read),
 * from path or standard input (NULL or "-"), when it is a scanline EXR, a
 * file or a pipe; otherwise, or with $TEXTURA_BAND_ROWS set to "whole"
 * (tex_rows_whole), the map is read whole into *whole and NULL is returned
 * (NULL with *whole NULL: an error); a tiled EXR on a pipe is decoded whole
 * from what the pipe has sent.  The input limit (limit.h) holds as for
 * tex_map_read, with its words.  Rows read are checked for non-finite
 * samples by the caller with tex_rows_nonfinite. */
tex_rows_reader *tex_map_open_rows(const char *path, tex_map *head, tex_map **whole);
/* $TEXTURA_BAND_ROWS is "whole": the tools read, work and write each map whole, as they
 * do a map in a format that has no rows to stream (the path bands are proved against) */
int tex_rows_whole(void);
/* The --nonfinite policy over n rows of w x nc samples starting at row y0:
 * 0, or -1 naming the first refused sample (the map's row, y0-based). */
int tex_rows_nonfinite(float *px, int w, int n, int nc, int y0, const char *name);
/* Read a map from a file image in memory; name is for messages. */
tex_map *tex_map_read_memory(const void *data, size_t len, const char *name);
/* Write a map; NULL or "-" is standard output. */
int tex_map_write(const tex_map *m, const char *path, const struct tex_write_opts *o);
/* A map written a band of rows at a time, never held whole: head gives its size,
 * channels, metadata and place (px unused), fill(arg, y, n, rows) its rows from the top
 * (stream.h's tex_rows_fn, n at least 64 rows but the last), to path as tex_map_write
 * writes it, with the same bytes.  tex_map_write_streams tells whether o's output takes
 * rows: the EXR stream and scanline files, EXR tiles to a file (not --mipmap), PNG, JPEG,
 * PNM, PAM and PBM anywhere, TIFF and PFM (which seek) to a file; others are written
 * whole, and tex_map_write_rows refuses them (a usage error). */
int tex_map_write_streams(const char *path, const struct tex_write_opts *o);
int tex_map_write_rows(const tex_map *head, tex_rows_fn fill, void *arg, const char *path,
                       const struct tex_write_opts *o);
/* The same, the EXR stream's rows taken where at says they lie (stream.h's
 * tex_rows_at_fn), not copied by fill */
int tex_map_write_rows_at(const tex_map *head, tex_rows_fn fill, tex_rows_at_fn at, void *arg,
                          const char *path, const struct tex_write_opts *o);
/* Whether tex_map_write could take path with format (tex_output_format: a format
 * known, not a directory; standard output not a terminal): 0, or -1 with its error.
 * Tools that write images check it before the work (a palette file is not an image: it
 * is not checked). */
int tex_map_write_check(const char *path, const char *format);

/* An output file.  tex_out_open writes a regular file (new or not) through
 * a temporary ".NAME.XXXXXX" beside it that tex_out_close renames onto it
 * on success (r == 0) and removes otherwise; a symbolic link is followed
 * and its target replaced so, the link kept.  A FIFO or character device
 * is written straight (direct), and so is /dev/fd/N (the descriptor N).  While the temporary file exists,
 * SIGINT, SIGTERM, SIGHUP and SIGPIPE remove it before ending the process
 * as they would have (signals the process ignores stay ignored).
 *
 *   struct tex_out out;
 *   if (tex_out_open(&out, path) < 0) return tex_out_close(&out, -1);
 *   r = write_all_of_it(out.fd);
 *   return tex_out_close(&out, r);          // r, or -1 if closing failed
 */
struct tex_out {
    int fd, direct, slot;
    unsigned mode;         /* of the file written */
    const char *name;      /* as given, for messages */
    char path[4096];       /* the file replaced (a link's target) */
    char tmp[4096 + 16];
};
int tex_out_open(struct tex_out *o, const char *path);
int tex_out_close(struct tex_out *o, int r);

/* Read all of a file descriptor into b (for standard input and pipes). */
int tex_read_fd(int fd, tex_buf *b, const char *name);
/* The one whole-file reader of text (scenes, scripts, palettes, materials):
 * path, or standard input for "-", at most max bytes.  Returns a buffer
 * that ends in a NUL byte not counted in *len (free() it), or NULL with the
 * error set: "PATH: reason", "standard input" for "-", and "PATH: larger
 * than MAX bytes" naming `what` ("a scene") past the limit. */
char *tex_read_text(const char *path, size_t max, size_t *len, const char *what);

TEX_API_END
#endif
