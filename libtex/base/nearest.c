/* nearest.c - the name nearest to a mistyped one (manual: nearest.h) */
#include <string.h>

#include "base/nearest.h"

enum { MAX = 63 }; /* longer words are not compared */

void tex_nearest_init(struct tex_nearest *n, const char *word)
{
    n->word = word;
    n->best = 1 << 20;
    n->name[0] = 0;
}

/* The optimal string alignment distance between a[0..m) and b[0..k). */
static int distance(const char *a, size_t m, const char *b, size_t k)
{
    int d[MAX + 1][MAX + 1];
    for (size_t i = 0; i <= m; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= k; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= m; i++)
        for (size_t j = 1; j <= k; j++) {
            int c = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            int del = d[i - 1][j] + 1, ins = d[i][j - 1] + 1;
            c = c < del ? c : del;
            c = c < ins ? c : ins;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < c)
                c = d[i - 2][j - 2] + 1;
            d[i][j] = c;
        }
    return d[m][k];
}

void tex_nearest_try(struct tex_nearest *n, const char *cand, size_t len)
{
    size_t m = strlen(n->word);
    if (!len || len > MAX || m > MAX)
        return;
    int d = distance(n->word, m, cand, len);
    if (d < n->best) {
        n->best = d;
        memcpy(n->name, cand, len);
        n->name[len] = 0;
    }
}

void tex_nearest_try_list(struct tex_nearest *n, const char *list)
{
    while (list && *list) {
        size_t len = strcspn(list, "|");
        tex_nearest_try(n, list, len);
        list += len + (list[len] == '|');
    }
}

const char *tex_nearest_name(const struct tex_nearest *n)
{
    int m = (int)strlen(n->word), limit = m / 3 > 1 ? m / 3 : 1;
    return n->name[0] && n->best > 0 && n->best <= limit && n->best < m ? n->name : NULL;
}
