/* stream.h - the Textura stream: texture maps as OpenEXR
 *
 * Tools pass texture maps to each other as OpenEXR: float32, scanline,
 * uncompressed on a pipe (it is read once, at once), optionally zip or piz
 * compressed on disk.  Encoding and decoding go through OpenEXR's core C
 * library (openexr.h).  Metadata rides as attributes:
 *
 *   textura:subregions  int     number of subregions of a region-id map
 *   textura:history     string  the command lines that made the map
 *
 * Channels are named Y (1 channel), R G (2), R G B (3), R G B A (4).  On
 * reading, R G B A and Y A are recognised, half and uint channels become
 * float, and any other set of channels is taken in the order the file
 * lists them.  A file with channels left out (more than four, or others
 * beside R G B A) keeps the first four or R G B A, with a warning naming
 * those kept (error.h).  Scanline and tiled files are read, the first
 * part of a multi-part file, the full-resolution level of a tiled one
 * (tex_exr_decode_levels also its mip levels).  Files on disk may be
 * written tiled and mip-mapped (tex_exr_encode_tiled).
 */
#ifndef TEX_STREAM_H
#define TEX_STREAM_H

#include <stddef.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

enum tex_compression { TEX_COMPRESS_NONE, TEX_COMPRESS_ZIP, TEX_COMPRESS_PIZ };

/* A growable byte buffer: malloc'ed, or (mapped > 0) pages of tex_pages_new's, which
 * tex_read_fd takes for a large file.  Free it with tex_buf_free. */
typedef struct tex_buf {
    unsigned char *data;
    size_t len, cap;
    size_t mapped; /* tex_pages_free's size; 0: the heap's */
} tex_buf;

int tex_buf_reserve(tex_buf *b, size_t cap);
void tex_buf_free(tex_buf *b);

/* Encode m as an EXR file image in out (appended to whatever it holds). */
int tex_exr_encode(const tex_map *m, enum tex_compression c, tex_buf *out);

/* Encode m as a tiled EXR (tile x tile pixels), with mipmap its mip-map
 * levels too (OpenEXR MIPMAP_LEVELS, ROUND_DOWN: each level tex_map_reduce
 * of the one above, down to 1 x 1), as .tx-style texture files have them.
 * A map of subregion ids refuses mipmap (a usage error). */
int tex_exr_encode_tiled(const tex_map *m, int tile, int mipmap, enum tex_compression c,
                         tex_buf *out);

/* Write m as the uncompressed stream to fd as it is encoded, without holding
 * the whole file in memory (a pipe cannot seek back for the offset table,
 * so the table is computed in advance and checked against the core's). */
int tex_exr_write_fd(const tex_map *m, int fd, const char *name);

/* Write a map made a band of rows at a time, never held whole: head gives
 * its size, channels, metadata and place (head->px unused); fill(arg, y, n,
 * rows) writes rows y..y+n-1 (w * nc floats each, one after the other), in
 * order from the top, n at least 64 rows but the last, and returns 0 or -1 with the error set.  A regular
 * file gets compression c, chunks written at their offsets, in tile x tile
 * tiles when tile > 0 (n is then tile, fill's rows a band of tiles); a pipe
 * gets the uncompressed scanline stream (tiles to a pipe: a usage error). */
typedef int (*tex_rows_fn)(void *arg, int y, int n, float *rows);
int tex_exr_write_rows(const tex_map *head, tex_rows_fn fill, void *arg, int tile,
                       enum tex_compression c, int fd, const char *name);
/* The same, where the rows lie somewhere already: at(arg, y, n, &rows) points rows at rows
 * y..y+k-1 (w * nc floats each, one after another, there until the next call) and returns
 * k, 1..n, or -1 with the error set.  An uncompressed scanline part (the stream's) is
 * written from there, not copied into the writer's band by fill; others use fill. */
typedef int (*tex_rows_at_fn)(void *arg, int y, int n, const float **rows);
int tex_exr_write_rows_at(const tex_map *head, tex_rows_fn fill, tex_rows_at_fn at, void *arg,
                          int tile, enum tex_compression c, int fd, const char *name);

/* A scanline EXR read a band of rows at a time, holding one chunk: from the
 * file at path, or (path NULL) from the pipe fd of which prefix_len bytes
 * were read into prefix.  head gets the size, channels, metadata and place
 * (head->px NULL; free head->history).  NULL with the error set, also for a
 * tiled file at path (read those whole).  A tiled file on the pipe, which
 * cannot be read again, is decoded whole into *whole (NULL returned) when
 * whole is not NULL, and refused otherwise.  The input limit (limit.h)
 * holds as for the whole-map readers: a header declaring more is refused,
 * and a pipe's bytes are counted as they are read.  The reader returned
 * owns a pipe fd other than standard input (0): tex_rows_close closes it.  Rows must be asked for
 * from the top down: tex_rows_read copies rows y..y+n-1 (w * nc floats
 * each) into rows. */
typedef struct tex_rows_reader tex_rows_reader;
tex_rows_reader *tex_rows_open(int fd, const void *prefix, size_t prefix_len, const char *path,
                               const char *name, tex_map *head, tex_map **whole);
int tex_rows_read(tex_rows_reader *r, int y, int n, float *rows, const char *name);
void tex_rows_close(tex_rows_reader *r);

/* The header of the EXR file at path into head (px NULL): size and channels
 * kept, and its place, the data window within the display window (x0, y0,
 * full_w, full_h; full_w set even for a whole map).  0, or -1 with the error. */
int tex_exr_probe(const char *path, tex_map *head);

/* Decode an EXR read from fd, of which the first prefix_len bytes were
 * already read into prefix (to recognise the format).  Reads as it decodes,
 * keeping only a window of the stream. */
tex_map *tex_exr_read_fd(int fd, const void *prefix, size_t prefix_len, const char *name);

/* Widen a pipe's buffer to 1 MiB where the system allows (no-op otherwise). */
void tex_pipe_widen(int fd);

/* Write all n bytes, retrying after interruptions; -1 with a message naming name. */
int tex_write_all(int fd, const void *p, size_t n, const char *name);

/* Decode an EXR held in memory; name is for messages only. */
tex_map *tex_exr_decode(const void *data, size_t len, const char *name);

/* Decode an EXR in memory with its mip levels when it has them (a tiled
 * MIPMAP_LEVELS, ROUND_DOWN file): an array of *n maps, the full resolution
 * first (free each, then the array); NULL with the error set. */
tex_map **tex_exr_decode_levels(const void *data, size_t len, const char *name, int *n);

/* The name of the compression of an EXR file image if the core library
 * cannot decode it ("DWAA", "DWAB" with OpenEXR 3.1), else NULL; the
 * decoders refuse such files as "unsupported compression NAME" and file.h
 * hands whole files to OpenImageIO instead. */
const char *tex_exr_unsupported(const void *data, size_t len);

TEX_API_END
#endif
