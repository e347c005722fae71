/* spool.h - a stream's rows in an unlinked temporary file, read back in any order
 *
 * Some work needs a stream's rows out of the order they pass in: t_xform's vertical
 * --wrap wants the last rows first, t_warp looks rows up around a displacement known only
 * once the displacement map has passed, t_palette's automatic range needs every row before
 * it colours the first.  Such rows go to a file in $TMPDIR (/tmp when unset or empty),
 * unlinked as soon as it is made, so nothing is left behind however the tool ends; they
 * cost the map's size on that file system (on a tmpfs, its memory), none of the
 * process's.
 *
 *   struct tex_spool s;
 *   if (tex_spool_rows(&s, "t_warp", reader, &head, "by.exr", head.h, take, &range) < 0) ...
 *   tex_spool_read(&s, -3, 10, rows);   // rows h-3..h-1, then 0..6: wrapped
 *   tex_spool_close(&s);
 *
 * tex_spool_rows: the reader r's first `rows` rows (prefix names the file, ".prefix.XXXXXX")
 * (stream.h; head its header, as tex_map_open_rows gave it; head->h for all, and the
 * spool's h is the rows it holds), about 1 MiB at a time,
 * through the --nonfinite policy (file.h tex_rows_nonfinite) and shown to take (when not
 * NULL: rows y..y+n-1, w x nc floats each) on their way, into a new spool of raw floats.
 * tex_spool_read: rows y..y+n-1 back, counted modulo the map's height (at most two reads
 * where they wrap).  Each returns 0 (the file's descriptor), or -1 with the error set,
 * naming the input.
 */
#ifndef TEX_SPOOL_H
#define TEX_SPOOL_H

#include "../base/api.h"
#include "../base/map.h"
#include "stream.h"

TEX_API_BEGIN

struct tex_spool {
    int fd;          /* -1: none */
    int w, h, nc;    /* the rows' map */
    const char *name; /* the input, for messages */
};

int tex_spool_rows(struct tex_spool *s, const char *prefix, tex_rows_reader *r,
                   const tex_map *head, const char *name, int rows,
                   void (*take)(void *arg, const float *rows, int y, int n), void *arg);
int tex_spool_read(const struct tex_spool *s, long y, int n, float *rows);
void tex_spool_close(struct tex_spool *s);

TEX_API_END
#endif
