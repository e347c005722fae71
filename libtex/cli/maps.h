/* maps.h - a tool's maps in and out
 *
 * A tool reads its maps with tex_cli_read and writes its result with tex_cli_write:
 * to -o FILE in the format of its extension, or to standard output (the EXR stream,
 * or --format's), the command line appended to the map's history.  Each dies with
 * libtex's message on failure.  A map need not be held whole: where the output takes
 * rows (tex_cli_takes_rows), tex_cli_write_rows writes it as a callback makes its
 * rows, and tex_cli_stream runs a per-pixel operation over an input a band of rows at
 * a time.
 *
 *   tex_map *m = tex_cli_read(argv[i]);        // NULL or "-": standard input
 *   ...
 *   tex_cli_write(m, &c);
 */
#ifndef TEX_CLI_MAPS_H
#define TEX_CLI_MAPS_H

#include "../base/api.h"
#include "../base/map.h"
#include "../io/stream.h"
#include "options.h"

TEX_API_BEGIN

/* Read a map or die. */
tex_map *tex_cli_read(const char *path);
/* The bit depth that --depth chose: 0 (auto), 8, 16 or 32. */
int tex_cli_depth(const struct tex_common *c);
/* Append the command line to the history and write the map to -o or
 * standard output, or die. */
void tex_cli_write(tex_map *m, const struct tex_common *c);

/* A map made a band of rows at a time, never held whole: where -o (or the
 * format) takes rows (tex_cli_takes_rows: io/file.h's tex_map_write_streams,
 * the EXR stream and files, PNG, JPEG, PNM, PAM, PBM, and TIFF and PFM files),
 * head (size, channels, place; its history gains the command line) is
 * written to -o or standard output as fill makes its rows, as
 * tex_map_write_rows calls it, with tex_cli_write's bytes; dies on errors.
 * tex_cli_streams: whether -o asks for a scanline EXR, where tools that do
 * more for other formats (t_apply's sRGB) stream. */
int tex_cli_streams(const struct tex_common *c);
/* Rows of output per band for a map w x nc wide: $TEXTURA_BAND_ROWS (the tests' way to try
 * every band height), or about 2 MiB of input in whole multiples of 64 rows (16 to 64 rows
 * of 8 MiB at most where a row is wider than 32 KiB) */
int tex_cli_band_rows(int w, int nc);
int tex_cli_takes_rows(const struct tex_common *c);
void tex_cli_write_rows(tex_map *head, const struct tex_common *c,
                        int (*fill)(void *arg, int y, int n, float *rows), void *arg);

/* A per-pixel tool's work in bounded memory: the map at path (NULL or "-":
 * standard input) goes through op a band of rows at a time, each band a
 * small map of the input's width (op changes it in place and returns it, or
 * returns a new map and frees the band; NULL with the error set on
 * failure), and out to -o or standard output, with the history.  Output
 * channels and subregions are op's on a 1 x 1 band of ones.  When the input
 * is not a scanline EXR (another format, tiles) or the output takes no rows
 * (tex_cli_takes_rows: --mipmap, BMP...), the map goes through op whole
 * instead: the same pixels either way, op being per-pixel.  Dies on errors. */
void tex_cli_stream(const char *path, const struct tex_common *c,
                    tex_map *(*op)(tex_map *band, void *arg), void *arg);
/* The same over the rows of a spool (io/spool.h) of the input whose header is head (as
 * tex_map_open_rows gave it; its history is taken and freed), when the rows must all have
 * passed before the first is worked on (t_palette's automatic range).  Dies on errors. */
struct tex_spool;
void tex_cli_stream_spool(const struct tex_spool *sp, tex_map *head, const struct tex_common *c,
                          tex_map *(*op)(tex_map *band, void *arg), void *arg);

/* A neighbourhood operation's work in bounded memory: output rows y..y+n-1 need input rows
 * y-margin..y+n-1+margin, those beyond the top and bottom given by the edge rule.  op gets
 * each band as a map of the input's width and n + 2 margin rows (the rows beyond the edges
 * filled in, clamped or mirrored), with b saying where it sits, and returns a map of n or of
 * n + 2 margin rows (the middle n are the band's output) that the caller frees, or NULL with
 * the error set; it must not free the band.  The whole map goes through op instead (b: y 0,
 * margin 0, n its height) when the input is not a scanline EXR or the output takes no
 * rows (tex_cli_takes_rows), when edge is
 * TEX_EDGE_WRAP (the first rows would need the last), and when the map has fewer than
 * 2 margin + 1 rows: the same pixels either way, when op's rows of output depend on
 * nothing but those rows of input.  Bands are about 2 MiB of input, and a multiple of
 * 64 rows; $TEXTURA_BAND_ROWS (1..65536) sets their height instead, to show that the
 * output does not depend on it.  Dies on errors. */
/* The map a row reader opened for (io/file.h tex_map_open_rows), none of its rows read
 * yet, read whole after all, with head's metadata (its history taken); the reader is
 * closed.  Dies on errors. */
tex_map *tex_cli_rows_whole(tex_rows_reader *r, tex_map *head, const char *name);

struct tex_band {
    int y, n, margin; /* the output rows and the rows of context above and below */
    int full_h;       /* the whole map's height */
};
typedef tex_map *tex_band_fn(tex_map *band, const struct tex_band *b, void *arg);
void tex_cli_stream_window(const char *path, const struct tex_common *c, int margin,
                           enum tex_edge edge, tex_band_fn *op, void *arg);

TEX_API_END
#endif
