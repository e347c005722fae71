/* nearest.h - the name nearest to a mistyped one, for messages that say "did you mean"
 *
 *   struct tex_nearest n;
 *   tex_nearest_init(&n, "frequnecy");
 *   for (each known name) tex_nearest_try(&n, name, strlen(name));
 *   const char *s = tex_nearest_name(&n);   // "frequency", or NULL: none is near
 *
 * Nearness is the optimal string alignment distance (insertions, deletions, changes and
 * swaps of neighbours, each 1), as getopt-style tools and shells measure it.  A name is
 * near when it is at most one edit away, or a third of the word's length for longer
 * words, and nearer than any other tried; the first of equals wins.
 */
#ifndef TEX_NEAREST_H
#define TEX_NEAREST_H

#include <stddef.h>

struct tex_nearest {
    const char *word;
    int best;      /* the distance of name, or a large number */
    char name[64]; /* the nearest so far */
};

void tex_nearest_init(struct tex_nearest *n, const char *word);
/* Try the len bytes at cand (not NUL-terminated) as a candidate. */
void tex_nearest_try(struct tex_nearest *n, const char *cand, size_t len);
/* Each '|'-separated word of list ("fbm|ridged|hybrid") as a candidate. */
void tex_nearest_try_list(struct tex_nearest *n, const char *list);
/* The nearest name close enough to be meant, or NULL. */
const char *tex_nearest_name(const struct tex_nearest *n);

#endif
