/* lockstep.h - per-pixel work over several maps read a band of rows at a time, in step
 *
 *   tex_lockstep *l = tex_cli_lockstep_new(2);
 *   tex_cli_lockstep_add(l, 0, "a.exr");         // opened for rows, or read whole
 *   tex_cli_lockstep_add(l, 1, "-");
 *   if (tex_cli_lockstep_streams(l, &c))         // all in rows, one size, -o takes rows
 *       tex_cli_lockstep_write(l, &c, 0, op, arg); // op on each band of both
 *   else
 *       a = tex_cli_lockstep_whole(l, 0), ...    // the whole-map path, as before
 *   tex_cli_lockstep_free(l);
 *
 * Inputs on pipes or in scanline EXR files are opened for rows (io/file.h
 * tex_map_open_rows); others are read whole.  When every input has rows, all of one
 * size, and the output takes rows (maps.h tex_cli_takes_rows), the output is written as
 * the writer asks for bands: op gets a band of each input (NULL for an input not added),
 * of the input's width and channels and the band's rows, with its subregions, and
 * returns a new map of those rows, or NULL with the error set.  The output's channels
 * and subregions are op's on bands of one row, its history input hist's.  op being per pixel,
 * the bytes are those of op on the whole maps.  Each function dies on errors.
 */
#ifndef TEX_CLI_LOCKSTEP_H
#define TEX_CLI_LOCKSTEP_H

#include "../base/api.h"
#include "../base/map.h"
#include "options.h"

TEX_API_BEGIN

typedef struct tex_lockstep tex_lockstep;
typedef tex_map *tex_lockstep_fn(tex_map *const *bands, void *arg);

tex_lockstep *tex_cli_lockstep_new(int n);
/* Input k from path ("-": standard input): its header (size, channels, subregions). */
const tex_map *tex_cli_lockstep_add(tex_lockstep *l, int k, const char *path);
int tex_cli_lockstep_streams(const tex_lockstep *l, const struct tex_common *c);
void tex_cli_lockstep_write(tex_lockstep *l, const struct tex_common *c, int hist,
                            tex_lockstep_fn *op, void *arg);
/* Input k whole, read now if it was opened for rows: the caller's to free */
tex_map *tex_cli_lockstep_whole(tex_lockstep *l, int k);
void tex_cli_lockstep_free(tex_lockstep *l);

TEX_API_END
#endif
