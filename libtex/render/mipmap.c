/* mipmap.c - textures: mip-map pyramids, lookups in them, primitives at hit points
 *
 * A texture is a map, with a pyramid of box-filtered levels for lookups filtered by the
 * pixel's footprint (Williams 1983), or a primitive evaluated where rays meet surfaces.
 */
#include <math.h>
#include <stdlib.h>

#include "base/error.h"
#include "ops/palette.h"
#include "render/mipmap.h"

int tex_texture_build_mip(struct tex_texture *t)
{
    tex_map *m = t->mip[0];
    int n = 1;
    for (int w = m->w, h = m->h; w > 1 || h > 1; w = (w + 1) / 2, h = (h + 1) / 2)
        n++;
    tex_map **mip = realloc(t->mip, n * sizeof *mip);
    if (!mip)
        return tex_error("out of memory");
    t->mip = mip;
    t->nlevels = 1;
    if (t->subregions)
        return 0; /* region ids are never averaged */
    for (int l = 1; l < n; l++) {
        tex_map *d = tex_map_reduce(mip[l - 1]);
        if (!d)
            return -1;
        mip[l] = d;
        t->nlevels = l + 1;
        if (d->w == 1 && d->h == 1)
            break;
    }
    return 0;
}

/* A primitive's values at n points (u, v[, w]) into out (n x its channels); fw: the
 * footprints' widths (NULL: none) */
void tex_field_points(const struct tex_texture *t, int n, const double *u, const double *v,
                         const double *w, const double *fw, float *out)
{
    const struct tex_field *f = t->field;
    if (fw && band_limited(t))
        f->prim->eval3_fw(f, n, u, v, w, fw, out);
    else if (t->solid)
        f->prim->eval3(f, n, u, v, w, out);
    else
        f->prim->eval2(f, n, u, v, out);
}

/* A primitive's value val at a hit (its channels, the rest 0) as RGB, through the
 * texture's palette; returns the region id or 0. */
int tex_field_finish(const struct tex_texture *t, float val[TEX_MAP_MAX_CHANNELS],
                        float out[3])
{
    const struct tex_field *f = t->field;
    int region = (f->prim->flags & TEX_PRIM_REGIONS) && f->ids ? (int)lrintf(val[0]) : 0;
    if (t->palette) { /* a region's indexed colour, or the value in [0, 1] */
        float rgba[4];
        if (region)
            tex_palette_index_n(t->palette, region, f->nregions, rgba);
        else
            tex_palette_lookup(t->palette, tex_palette_t(val[0], 0, 1, TEX_OUTSIDE_CLAMP), rgba);
        val[0] = rgba[0], val[1] = rgba[1], val[2] = rgba[2];
        to_rgb(val, 3, out);
    } else {
        to_rgb(val, f->nc, out);
    }
    return region;
}

/* A primitive's value at a hit point (u, v[, w]) seen through a footprint sqrt(fw2) wide */
int tex_field_eval(const struct tex_texture *t, double u, double v, double w, double fw2,
                      float out[3])
{
    float val[TEX_MAP_MAX_CHANNELS] = {0};
    double fw = sqrt(fw2);
    tex_field_points(t, 1, &u, &v, &w, &fw, val);
    return tex_field_finish(t, val, out);
}

/* texture_eval at any coordinates (wrapped as placed ones), out of line */
int tex_texture_lookup(const struct tex_texture *t, double u, double v, double w, double fw2,
                          float out[3])
{
    if (t->mip)
        u = wrap01(u), v = wrap01(v);
    return texture_eval(t, u, v, w, fw2, out, NULL);
}

int tex_texture_eval(const struct tex_texture *t, double u, double v, double w, double fw,
                     float out[3])
{
    return tex_texture_lookup(t, u, v, w, fw > 0 ? fw * fw : 0, out);
}

void tex_texture_points(const struct tex_texture *t, int n, const double *u, const double *v,
                        const double *fw2, float *out, double *grad)
{
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX512 && t->nlevels < 32) { /* struct pyramid's room */
        tex_map_points_avx512(t, n, u, v, fw2, out, grad);
        return;
    }
#endif
    for (int i = 0; i < n; i++)
        texture_eval(t, u[i], v[i], 0, fw2[i], out + 3 * i, grad ? grad + 2 * i : NULL);
}
