/* assemble.c - windows of a map put back together, a band of rows at a time */
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "io/assemble.h"
#include "io/file.h"

struct part {
    const char *path;
    tex_map head; /* place and size from the header */
    tex_map *m;   /* loaded while the rows pass through it */
};

struct job {
    struct part *p;
    int n, nc;
    const char *history;
};

static int by_place(const void *a, const void *b)
{
    const struct part *p = a, *q = b;
    if (p->head.y0 != q->head.y0)
        return p->head.y0 < q->head.y0 ? -1 : 1;
    return (p->head.x0 > q->head.x0) - (p->head.x0 < q->head.x0);
}

/* Rows y..y+n-1 of the full map: every window they cross, loaded on first use
 * and freed once the rows are below it. */
static int fill(void *arg, int y, int n, float *rows)
{
    struct job *j = arg;
    size_t fw = (size_t)j->p[0].head.full_w, nc = (size_t)j->nc;

    for (int i = 0; i < j->n; i++) {
        struct part *p = &j->p[i];
        const tex_map *h = &p->head;
        if (h->y0 >= y + n || h->y0 + h->h <= y)
            continue;
        if (!p->m) {
            if (!(p->m = tex_map_read(p->path)))
                return -1;
            if (p->m->w != h->w || p->m->h != h->h || p->m->nc != j->nc)
                return tex_error("%s: changed while being assembled", p->path);
        }
        for (int r = y > h->y0 ? y : h->y0; r < y + n && r < h->y0 + h->h; r++)
            memcpy(rows + ((size_t)(r - y) * fw + h->x0) * nc, tex_map_row(p->m, r - h->y0),
                   sizeof *rows * nc * h->w);
        if (h->y0 + h->h <= y + n) {
            tex_map_free(p->m);
            p->m = NULL;
        }
    }
    return 0;
}

/* The windows must share the full size and channels, and cover it once. */
static int check_cover(const struct part *p, int n)
{
    const tex_map *a = &p[0].head;
    long long area = 0;

    for (int i = 0; i < n; i++) {
        const tex_map *h = &p[i].head;
        if (h->full_w != a->full_w || h->full_h != a->full_h)
            return tex_usage_error("%s is a window of a %dx%d map, %s of a %dx%d one", p[i].path,
                                   h->full_w, h->full_h, p[0].path, a->full_w, a->full_h);
        if (h->nc != a->nc)
            return tex_usage_error("%s has %d channels, %s %d", p[i].path, h->nc, p[0].path,
                                   a->nc);
        for (int k = 0; k < i; k++) {
            const tex_map *g = &p[k].head;
            if (h->x0 < g->x0 + g->w && g->x0 < h->x0 + h->w && h->y0 < g->y0 + g->h &&
                g->y0 < h->y0 + h->h)
                return tex_usage_error("windows %s and %s overlap", p[k].path, p[i].path);
        }
        area += (long long)h->w * h->h;
    }
    if (area != (long long)a->full_w * a->full_h)
        return tex_usage_error("the windows cover %lld of the %dx%d map's %lld pixels", area,
                               a->full_w, a->full_h, (long long)a->full_w * a->full_h);
    return 0;
}

int tex_assemble(const char *const *paths, int n, int fd, const char *name, int tile,
                 enum tex_compression c, const char *history)
{
    struct part *p = calloc((size_t)n, sizeof *p);
    struct job j = {p, n, 0, history};
    tex_map head = {0}, *first = NULL;
    int r = -1;

    if (!p)
        return tex_error("out of memory");
    for (int i = 0; i < n; i++) {
        p[i].path = paths[i];
        if (tex_exr_probe(paths[i], &p[i].head) < 0)
            goto done;
    }
    qsort(p, (size_t)n, sizeof *p, by_place);
    if (check_cover(p, n) < 0)
        goto done;
    /* The full map's metadata: the top-left window's, without a place.  The window stays
     * read for fill: read again, it warned twice of what it holds (channels dropped). */
    if (!(first = tex_map_read(p[0].path)))
        goto done;
    head.w = p[0].head.full_w;
    head.h = p[0].head.full_h;
    head.nc = j.nc = p[0].head.nc;
    head.subregions = first->subregions;
    if (history && tex_map_add_history(first, history) < 0)
        goto done;
    if (first->history && !(head.history = strdup(first->history))) {
        r = tex_error("out of memory");
        goto done;
    }
    p[0].m = first;
    first = NULL;
    if (p[0].m->w != p[0].head.w || p[0].m->h != p[0].head.h || p[0].m->nc != j.nc) {
        r = tex_error("%s: changed while being assembled", p[0].path);
        goto done;
    }
    r = tex_exr_write_rows(&head, fill, &j, tile, c, fd, name);
done:
    for (int i = 0; i < n; i++)
        tex_map_free(p[i].m);
    tex_map_free(first);
    free(head.history);
    free(p);
    return r;
}
