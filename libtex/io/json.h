/* json.h - JSON text: strings quoted and escaped, parameter rows written, documents read
 *
 * Tools print JSON (t_info --json, t_proto's replies, --help-json) with printf for
 * numbers and this for strings, so that one escaping serves them all:
 *
 *   struct tex_str b = {0};
 *   tex_json_string(&b, m->history);    // "t_noise -s 64\nt_palette marble"
 *   tex_json_rows(&b, prim->params);    // [{"name":"frequency","type":"real",...}]
 *
 * and read a document (t_proto's graphs and projects) into a tree:
 *
 *   char err[128];
 *   struct tex_json *g = tex_json_parse(text, strlen(text), err, sizeof err);
 *   const struct tex_json *nodes = tex_json_get(g, "nodes");   // NULL if absent
 *   for (int i = 0; nodes && i < nodes->n; i++) ... nodes->item[i].str ...
 *   tex_json_free(g);
 *
 * '"' and '\' are escaped with a backslash, a newline is \n, every other byte below
 * 0x20 is \u00XX, and every other byte, UTF-8's included, is copied as it is (RFC 8259,
 * section 7).  NULL is the empty string.
 */
#ifndef TEX_IO_JSON_H
#define TEX_IO_JSON_H

#include "strbuf.h"

struct tex_param;

#ifdef __cplusplus
extern "C" {
#endif

/* Append s to b as a quoted JSON string; 0, or -1 when memory ran out (b unchanged). */
int tex_json_string(struct tex_str *b, const char *s);

/* Append the rows up to the {0} row as an array: each row's name, type, range, default as
 * the option prints it, help, choices, argument name (meta) and the modes it applies to
 * (kinds, 0: every mode). */
void tex_json_rows(struct tex_str *b, const struct tex_param *rows);

/* A value read: a string's bytes (escapes decoded) and a number's text as written are in
 * str; an array's items and an object's members (each with its key) in item[0..n-1]. */
enum tex_json_type { TEX_JSON_NULL, TEX_JSON_FALSE, TEX_JSON_TRUE, TEX_JSON_NUMBER,
                     TEX_JSON_STRING, TEX_JSON_ARRAY, TEX_JSON_OBJECT };
struct tex_json {
    enum tex_json_type type;
    char *key, *str;
    struct tex_json *item;
    int n;
};

/* The document in text[0..len-1] (RFC 8259; nested at most 64 deep); NULL with the error
 * and its byte offset in err when it is not JSON or memory ran out. */
struct tex_json *tex_json_parse(const char *text, size_t len, char *err, size_t errn);
/* An object's member of that key (the first), or NULL (also when v is not an object). */
const struct tex_json *tex_json_get(const struct tex_json *v, const char *key);
void tex_json_free(struct tex_json *v);

#ifdef __cplusplus
}
#endif
#endif
