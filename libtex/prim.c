/* prim.c - the primitive registry, fields, and sampling on a grid */
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "prim.h"

const struct tex_primitive *const tex_primitives[] = {
#define TEX_PRIMITIVE(n) &tex_prim_##n,
#include "primitives.def"
#undef TEX_PRIMITIVE
    NULL};

const struct tex_primitive *tex_primitive_find(const char *name)
{
    for (int i = 0; tex_primitives[i]; i++)
        if (strcmp(tex_primitives[i]->name, name) == 0)
            return tex_primitives[i];
    return NULL;
}

struct tex_field *tex_field_new(const struct tex_primitive *p)
{
    struct tex_field *f = calloc(1, sizeof *f);

    if (!f || !(f->params = calloc(1, p->params_size ? p->params_size : 1))) {
        free(f);
        tex_error("out of memory");
        return NULL;
    }
    f->prim = p;
    f->nc = 1;
    if (tex_params_defaults(p->params, f->params) < 0) {
        tex_field_free(f);
        return NULL;
    }
    return f;
}

int tex_field_set(struct tex_field *f, const char *name, const char *value)
{
    const struct tex_param *p = tex_param_find(f->prim->params, name);

    if (!p)
        return tex_usage_error("%s has no parameter '%s'", f->prim->name, name);
    return tex_param_set(p, f->params, value);
}

int tex_field_init(struct tex_field *f, int w, int h)
{
    f->w = w;
    f->h = h;
    if (f->tile && !(f->prim->flags & TEX_PRIM_TILE))
        return tex_usage_error("%s cannot tile (--tile)", f->prim->name);
    if (f->ids && !(f->prim->flags & TEX_PRIM_REGIONS))
        return tex_usage_error("%s has no subregions (--ids)", f->prim->name);
    return f->prim->init ? f->prim->init(f) : 0;
}

void tex_field_free(struct tex_field *f)
{
    if (!f)
        return;
    if (f->prim->fini)
        f->prim->fini(f);
    free(f->params);
    free(f);
}

tex_map *tex_field_sample(const struct tex_field *f)
{
    const struct tex_primitive *p = f->prim;
    tex_map *m = tex_map_new(f->w, f->h, f->nc);
    int failed = 0;

    if (!m)
        return NULL;
    if (p->flags & TEX_PRIM_REGIONS && f->ids)
        m->subregions = f->nregions;
    if (p->flags & TEX_PRIM_GRID) {
        if (p->grid(f, m) < 0) {
            tex_map_free(m);
            return NULL;
        }
        return m;
    }
    if (p->row) {
#pragma omp parallel for schedule(dynamic, 4)
        for (int y = 0; y < f->h; y++)
            p->row(f, y, tex_map_row(m, y));
        return m;
    }
#pragma omp parallel
    {
        double *u = malloc(2 * sizeof *u * f->w), *v = u ? u + f->w : NULL;
        if (!u) {
#pragma omp atomic write
            failed = 1;
        } else {
            for (int x = 0; x < f->w; x++)
                u[x] = (x + 0.5) / f->w;
#pragma omp for schedule(dynamic, 4)
            for (int y = 0; y < f->h; y++) {
                for (int x = 0; x < f->w; x++)
                    v[x] = (y + 0.5) / f->h;
                p->eval2(f, f->w, u, v, tex_map_row(m, y));
            }
        }
        free(u);
    }
    if (failed) {
        tex_map_free(m);
        tex_error("out of memory");
        return NULL;
    }
    return m;
}
