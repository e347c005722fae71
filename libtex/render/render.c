/* render.c - an image's samples: pixels, packets, tiles and threads
 *
 * Each pixel draws its sample positions (and area-light jitter) from an
 * RNG seeded by the scene seed and the pixel's index, and pixels are
 * independent, so any thread count gives the same image, and a region of
 * the image the same pixels as the whole render.  Tiles of 16x16
 * pixels are shared among OpenMP threads dynamically.
 *
 * Eye rays go in packets of 8x8 pixels (render_packet): all find their hits,
 * then the primitives evaluated at hit points, and the image maps that
 * surfaces apply first, are evaluated over the packet's hits in one call each
 * (tex_prefetch_eval: a map's footprints and trilinear lookups in vector
 * lanes; a leaf's hits of one planar map on a plane, or of one natural map on a
 * box, cylinder, cone or sphere, in lanes from their points on,
 * tex_prefetch_lanes), then every hit is shaded: those on plain surfaces (Phong
 * without rays of their own, tex_surface_plain) together, light by light
 * (plain_shade), the others one by one.  A point gets the same value in a call
 * of any length, and each pixel draws from its own rng in the same order, so
 * the image is the one pixel-by-pixel tracing makes; TEXTURA_PACKETS=0 in the
 * environment traces pixel by pixel (tests/render/t_apply_packets.sh compares the
 * two).
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/rng.h"
#include "base/simd.h"
#include "render/camera.h"
#include "render/scene.h"
#include "render/whitted.h"
#include "render/x86/light_x86.h"

#define TILE 16

/* A sample's colour col added to the pixel's sum acc, in RGB */
static inline void accumulate(const struct tex_scene *s, const tex_colour *col, double acc[3])
{
    float rgb[3];
    if (s->cs.mode == TEX_COLOUR_RGB) { /* the identity: no call, no store and reload */
        for (int j = 0; j < 3; j++)
            acc[j] += col->v[j];
        return;
    }
    s->cs.to_rgb(&s->cs, col, rgb);
    for (int j = 0; j < 3; j++)
        acc[j] += rgb[j];
}

static void seed_pixel(const struct tex_render_ctx *c, int x, int y, tex_rng *rng)
{
    const struct tex_settings *st = &c->s->settings;
    if (c->need_rng)
        tex_rng_seed(rng, tex_hash64(st->seed ^ tex_hash64((uint64_t)y * st->w + x)));
}

static void put_pixel(int spp, const double acc[3], float *px)
{
    for (int j = 0; j < 3; j++)
        px[j] = (float)(spp == 1 ? acc[j] : acc[j] / spp);
}

/* One pixel, its samples traced one by one (TEXTURA_PACKETS=0) */
static void render_pixel(const struct tex_render_ctx *c0, const struct tex_camera *cam, int x, int y, float *px)
{
    tex_rng rng;
    seed_pixel(c0, x, y, &rng);
    struct tex_render_ctx c = *c0;
    c.rng = &rng;
    int spp = c0->s->settings.spp;
    double acc[3] = {0, 0, 0};
    for (int i = 0; i < spp; i++) {
        tex_ray r;
        tex_colour col;
        tex_camera_ray(c.s, cam, x, y, i, &rng, &r);
        tex_trace(&c, &r, NULL, 0, 1, &col);
        accumulate(c0->s, &col, acc);
    }
    put_pixel(spp, acc, px);
}

/* A packet of eye rays: a square of PACKET x PACKET pixels, traced a sample at a time.
 * Every ray finds its hit first; then the textures of all the hits are looked up together
 * (tex_prefetch_eval: one batched call per primitive); then each hit is shaded.  Each
 * pixel keeps its own rng and draws from it in the order render_pixel does, and the
 * lookups ahead are the same computations, so the bytes are the per-pixel render's. */
#define PACKET 8
#define QUEUES 3 /* lanes' queues: a packet's leaves (a floor, an object's faces) */
#define NP (PACKET * PACKET)
_Static_assert(NP <= TEX_TRANSMIT_MAX, "a packet's plain hits' shadow rays go in one batch");

/* A packet's hits on plain surfaces (tex_surface_plain), in an RGB scene lit by point and
 * spot lights alone: shade's work for them (ambient, then each light's direction, shadow
 * ray and Phong) without its general set-up (nor the material's, where tex_plain_material
 * makes it), done light by light over all of them, their shadow rays together.  Each sum in
 * the same order as shade's: the same bits. */
struct plain {
    int n, k[NP];                        /* k: the hit in the packet */
    const struct tex_object *outside[NP]; /* shade's */
    tex_v3 P[NP], N[NP], V[NP], Pout[NP];
    struct tex_light_ahead a[NP];            /* the light's from each */
    struct tex_plain m[NP];
    float out[NP][3];
    int nbent, bent[NP]; /* the hits whose N the general path made */
    tex_v3 Ngv[NP];      /* their geometric normals */
    int nlater;          /* hits whose Kd function was left to run together */
    struct tex_plain_later later[NP];
};

/* A packet's hits that general_shade shades, their shadow rays traced together light by
 * light: those whose light samples number LIT_MIN to LIT_MAX */
#define LIT_MAX 32
/* and LIT_MIN at least: with fewer, a packet's hits held between their material and their
 * shading (64 of 2 KiB) cost more in the cache than their rays' batches saved (the
 * spheres benchmark, one light: 15 % more CPU than each hit shaded whole) */
#define LIT_MIN 4
struct general {
    int n, k[NP]; /* k: the hit in the packet */
    struct tex_shading sh[NP];
    struct tex_light_ahead lit[NP][LIT_MAX];
};

struct packet {
    tex_rng rng[PACKET * PACKET];
    int x[PACKET * PACKET], y[PACKET * PACKET]; /* the pixels: no division by the width */
    double acc[PACKET * PACKET][3];
    tex_ray r[PACKET * PACKET];
    struct tex_hit h[PACKET * PACKET];
    int hit[PACKET * PACKET];
    tex_v3 P[PACKET * PACKET], Ng[PACKET * PACKET];
    struct tex_prefetch pre[PACKET * PACKET], *pp[PACKET * PACKET];
    struct tex_lanes lanes[QUEUES];
    struct plain plain;
    struct general general;
};

/* The packet's hit k taken as the next plain one: its frame (shade's) from the normal Ngv
 * facing the ray (Pout's) and the shading normal N, and its ambient light */
static inline __attribute__((always_inline)) void plain_frame(const struct tex_render_ctx *c,
                                                               struct packet *pk, int k,
                                                               int entering, tex_v3 Ngv,
                                                               tex_v3 N)
{
    struct plain *pl = &pk->plain;
    int i = pl->n++;
    const struct tex_object *leaf = pk->h[k].leaf;
    tex_v3 P = pk->P[k];
    pl->k[i] = k;
    pl->outside[i] = entering && leaf->hull ? tex_object_top(leaf) : NULL;
    pl->P[i] = P, pl->N[i] = N, pl->V[i] = tex_v3_scale(pk->r[k].d, -1);
    pl->Pout[i] = tex_v3_madd(P, Ngv, tex_eps_at(P));
    for (int j = 0; j < 3; j++)
        pl->out[i][j] = c->ambient->v[j] * pl->m[i].ka[j];
}

/* Hit k (normal Ngv facing the ray) taken as a plain one where its surface's material takes
 * the general path (tex_surface_plain 2), its normal bent there.  Not inlined: the plain
 * surfaces' loop stays small. */
static __attribute__((noinline)) void plain_resolve(const struct tex_render_ctx *c, struct packet *pk,
                                                    int k, const struct tex_surface *sf,
                                                    int entering, tex_v3 Ngv)
{
    struct plain *pl = &pk->plain;
    const tex_ray *r = &pk->r[k];
    const struct tex_hit *h = &pk->h[k];
    tex_v3 N = Ngv;
    struct tex_shade_at at = {h->leaf, &pk->P[k], &r->d, fabs(r->width + h->t * r->spread),
                              r->dist + h->t, 0, &pk->pre[k]};
    tex_plain_resolve(c->s, sf, &at, &N, &pl->m[pl->n], &pl->later[pl->n]);
    pl->nlater += pl->later[pl->n].fn != NULL;
    pl->bent[pl->nbent++] = pl->n;
    pl->Ngv[pl->n] = Ngv;
    plain_frame(c, pk, k, entering, Ngv, N);
}

/* Hit k of the packet taken as a plain one: 1, or 0 for shade */
static int plain_take(const struct tex_render_ctx *c, struct packet *pk, int k)
{
    struct plain *pl = &pk->plain;
    const struct tex_surface *sf = tex_surface_of(c->s, pk->h[k].leaf);
    int kind = tex_surface_plain(sf);
    if (!kind || (kind == 1 && !tex_plain_material(sf, &pk->pre[k], &pl->m[pl->n])))
        return 0;
    tex_v3 Ng = pk->Ng[k];
    int entering = tex_v3_dot(pk->r[k].d, Ng) < 0;
    tex_v3 N = entering ? Ng : tex_v3_scale(Ng, -1);
    if (kind == 2) {
        plain_resolve(c, pk, k, sf, entering, N);
    } else {
        pl->later[pl->n].fn = NULL;
        plain_frame(c, pk, k, entering, N, N);
    }
    return 1;
}

/* Shadow rays gathered to be traced together (tex_scene_transmit_n), written where the walk
 * reads them: each one's light sample, whose ok and fatt take the light passing, as
 * tex_direct_light's do */
struct shadows {
    struct tex_shadow_rays b;
    struct tex_light_ahead *a[TEX_TRANSMIT_MAX];
};

static void shadows_trace(const struct tex_scene *s, struct shadows *sw)
{
    if (!sw->b.n)
        return;
    tex_scene_transmit_n(s, &sw->b);
    for (int i = 0; i < sw->b.n; i++)
        tex_light_pass(sw->a[i], sw->b.tr[i]);
    sw->b.n = 0;
}

/* Light sample a's shadow ray from o (from: tex_scene_trace's) as sw's ray i */
static inline void shadow_write(struct shadows *sw, int i, const tex_v3 *o,
                                const struct tex_object *from, struct tex_light_ahead *a)
{
    sw->b.r[i].o = *o, sw->b.r[i].d = a->L, sw->b.tmin[i] = 0, sw->b.tmax[i] = a->dist;
    sw->b.from[i] = from, sw->a[i] = a;
}

/* The shadow ray of light sample a from o (from: tex_scene_trace's) added to sw, the rays
 * traced when sw is full */
static inline void shadow_ray(const struct tex_scene *s, struct shadows *sw, const tex_v3 *o,
                              const struct tex_object *from, struct tex_light_ahead *a)
{
    shadow_write(sw, sw->b.n++, o, from, a);
    if (sw->b.n == TEX_TRANSMIT_MAX)
        shadows_trace(s, sw);
}

/* Light l's share at the plain hits (direct_light's); batch: their shadow rays together */
static void plain_light(const struct tex_scene *s, const struct tex_light *l, struct plain *pl,
                        int batch)
{
    int i = 0;
#ifdef TEX_X86
    if (tex_light_lanes(l) && tex_simd_level() >= TEX_SIMD_AVX2)
        for (; i + 4 <= pl->n; i += 4) /* the square roots and divisions four at a time */
            tex_light_points4_avx2(l, &pl->P[i], &pl->a[i]);
#endif
    for (; i < pl->n; i++)
        tex_light_ahead_at(l, 0, 0.5, 0.5, &pl->P[i], &pl->a[i]);
    for (i = 0; i < pl->n; i++) { /* direct_light's tests */
        struct tex_light_ahead *a = &pl->a[i];
        a->ok = a->ok && !(tex_v3_dot(a->L, pl->N[i]) <= 0);
    }
    for (int j = 0; j < pl->nbent; j++) { /* and the geometric normal's, where bent */
        struct tex_light_ahead *a = &pl->a[pl->bent[j]];
        a->ok = a->ok && !(tex_v3_dot(a->L, pl->Ngv[pl->bent[j]]) <= 0);
    }
    struct shadows sw;
    sw.b.n = 0;
    for (int i = 0; batch && i < pl->n; i++) { /* each hit's ray written, kept where lit */
        shadow_write(&sw, sw.b.n, &pl->Pout[i], pl->outside[i], &pl->a[i]);
        sw.b.n += pl->a[i].ok != 0;
    }
    for (int i = 0; !batch && i < pl->n; i++) {
        struct tex_light_ahead *a = &pl->a[i];
        if (a->ok)
            tex_light_pass(a, tex_scene_transmit(s, &pl->Pout[i], &a->L, 0, a->dist,
                                                 pl->outside[i]));
    }
    shadows_trace(s, &sw);
    for (int i = 0; i < pl->n; i++) {
        if (!pl->a[i].ok)
            continue;
        struct tex_material m;
        tex_colour E, out;
        for (int j = 0; j < 3; j++) {
            E.v[j] = l->e.v[j] * (float)pl->a[i].fatt;
            m.kd.v[j] = pl->m[i].kd[j], m.ks.v[j] = pl->m[i].ks[j], out.v[j] = pl->out[i][j];
        }
        m.n = pl->m[i].n;
        tex_phong_direct(&m, &pl->N[i].x, &pl->V[i].x, &pl->a[i].L.x, &E, 3, &out);
        for (int j = 0; j < 3; j++)
            pl->out[i][j] = out.v[j];
    }
}

/* The plain hits taken shaded, into their pixels' sums */
static void plain_shade(const struct tex_render_ctx *c, struct packet *pk)
{
    struct plain *pl = &pk->plain;
    const struct tex_scene *s = c->s;
    if (pl->nlater) { /* their Ka and Kd, then the ambient term plain_frame made from Ka */
        tex_plain_later_run(pl->later, pl->m, pl->n);
        for (int i = 0; i < pl->n; i++)
            for (int j = 0; pl->later[i].fn && j < 3; j++)
                pl->out[i][j] = c->ambient->v[j] * pl->m[i].ka[j];
    }
    for (int li = 0; li < s->nlights; li++)
        plain_light(s, &s->lights[li], pl, c->batch);
    for (int i = 0; i < pl->n; i++)
        for (int j = 0; j < 3; j++)
            pk->acc[pl->k[i]][j] += pl->out[i][j];
    pl->n = pl->nbent = pl->nlater = 0;
}

/* Hit k of the packet (its rng c's) taken to be shaded with the others (general_shade), its
 * material and light samples made: 1, or 0 where its samples number fewer than LIT_MIN or
 * more than LIT_MAX */
static int general_take(const struct tex_render_ctx *c, struct packet *pk, int k, int samples)
{
    struct general *g = &pk->general;
    if (!c->batch || samples < LIT_MIN || samples > LIT_MAX)
        return 0;
    int i = g->n++;
    g->k[i] = k;
    tex_shade_begin(c, &pk->r[k], &pk->h[k], pk->P[k], pk->Ng[k], &pk->pre[k], 0, &g->sh[i]);
    tex_light_rays(c, &g->sh[i], g->lit[i]);
    return 1;
}

/* The hits general_take took: their shadow rays traced together, light by light, then each
 * shaded (tex_shade_end) into its pixel's sum */
static void general_shade(struct tex_render_ctx *c, struct packet *pk)
{
    struct general *g = &pk->general;
    const struct tex_scene *s = c->s;
    struct shadows sw;
    sw.b.n = 0;
    for (int li = 0, at = 0; li < s->nlights; li++) {
        int ns = tex_light_samples(&s->lights[li]);
        for (int i = 0; i < g->n; i++)
            for (int j = at; j < at + ns; j++)
                if (g->lit[i][j].ok)
                    shadow_ray(s, &sw, &g->sh[i].Pout, g->sh[i].f.outside, &g->lit[i][j]);
        shadows_trace(s, &sw);
        at += ns;
    }
    for (int i = 0; i < g->n; i++) {
        int k = g->k[i];
        tex_colour col;
        c->rng = &pk->rng[k];
        tex_shade_end(c, &pk->r[k], &g->sh[i], g->lit[i], 0, 1, &col);
        accumulate(s, &col, pk->acc[k]);
    }
    g->n = 0;
}

/* Hit k of the packet queued for the lanes (tex_lanes_take) in the first queue of its leaf
 * and surface, or an empty one: 1, else 0 */
static int take_lanes(struct packet *pk, int k, const struct tex_surface *sf,
                      const struct tex_object *leaf, const tex_v3 *N, double w)
{
    for (int q = 0; q < QUEUES; q++) {
        if (tex_lanes_take(&pk->lanes[q], &pk->pre[k], sf, leaf, &pk->P[k], &pk->r[k].d, N, w))
            return 1;
        if (!pk->lanes[q].n) /* an empty queue refused it: every queue would */
            return 0;
    }
    return 0;
}

/* The packet's hits made ready to shade: their points and normals, their mappings and
 * footprints, then the lookups of all of them together. */
static void look_ahead(const struct tex_scene *s, struct packet *pk, int n)
{
    int m = 0;
    for (int q = 0; q < QUEUES; q++)
        pk->lanes[q].n = 0;
    for (int k = 0; k < n; k++) {
        tex_ray *r = &pk->r[k];
        if (!pk->hit[k])
            continue;
        pk->P[k] = tex_v3_madd(r->o, r->d, pk->h[k].t);
        pk->Ng[k] = tex_hit_normal(&pk->h[k], pk->P[k]);
        const struct tex_object *leaf = pk->h[k].leaf;
        const struct tex_surface *sf = tex_surface_of(s, leaf);
        if (!tex_surface_footprints(sf) || !s->settings.filter) {
            tex_prefetch_map(&pk->pre[k], sf, leaf, &pk->P[k]);
        } else { /* the frame as tex_shade() has it */
            tex_v3 N = pk->Ng[k];
            N = tex_v3_dot(r->d, N) < 0 ? N : tex_v3_scale(N, -1);
            double w = fabs(r->width + pk->h[k].t * r->spread);
            if (take_lanes(pk, k, sf, leaf, &N, w))
                continue;
            tex_prefetch_map(&pk->pre[k], sf, leaf, &pk->P[k]);
            tex_prefetch_footprints(&pk->pre[k], &r->d, &N, w);
        }
        pk->pp[m++] = &pk->pre[k];
    }
    for (int q = 0; q < QUEUES; q++)
        m += tex_prefetch_lanes(&pk->lanes[q], pk->pp + m);
    tex_prefetch_eval(pk->pp, m);
}

/* The pixels [x0, x1) x [y0, y1) of the image (at most PACKET square) into img, whose
 * origin is the image's (rx, ry). */
static void render_packet(const struct tex_render_ctx *c0, const struct tex_camera *cam, struct packet *pk,
                          int x0, int y0, int x1, int y1, tex_map *img, int rx, int ry)
{
    const struct tex_scene *s = c0->s;
    int spp = s->settings.spp, np = 0;
    struct tex_render_ctx c = *c0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++, np++)
            pk->x[np] = x, pk->y[np] = y;
    for (int k = 0; k < np; k++) {
        seed_pixel(c0, pk->x[k], pk->y[k], &pk->rng[k]);
        pk->acc[k][0] = pk->acc[k][1] = pk->acc[k][2] = 0;
    }
    /* a packet beside the box (most of a floor or a sky) tests only the unbounded objects,
     * and one beside an object's box does not test it */
    uint64_t visit = tex_camera_objects(cam, x0, y0, x1, y1);
    int samples = 0; /* light samples at a hit */
    for (int li = 0; li < s->nlights; li++)
        samples += tex_light_samples(&s->lights[li]);
    for (int i = 0; i < spp; i++) {
        tex_camera_rays(c.s, cam, pk->x, pk->y, np, i, pk->rng, pk->r);
        if (visit)
            tex_scene_trace_packet(s, np, pk->r, visit, pk->h, pk->hit);
        for (int k = 0; k < np && !visit; k++)
            pk->hit[k] = tex_scene_trace_unbounded(s, &pk->r[k].o, &pk->r[k].d, 0, INFINITY,
                                                   &pk->h[k]);
        look_ahead(s, pk, np);
        for (int k = 0; k < np; k++) {
            tex_colour col;
            c.rng = &pk->rng[k];
            if (pk->hit[k] && ((c.plain && plain_take(&c, pk, k)) ||
                               general_take(&c, pk, k, samples)))
                continue;
            if (pk->hit[k])
                tex_shade(&c, &pk->r[k], &pk->h[k], pk->P[k], pk->Ng[k], &pk->pre[k], 0, 1, &col);
            else
                tex_miss(&c, &pk->r[k], &col);
            accumulate(s, &col, pk->acc[k]);
        }
        general_shade(&c, pk);
        plain_shade(&c, pk);
    }
    for (int k = 0; k < np; k++)
        put_pixel(spp, pk->acc[k], tex_map_px(img, pk->x[k] - rx, pk->y[k] - ry));
}

tex_map *tex_render(struct tex_scene *s, void (*progress)(long, long, void *), void *arg)
{
    return tex_render_region(s, 0, 0, s->settings.w, s->settings.h, progress, arg);
}

/* A packet for each of n threads, made on the first band and kept for the others, in one
 * huge page where the kernel gives it (tex_pages_new): each thread's first touch of its own
 * 4 KiB pages was 29 page faults, 1 % of a render at -j 2 on a virtual machine; the pages
 * are made present here (tex_pages_touch), where a huge page's zeroing was 1.6 % of
 * render_packet's time at -j 2. NULL without the memory. */
static struct packet *packet_pool(struct tex_scene *s, int n)
{
    if (s->npackets < n) {
        tex_pages_free(s->packets, s->packets_mapped);
        s->packets = tex_pages_new(n * sizeof(struct packet), 0, &s->packets_mapped);
        if (s->packets) /* touched here, not by the threads' first packets */
            tex_pages_touch(s->packets, s->packets_mapped);
        s->npackets = s->packets ? n : 0;
    }
    return s->packets;
}

/* The scene prepared and the region inside its image, or -1 with the error set. */
static int region_check(struct tex_scene *s, int rx, int ry, int rw, int rh)
{
    if (!s->bvh && tex_scene_prepare(s) < 0)
        return -1;
    const struct tex_settings *st = &s->settings;
    if (rx < 0 || ry < 0 || rw < 1 || rh < 1 || rx > st->w - rw || ry > st->h - rh)
        return tex_usage_error("region %d,%d,%d,%d lies outside the %dx%d image", rx, ry, rw,
                               rh, st->w, st->h);
    return 0;
}

/* The pixels of img (the region of its size at rx, ry), or -1 with the error set. */
static int render_into(struct tex_scene *s, int rx, int ry, tex_map *img,
                       void (*progress)(long, long, void *), void *arg)
{
    const struct tex_settings *st = &s->settings;
    int rw = img->w, rh = img->h;
    tex_colour ambient, background;
    s->cs.from_rgb(&s->cs, s->ambient, TEX_SPECTRUM_ILLUMINANT, &ambient);
    s->cs.from_rgb(&s->cs, s->background, TEX_SPECTRUM_ILLUMINANT, &background);
    struct tex_render_ctx c = {s, s->cs.n, &ambient, &background, NULL, st->spp > 1,
                    s->cs.mode == TEX_COLOUR_RGB, tex_scene_shadow_batches(s)};
    for (int i = 0; i < s->nlights; i++) {
        c.need_rng |= s->lights[i].kind == TEX_LIGHT_AREA;
        c.plain &= s->lights[i].kind == TEX_LIGHT_POINT || s->lights[i].kind == TEX_LIGHT_SPOT;
    }
    struct tex_camera cam;
    tex_camera_setup(s, &cam);
    int tw = (rw + TILE - 1) / TILE, th = (rh + TILE - 1) / TILE;
    long ntiles = (long)tw * th, done = 0;
    int threads = st->threads > 0 ? st->threads : omp_get_max_threads();
    /* TEXTURA_PACKETS=0: every pixel on its own (the tests compare the two) */
    const char *pe = getenv("TEXTURA_PACKETS");
    int packets = !(pe && !strcmp(pe, "0")) && !s->nhypers; /* volumes: tex_trace's */
    struct packet *pool = packets ? packet_pool(s, threads) : NULL;
#pragma omp parallel num_threads(threads)
    {
        /* without the memory for packets, a thread goes pixel by pixel: the same bytes */
        struct packet *pk = pool ? &pool[omp_get_thread_num()] : NULL;
#pragma omp for schedule(dynamic, 1)
        for (long t = 0; t < ntiles; t++) {
            int x0 = (int)(t % tw) * TILE, y0 = (int)(t / tw) * TILE;
            int x1 = x0 + TILE < rw ? x0 + TILE : rw, y1 = y0 + TILE < rh ? y0 + TILE : rh;
            /* pixels keep their place in the whole image: camera rays and seeds */
            for (int py = y0; pk && py < y1; py += PACKET)
                for (int px = x0; px < x1; px += PACKET)
                    render_packet(&c, &cam, pk, rx + px, ry + py,
                                  rx + (px + PACKET < x1 ? px + PACKET : x1),
                                  ry + (py + PACKET < y1 ? py + PACKET : y1), img, rx, ry);
            for (int y = y0; !pk && y < y1; y++)
                for (int x = x0; x < x1; x++)
                    render_pixel(&c, &cam, rx + x, ry + y, tex_map_px(img, x, y));
            long d;
#pragma omp atomic capture
            d = ++done;
            if (progress && omp_get_thread_num() == 0)
                progress(d, ntiles, arg);
        }
    }
    if (progress)
        progress(ntiles, ntiles, arg);
    return 0;
}

tex_map *tex_render_region(struct tex_scene *s, int rx, int ry, int rw, int rh,
                           void (*progress)(long, long, void *), void *arg)
{
    tex_map *img;
    if (region_check(s, rx, ry, rw, rh) < 0 || !(img = tex_map_new(rw, rh, 3)))
        return NULL;
    tex_pages_touch(img->px, img->mapped); /* here, not in the threads' put_pixel */
    if (rw != s->settings.w || rh != s->settings.h) {
        img->x0 = rx;
        img->y0 = ry;
        img->full_w = s->settings.w;
        img->full_h = s->settings.h;
    }
    if (render_into(s, rx, ry, img, progress, arg) < 0) {
        tex_map_free(img);
        return NULL;
    }
    return img;
}

int tex_render_rows(struct tex_scene *s, int rx, int ry, int rw, int rh, float *px)
{
    tex_map img = {.w = rw, .h = rh, .nc = 3, .px = px};
    return region_check(s, rx, ry, rw, rh) < 0 ? -1 : render_into(s, rx, ry, &img, NULL, NULL);
}
