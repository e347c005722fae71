/* names.h - a table from names to pointers, for parsers that meet many definitions
 *
 *   struct tex_names t = {0};
 *   if (tex_names_put(&t, "marble", p) < 0) ...   // -1: out of memory, error set
 *   void *q = tex_names_get(&t, "marble");        // p, or NULL when absent
 *   tex_names_free(&t);
 *
 * Open addressing on FNV-1a, doubled at half full: put and get take constant time on
 * average, where a search of every name before took quadratic time over a file (2 10^5
 * materials, 10^5 composed primitives: over 20 s).  The table keeps copies of the names;
 * a name put twice keeps its first value.
 */
#ifndef TEX_NAMES_H
#define TEX_NAMES_H

struct tex_names {
    char **key;
    void **val;
    long cap, n;
};

int tex_names_put(struct tex_names *t, const char *name, void *val);
void *tex_names_get(const struct tex_names *t, const char *name);
void tex_names_free(struct tex_names *t);

#endif
