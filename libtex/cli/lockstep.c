/* lockstep.c - several maps read a band of rows at a time, in step (see lockstep.h) */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "cli/cli.h"
#include "cli/lockstep.h"
#include "io/file.h"

struct tex_lockstep {
    int n, rows;          /* inputs; the bands' room in rows */
    tex_rows_reader **r;  /* input k's rows, or NULL */
    tex_map *heads;       /* their headers (px NULL) */
    tex_map **whole;      /* inputs read whole */
    tex_map **band;       /* a band of each */
    const char **name;
    tex_lockstep_fn *op;
    void *arg;
};

static void *need(void *p)
{
    if (!p) {
        tex_error("out of memory");
        tex_die();
    }
    return p;
}

tex_lockstep *tex_cli_lockstep_new(int n)
{
    tex_lockstep *l = need(calloc(1, sizeof *l));

    l->n = n;
    l->r = need(calloc((size_t)n, sizeof *l->r));
    l->heads = need(calloc((size_t)n, sizeof *l->heads));
    l->whole = need(calloc((size_t)n, sizeof *l->whole));
    l->band = need(calloc((size_t)n, sizeof *l->band));
    l->name = need(calloc((size_t)n, sizeof *l->name));
    return l;
}

const tex_map *tex_cli_lockstep_add(tex_lockstep *l, int k, const char *path)
{
    l->name[k] = strcmp(path, "-") ? path : "standard input";
    if (!(l->r[k] = tex_map_open_rows(path, &l->heads[k], &l->whole[k])) && !l->whole[k])
        tex_die();
    return l->r[k] ? &l->heads[k] : l->whole[k];
}

int tex_cli_lockstep_streams(const tex_lockstep *l, const struct tex_common *c)
{
    const tex_map *first = NULL;

    for (int k = 0; k < l->n; k++) {
        if (l->whole[k])
            return 0;
        if (!l->r[k])
            continue;
        if (first && (l->heads[k].w != first->w || l->heads[k].h != first->h))
            return 0;
        first = first ? first : &l->heads[k];
    }
    return first && tex_cli_takes_rows(c);
}

/* Band k of n rows, from its reader when read (y >= 0), its room grown as asked */
static tex_map *band_of(tex_lockstep *l, int k, int y, int n)
{
    tex_map *b = l->band[k];

    if (!b || n > l->rows) {
        tex_map_free(b);
        if (!(b = l->band[k] = tex_map_new(l->heads[k].w, n, l->heads[k].nc)))
            return NULL;
    }
    b->h = n;
    b->subregions = l->heads[k].subregions;
    if (y >= 0 && (tex_rows_read(l->r[k], y, n, b->px, l->name[k]) < 0 ||
                   tex_rows_nonfinite(b->px, b->w, n, b->nc, y, l->name[k]) < 0))
        return NULL;
    return b;
}

static int lockstep_fill(void *arg, int y, int n, float *rows)
{
    tex_lockstep *l = arg;
    tex_map *out;

    for (int k = 0; k < l->n; k++)
        if (l->r[k] && !band_of(l, k, y, n))
            return -1;
    l->rows = n > l->rows ? n : l->rows;
    if (!(out = l->op(l->band, l->arg)))
        return -1;
    memcpy(rows, out->px, tex_map_samples(out) * sizeof *rows);
    tex_map_free(out);
    return 0;
}

void tex_cli_lockstep_write(tex_lockstep *l, const struct tex_common *c, int hist,
                            tex_lockstep_fn *op, void *arg)
{
    tex_map head = {0}, *probe;

    l->op = op, l->arg = arg;
    for (int k = 0; k < l->n; k++)
        if (l->r[k]) {
            if (!band_of(l, k, -1, 1)) /* a row of zeros */
                tex_die();
            head.w = l->heads[k].w, head.h = l->heads[k].h;
        }
    l->rows = 1;
    if (!(probe = op(l->band, arg)))
        tex_die();
    head.nc = probe->nc;
    head.subregions = probe->subregions;
    tex_map_free(probe);
    if (hist >= 0 && l->r[hist]) /* the history of input hist */
        head.history = l->heads[hist].history, l->heads[hist].history = NULL;
    tex_cli_write_rows(&head, c, lockstep_fill, l);
    free(head.history);
}

tex_map *tex_cli_lockstep_whole(tex_lockstep *l, int k)
{
    tex_map *m = l->whole[k];

    if (l->r[k]) {
        m = tex_cli_rows_whole(l->r[k], &l->heads[k], l->name[k]);
        l->r[k] = NULL;
    }
    l->whole[k] = NULL;
    return m;
}

void tex_cli_lockstep_free(tex_lockstep *l)
{
    if (!l)
        return;
    for (int k = 0; k < l->n; k++) {
        tex_rows_close(l->r[k]);
        if (l->r[k])
            free(l->heads[k].history);
        tex_map_free(l->whole[k]);
        tex_map_free(l->band[k]);
    }
    free(l->r), free(l->heads), free(l->whole), free(l->band), free(l->name);
    free(l);
}
