/* json.h - JSON text: strings quoted and escaped
 *
 * Tools print JSON (t_info --json, t_proto's replies) with printf for numbers and
 * this for strings, so that one escaping serves them all:
 *
 *   struct tex_str b = {0};
 *   tex_json_string(&b, m->history);    // "t_noise -s 64\nt_palette marble"
 *
 * '"' and '\' are escaped with a backslash, a newline is \n, every other byte below
 * 0x20 is \u00XX, and every other byte, UTF-8's included, is copied as it is (RFC 8259,
 * section 7).  NULL is the empty string.
 */
#ifndef TEX_IO_JSON_H
#define TEX_IO_JSON_H

#include "strbuf.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Append s to b as a quoted JSON string; 0, or -1 when memory ran out (b unchanged). */
int tex_json_string(struct tex_str *b, const char *s);

#ifdef __cplusplus
}
#endif
#endif
