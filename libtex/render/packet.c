/* packet.c - a packet's textures looked up ahead, together: batched primitives, a map's
 * footprints and lookups in lanes */
#include <math.h>
#include <string.h>

#include "render/packet.h"
#include "render/x86/packet_x86.h"

/* The gradients g and scales of pm into lane l of fr (gw where solid) */
static void lane_mapping(struct frames *fr, int l, const tex_v3 g[3], const struct placement *pm,
                         int solid)
{
    for (int c = 0; c < 3; c++) {
        fr->gu[c][l] = (&g[0].x)[c], fr->gv[c][l] = (&g[1].x)[c];
        if (solid)
            fr->gw[c][l] = (&g[2].x)[c];
    }
    fr->su[l] = pm->su, fr->sv[l] = pm->sv;
}

/* The j-th texture sf applies */
static const struct tex_apply *apply_at(const struct tex_surface *sf, int j)
{
    const struct tex_apply *ap = sf->apply;
    while (j-- > 0)
        ap = ap->next;
    return ap;
}

/* The footprint of hit pf's texture j (mapping a) on the hit's own frame, as
 * apply_textures takes it: a band-limited solid's width (solid), else a map's
 * tex_footprint_width2 */
static double scalar_width(const struct tex_prefetch *pf, int j, const struct tex_prefetch_ap *a,
                           int solid)
{
    const struct tex_apply *ap = apply_at(pf->sf, j);
    const struct placement *pm = pf->sf->cache->placement + j;
    struct footprint fp;
    footprint_at(&fp, &pf->D, &pf->N, pf->width);
    return solid ? sqrt(tex_solid_width2(ap, pm, pf->leaf, &fp, &pf->P, &pf->pl, a->uvw0))
                 : tex_footprint_width2(ap, pm, pf->leaf, &fp, &pf->P, &pf->pl, a->face, a->uvw0[0],
                                    a->uvw0[1]);
}

/* The footprints fw of n pending points of one texture (hit[i], its texture number j[i]
 * there, or the first where j is NULL; mapping a[i]), as scalar_width makes them: 0
 * unfiltered; in vector lanes where the CPU has AVX2 those whose mapping has gradients
 * (affine, or a map's tex_point_gradient), but those seen head-on.  A map's (solid 0) also
 * gives, where lane is given, the lane of fr of each point (else -1) and, where bump, the
 * frames' bump members. */
static void batch_widths(int n, struct tex_prefetch *const *hit, struct tex_prefetch_ap *const *a,
                         const int *j, int solid, int bump, struct frames *fr, double *fw,
                         int *lane)
{
    for (int c = 0; c < 3; c++) /* the frames' rows: fr's own */
        fr->d[c] = fr->rows[c], fr->nn[c] = fr->rows[3 + c];
    fr->w = fr->rows[6];
    int level = tex_simd_level(), lanes = 0, at[CHUNK], affine = 0;
    int simd = level >= TEX_SIMD_AVX2, wide = level >= TEX_SIMD_AVX512 ? 8 : 4;
    /* the gradients' leaf and texture, kept while hits share them; lane 0's (leaf0, ap0) */
    const struct tex_object *leaf = NULL, *leaf0 = NULL;
    const struct tex_apply *gap = NULL, *ap = NULL, *ap0 = NULL;
    const struct tex_surface *sf = NULL; /* ap and pm's, kept while hits share them */
    const struct placement *pm = NULL, *pm0 = NULL;
    tex_v3 g[3], g0[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; /* g0, pm0: lane 0's */
    tex_v3 pg[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; /* a point's own (tex_point_gradient) */
    for (int i = 0, jk = -1; i < n; i++) {
        const struct tex_prefetch *pf = hit[i];
        int ji = j ? j[i] : 0; /* the point's texture number at its hit */
        if (pf->sf != sf || ji != jk) {
            sf = pf->sf, jk = ji;
            ap = apply_at(sf, jk), pm = sf->cache->placement + jk;
        }
        fw[i] = 0;
        if (lane)
            lane[i] = -1;
        if (!(pf->width > 0))
            continue;
        if (simd && (pf->leaf != leaf || ap != gap))
            affine = map_gradient(gap = ap, leaf = pf->leaf, g);
        /* own: a mapping that is not affine, its gradients the point's own */
        int own = simd && !affine && !solid && tex_point_gradient(ap, leaf, &pf->pl, a[i]->face, pg);
        if (!simd || (!affine && !own)) {
            fw[i] = scalar_width(pf, ji, a[i], solid);
            continue;
        }
        const double *d = &pf->D.x, *nn = &pf->N.x;
        for (int c = 0; c < 3; c++)
            fr->rows[c][lanes] = d[c], fr->rows[3 + c][lanes] = nn[c];
        fr->rows[6][lanes] = pf->width;
        if (!lanes) { /* lane 0's mapping, which the lanes share until one differs */
            fr->shared = !own, leaf0 = leaf, ap0 = gap, pm0 = pm;
            memcpy(g0, g, sizeof g0);
        } else if (fr->shared && (own || leaf != leaf0 || gap != ap0)) {
            for (int k = fr->shared = 0; k < lanes; k++) /* no longer shared: written out */
                lane_mapping(fr, k, g0, pm0, solid);
        }
        if (!lanes || !fr->shared)
            lane_mapping(fr, lanes, own ? pg : g, pm, solid);
        at[lanes++] = i;
    }
#ifdef TEX_X86
    double lw[CHUNK];
    for (int l = 0; l < lanes; l += wide) {
        int m = lanes - l < wide ? lanes - l : wide;
        unsigned headon = wide == 4 ? solid ? tex_solid_footprints4_avx2(fr, l, m, lw)
                                            : tex_footprints4_avx2(fr, l, m, bump, lw)
                          : solid   ? tex_solid_footprints8_avx512(fr, l, m, lw)
                                    : tex_footprints8_avx512(fr, l, m, bump, lw);
        for (int k = l; k < l + m; k++) {
            int on = !(headon >> (k - l) & 1), i = at[k];
            fw[i] = on ? lw[k] : scalar_width(hit[i], j ? j[i] : 0, a[i], solid);
            if (lane)
                lane[i] = on ? k : -1;
        }
    }
#endif
}

/* bump_tilt's direction (before its strength) from a map's gradient grad and the footprint
 * in lane l of fr */
static void lane_tilt(const struct frames *fr, int l, const double grad[2], double tilt[3])
{
    double du[2] = {fr->du[0][l], fr->du[1][l]}, dv[2] = {fr->dv[0][l], fr->dv[1][l]};
    double g[2] = {0, 0}; /* made from grad (tex_tilt_along) */
    tex_v3 e1 = tex_v3_make(fr->e1[0][l], fr->e1[1][l], fr->e1[2][l]);
    tex_v3 e2 = tex_v3_make(fr->e2[0][l], fr->e2[1][l], fr->e2[2][l]);
    tex_v3 d = tex_tilt_along(grad, du, dv, g, e1, e2);
    tilt[0] = d.x, tilt[1] = d.y, tilt[2] = d.z;
}

/* A map's lookup into the record a of its point: the value val (RGB), the footprint fw2 and,
 * where bumped, the gradient grad and, where the footprint was made in lane l of fr (else
 * l < 0), the tilt's direction */
static void lookup_record(struct tex_prefetch_ap *a, const float val[3], double fw2,
                          const double *grad, const struct frames *fr, int l)
{
    memcpy(a->val, val, 3 * sizeof *val);
    if (grad)
        a->grad[0] = grad[0], a->grad[1] = grad[1];
    if (grad && l >= 0)
        lane_tilt(fr, l, grad, a->tilt);
    a->has_tilt = grad && l >= 0;
    a->fw = fw2;
    a->has_val = 1;
}

/* The values of n pending points a[i] of mip-mapped texture t (hits hit[i], placed at u, v)
 * and their footprints, as apply_textures would look them up: into a[i]->val as RGB, the
 * footprint (squared) into a[i]->fw; bumped, the gradient and (from the lanes) the tilt's
 * direction. */
static void map_batch(const struct tex_texture *t, int n, struct tex_prefetch *const *hit,
                      struct tex_prefetch_ap *const *a, const double *u, const double *v)
{
    struct frames fr;
    double fw2[CHUNK], grad[2 * CHUNK], *gp = NULL;
    float out[3 * CHUNK];
    int lane[CHUNK];
    for (int i = 0; i < n && !gp; i++)
        if (a[i]->bump) /* then every point's gradient */
            gp = grad;
    batch_widths(n, hit, a, NULL, 0, gp != NULL, &fr, fw2, lane);
    tex_texture_points(t, n, u, v, fw2, out, gp);
    for (int i = 0; i < n; i++)
        lookup_record(a[i], out + 3 * i, fw2[i], gp ? gp + 2 * i : NULL, &fr, lane[i]);
}

void tex_prefetch_map(struct tex_prefetch *pf, const struct tex_surface *sf,
                      const struct tex_object *leaf, const tex_v3 *P)
{
    const struct placement *pm = sf->cache->placement;
    pf->sf = sf;
    pf->n = 0;
    pf->width = 0;
    if (!sf->apply) /* untextured: nothing to look up */
        return;
    pf->leaf = leaf;
    pf->P = *P;
    pf->pl = tex_xform_point(&leaf->to_obj, *P);
    for (const struct tex_apply *ap = sf->apply; ap && pf->n < TEX_PREFETCH_MAX;
         ap = ap->next, pm++) {
        struct tex_prefetch_ap *a = &pf->ap[pf->n++];
        map_hit(ap, pm, leaf, P, &pf->pl, a);
        /* the first texture only: a later one may find the footprint's tangents normalised
         * by an earlier one (footprint_unit), which the batch does not follow */
        if (pf->n == 1 && map_ahead(ap))
            a->pending = a->inside;
    }
}

/* Whether the lanes map hits of ap on leaf: a plane's planar mapping, or (AVX-512) a natural
 * one on a box, cylinder, cone or sphere (asked of a queue's first hit: the others share its
 * leaf and surface) */
static int lanes_mapping(const struct tex_apply *ap, const struct tex_object *leaf)
{
    int k = leaf->kind, level = tex_simd_level(); /* the level in use, not the cache's */
    int natural = ap->mapping == TEX_MAP_NATURAL && !(ap->size[0] > 0) && /* lanes: unsized */
                  level >= TEX_SIMD_AVX512;
    return (level >= TEX_SIMD_AVX2 && plane_planar(ap, leaf)) ||
           (natural && (k == TEX_SHAPE_BOX || k == TEX_SHAPE_CYLINDER || k == TEX_SHAPE_CONE ||
                        k == TEX_SHAPE_SPHERE));
}

int tex_lanes_take(struct tex_lanes *L, struct tex_prefetch *pf, const struct tex_surface *sf,
                   const struct tex_object *leaf, const tex_v3 *P, const tex_v3 *D,
                   const tex_v3 *N, double width)
{
    if (!sf->cache->lanes || !(width > 0) || L->n == TEX_LANES ||
        (L->n ? L->leaf != leaf || L->sf != sf : !lanes_mapping(sf->apply, leaf)))
        return 0;
    int i = L->n++;
    L->sf = sf, L->leaf = leaf, L->pf[i] = pf;
    L->p[0][i] = P->x, L->p[1][i] = P->y, L->p[2][i] = P->z;
    L->d[0][i] = D->x, L->d[1][i] = D->y, L->d[2][i] = D->z;
    L->nn[0][i] = N->x, L->nn[1][i] = N->y, L->nn[2][i] = N->z;
    L->w[i] = width;
    return 1;
}

/* Queued hit i of L, which the lanes could not finish, mapped the usual way */
static void lanes_leftover(const struct tex_lanes *L, int i)
{
    tex_v3 P = tex_v3_make(L->p[0][i], L->p[1][i], L->p[2][i]);
    tex_v3 D = tex_v3_make(L->d[0][i], L->d[1][i], L->d[2][i]);
    tex_v3 N = tex_v3_make(L->nn[0][i], L->nn[1][i], L->nn[2][i]);
    tex_prefetch_map(L->pf[i], L->sf, L->leaf, &P);
    tex_prefetch_footprints(L->pf[i], &D, &N, L->w[i]);
}

#ifdef TEX_X86
/* Record pf of a hit the lanes finished, in lane l of fr: map_hit's fields (face: the
 * mapping's), then the lookup's (grad: a bump's gradient, else NULL) */
static void lanes_record(const struct tex_lanes *L, struct tex_prefetch *pf, int face,
                         double u0, double v0, double u, double v, double fw2,
                         const float val[3], const struct frames *fr, int l, const double *grad)
{
    struct tex_prefetch_ap *a = &pf->ap[0];
    pf->sf = L->sf, pf->leaf = L->leaf, pf->n = 1;
    a->tex = L->sf->apply->tex;
    a->face = face, a->inside = 1, a->pending = 0;
    a->bump = L->sf->cache->placement[0].bump;
    a->uvw0[0] = u0, a->uvw0[1] = v0, a->uvw0[2] = 0;
    a->uvw[0] = u, a->uvw[1] = v, a->uvw[2] = 0;
    lookup_record(a, val, fw2, grad, fr, l);
}
#endif

int tex_prefetch_lanes(struct tex_lanes *L, struct tex_prefetch **rest)
{
    int n = L->n, nrest = 0;
    L->n = 0;
    if (!n)
        return 0;
#ifdef TEX_X86
    struct frames fr;
    /* u, v and fw2: the finished hits' moved to the front, at[] giving their lanes (set to 0
     * first: gcc cannot follow the masked stores that fill them) */
    double u0[TEX_LANES], v0[TEX_LANES], u[TEX_LANES] = {0}, v[TEX_LANES] = {0};
    double fw2[TEX_LANES] = {0};
    float out[3 * TEX_LANES];
    int at[TEX_LANES], m = 0, bump = L->sf->cache->placement[0].bump;
    int face[TEX_LANES], natural = L->leaf->kind != TEX_SHAPE_PLANE;
    double grad[2 * TEX_LANES];
    tex_v3 g[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    _Static_assert(TEX_LANES <= CHUNK, "a struct frames holds the lanes");
    for (int c = 0; c < 3; c++)
        fr.d[c] = L->d[c], fr.nn[c] = L->nn[c];
    fr.w = L->w;
    fr.shared = !natural; /* a plane's mapping is affine: every lane shares lane 0's */
    if (!natural) {
        map_gradient(L->sf->apply, L->leaf, g);
        lane_mapping(&fr, 0, g, L->sf->cache->placement, 0);
    }
    int wide = tex_simd_level() >= TEX_SIMD_AVX512 ? 8 : 4; /* AVX2: a plane's alone */
    for (int i = 0; i < n; i += wide) {
        int k = n - i < wide ? n - i : wide;
        unsigned inside = wide == 4 ? tex_plane_map4_avx2(L, i, k, u0, v0, u, v)
                          : natural ? tex_natural_map8_avx512(L, i, k, u0, v0, u, v, face, &fr)
                                    : tex_plane_map8_avx512(L, i, k, u0, v0, u, v);
        unsigned done = inside & ~(wide == 4 ? tex_footprints4_avx2(&fr, i, k, bump, fw2)
                                             : tex_footprints8_avx512(&fr, i, k, bump, fw2));
        for (int j = i; j < i + k; j++) {
            if (done >> (j - i) & 1)
                u[m] = u[j], v[m] = v[j], fw2[m] = fw2[j], at[m++] = j;
            else
                lanes_leftover(L, j), rest[nrest++] = L->pf[j];
        }
    }
    tex_texture_points(L->sf->apply->tex, m, u, v, fw2, out, bump ? grad : NULL);
    for (int q = 0; q < m; q++)
        lanes_record(L, L->pf[at[q]], natural ? face[at[q]] : 1, u0[at[q]], v0[at[q]], u[q],
                     v[q], fw2[q], out + 3 * q, &fr, at[q], bump ? grad + 2 * q : NULL);
#else
    for (int i = 0; i < n; i++)
        lanes_leftover(L, i), rest[nrest++] = L->pf[i];
#endif
    return nrest;
}

int tex_surface_footprints(const struct tex_surface *sf)
{
    return sf->cache->footprints;
}

void tex_prefetch_footprints(struct tex_prefetch *pf, const tex_v3 *D, const tex_v3 *N,
                             double width)
{
    if (width > 0) /* the frame of the footprints tex_prefetch_eval makes, on apply_textures' N */
        pf->D = *D, pf->N = *N, pf->width = width;
}

void tex_prefetch_eval(struct tex_prefetch *const *pf, int n)
{
    double u[CHUNK], v[CHUNK], w[CHUNK], fw[CHUNK]; /* fw: band-limited solids' footprints */
    float out[CHUNK * TEX_MAP_MAX_CHANNELS];
    struct frames fr;
    struct tex_prefetch_ap *who[CHUNK];
    struct tex_prefetch *hit[CHUNK];
    int at[CHUNK]; /* the point's texture number at its hit */
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < pf[i]->n; j++) {
            if (!pf[i]->ap[j].pending)
                continue;
            /* every pending point of this primitive from here on, up to a chunk */
            const struct tex_texture *t = pf[i]->ap[j].tex;
            int m = 0;
            for (int k = i; k < n && m < CHUNK; k++) {
                for (int l = k == i ? j : 0; l < pf[k]->n && m < CHUNK; l++) {
                    struct tex_prefetch_ap *b = &pf[k]->ap[l];
                    if (!b->pending || b->tex != t)
                        continue;
                    b->pending = 0;
                    who[m] = b, hit[m] = pf[k], at[m] = l;
                    u[m] = b->uvw[0], v[m] = b->uvw[1], w[m] = b->uvw[2], fw[m] = 0;
                    m++;
                }
            }
            if (t->mip) {
                map_batch(t, m, hit, who, u, v);
                continue;
            }
            if (band_limited(t))
                batch_widths(m, hit, who, at, 1, 0, &fr, fw, NULL);
            tex_field_points(t, m, u, v, w, fw, out);
            int nc = t->field->nc;
            for (int q = 0; q < m; q++) {
                memset(who[q]->val, 0, sizeof who[q]->val);
                memcpy(who[q]->val, out + (size_t)q * nc, nc * sizeof *out);
                who[q]->has_val = 1;
            }
        }
    }
}
