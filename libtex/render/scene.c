/* scene.c - the scene: its overrides, preparation for rendering, warnings and release */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/map.h"
#include "lang/proc.h"
#include "ops/palette.h"
#include "render/colour_spectral.h"
#include "render/render_ct.h"
#include "render/scene.h"

void tex_scene_warn(struct tex_scene *s, const char *fmt, ...)
{
    char line[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    size_t old = s->warnings ? strlen(s->warnings) : 0, n = strlen(line);
    char *w = realloc(s->warnings, old + n + 2);
    if (!w)
        return;
    memcpy(w + old, line, n);
    w[old + n] = '\n';
    w[old + n + 1] = 0;
    s->warnings = w;
}

void tex_scene_free(struct tex_scene *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->ntextures; i++) {
        struct tex_texture *t = s->textures[i];
        if (t->mip)
            for (int l = 0; l < t->nlevels; l++)
                tex_map_free(t->mip[l]);
        free(t->mip);
        tex_field_free(t->field);
        free(t);
    }
    free(s->textures);
    for (int i = 0; i < s->nsurfaces; i++)
        tex_surface_uncache(s->surfaces[i]);
    for (int i = 0; i < s->npalettes; i++)
        tex_palette_free(s->palettes[i]);
    free(s->palettes);
    free(s->objects);
    tex_bvh_free(s->bvh);
    tex_procs_free(s->procs); /* after the textures' fields */
    for (size_t i = 0; i < s->npool; i++)
        free(s->pool[i]);
    free(s->pool);
    tex_pages_free(s->packets, s->packets_mapped);
    free(s->warnings);
    free(s->file);
    tex_colour_space_spectral_free(&s->cs);
    free(s);
}

/* An override through the settings' rows: the same ranges as the scene's. */
static int set_setting(struct tex_scene *s, const char *word, const double *v, int k)
{
    return tex_param_store(tex_param_find(tex_settings_rows, word), s, v, k, TEX_PARAM_WORD);
}

int tex_scene_set_size(struct tex_scene *s, int w, int h)
{
    return set_setting(s, "image", (const double[]){w, h}, 2);
}

void tex_scene_size(const struct tex_scene *s, int *w, int *h)
{
    *w = s->settings.w;
    *h = s->settings.h;
}

int tex_scene_set_samples(struct tex_scene *s, int spp)
{
    return set_setting(s, "samples", (const double[]){spp}, 1);
}

void tex_scene_set_threads(struct tex_scene *s, int n)
{
    s->settings.threads = n > 0 ? n : 0;
}

void tex_scene_set_model(struct tex_scene *s, const struct tex_shading_model *m)
{
    for (int k = 0; m && k < s->nsurfaces; k++)
        s->surfaces[k]->model = m;
}

const char *tex_scene_warnings(const struct tex_scene *s)
{
    return s->warnings ? s->warnings : "";
}

int tex_scene_set_colour(struct tex_scene *s, int bands)
{
    struct tex_colour_space cs;
    if (!bands)
        tex_colour_space_rgb(&cs);
    else if (tex_colour_space_spectral(&cs, bands, NULL) < 0)
        return -1;
    tex_colour_space_spectral_free(&s->cs);
    s->cs = cs;
    return 0;
}

/* Is point p inside object ob?  A ray from p: inside if p lies in one of
 * its intervals; *out is where that ray leaves it. */
static int inside(const struct tex_object *ob, tex_v3 p, struct tex_hit *out)
{
    struct tex_spans sp;
    tex_object_spans(ob, p, tex_v3_make(0.5773, 0.5774, 0.5775), &sp);
    for (int i = 0; i < sp.n; i++) {
        if (sp.in[i].t < 0 && sp.out[i].t > 0) {
            *out = sp.out[i];
            return 1;
        }
    }
    return 0;
}

/* The camera's media: the transparent solids around the eye (their exit
 * surfaces have Kt > 0), outermost (farthest exit) first; the others warn. */
static void eye_media(struct tex_scene *s)
{
    struct tex_media *m = &s->eye_media;
    double exit[TEX_MEDIA_MAX];
    m->n = 0;
    for (int i = 0; i < s->nobjects; i++) {
        const struct tex_object *o = s->objects[i];
        struct tex_hit h;
        if (!inside(o, s->eye, &h))
            continue;
        const struct tex_surface *sf = h.leaf && h.leaf->surface ? h.leaf->surface : s->surfaces[0];
        if (!(sf->kt > 0) || m->n == TEX_MEDIA_MAX) {
            tex_scene_warn(s, "%s:%d:%d: warning: the camera is inside this object", s->file, o->line,
                 o->col);
            continue;
        }
        int k = m->n++; /* insertion by exit distance, ties in scene order */
        for (; k > 0 && exit[k - 1] < h.t; k--) {
            m->ob[k] = m->ob[k - 1], m->ior[k] = m->ior[k - 1];
            exit[k] = exit[k - 1];
        }
        m->ob[k] = o, m->ior[k] = sf->ior, exit[k] = h.t;
    }
}

int tex_scene_prepare(struct tex_scene *s)
{
    struct tex_settings *st = &s->settings;
    if (st->w < 1 || st->h < 1 || st->w > TEX_SCENE_MAX_SIDE || st->h > TEX_SCENE_MAX_SIDE)
        return tex_usage_error("image size %dx%d is outside 1..%d on each side", st->w, st->h,
                               TEX_SCENE_MAX_SIDE);
    if (tex_map_check_size(st->w, st->h, 3) < 0)
        return -1;
    if (st->spp < 1 || st->spp > 4096)
        return tex_usage_error("samples per pixel %d is outside 1..4096", st->spp);
    for (int i = 0; i < s->nlights; i++) {
        struct tex_light *l = &s->lights[i];
        if (!l->spectrum) {
            s->cs.from_rgb(&s->cs, l->rgb, TEX_SPECTRUM_ILLUMINANT, &l->e);
            continue;
        }
        /* the spectrum at luminance 1 times the intensity */
        if (tex_colour_space_spectral_light(&s->cs, l->spectrum, &l->e) < 0)
            return -1;
        tex_colour_scale(&l->e, s->cs.n, &l->e, l->rgb[0]);
    }
    /* the colour model may have changed since the surfaces were read; their caches are
     * filled once here, not by every band of rows a render is asked for (t_apply's ten
     * bands tabulated Fresnel ten times: 2 % of a spectral render) */
    for (int i = 0; i < s->nsurfaces; i++) {
        if (s->surfaces[i]->ct)
            tex_ct_set_space(s->surfaces[i]->ct, &s->cs);
        if (tex_surface_cache(s->surfaces[i], &s->cs) < 0)
            return -1;
    }
    tex_bvh_free(s->bvh);
    s->bvh = tex_bvh_build(s->objects, s->nobjects);
    if (!s->bvh)
        return -1;
    eye_media(s);
    return 0;
}
