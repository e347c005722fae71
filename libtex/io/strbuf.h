/* strbuf.h - a growable string, for text made piece by piece
 *
 * A reply, a JSON document or a command line is appended to a struct tex_str a piece
 * at a time; s holds n bytes and a NUL after them (bytes may include NULs: a PNG).
 * Start from {0}; free(b.s) when done.  Out of memory, an append adds nothing and
 * returns -1: the text stays as it was.
 *
 *   struct tex_str b = {0};
 *   tex_str_add(&b, "{\"width\": %d}", w);
 *   fwrite(b.s, 1, b.n, stdout);
 *   free(b.s);
 */
#ifndef TEX_IO_STRBUF_H
#define TEX_IO_STRBUF_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct tex_str {
    char *s;         /* NULL until the first append */
    size_t n, cap;   /* bytes held, bytes allocated */
};

/* Room for n more bytes and the NUL; 0, or -1 when memory ran out. */
int tex_str_room(struct tex_str *b, size_t n);
/* Append printf's text; 0, or -1. */
int tex_str_add(struct tex_str *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Append n bytes as they are, NULs included; 0, or -1. */
int tex_str_bytes(struct tex_str *b, const void *data, size_t n);

#ifdef __cplusplus
}
#endif
#endif
