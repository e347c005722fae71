/* compose.c - per-pixel operators, cascades, tiling, warping, blur */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "base/error.h"
#include "base/param.h"
#include "ops/filter.h"

static const char *const op_names[TEX_OP_COUNT] = {
    "add", "sub", "mul", "div", "min", "max", "mix", "abs", "invert", "threshold",
    "over", "under", "and", "or", "xor"};

int tex_op_find(const char *name)
{
    for (int i = 0; i < TEX_OP_COUNT; i++)
        if (!strcmp(name, op_names[i]))
            return i;
    char near[32];
    if (tex_choice_nearest(tex_op_names(), name, near, sizeof near))
        return tex_usage_error("unknown operator '%s'; did you mean %s? (valid: %s)", name, near,
                               tex_op_names());
    return tex_usage_error("unknown operator '%s' (valid: %s)", name, tex_op_names());
}

const char *tex_op_name(enum tex_op op)
{
    return op >= 0 && op < TEX_OP_COUNT ? op_names[op] : "?";
}

const char *tex_op_names(void)
{
    return "add|sub|mul|div|min|max|mix|abs|invert|threshold|over|under|and|or|xor";
}

int tex_op_arity(enum tex_op op)
{
    return op == TEX_OP_MIX ? 3 : op == TEX_OP_ABS || op == TEX_OP_INVERT || op == TEX_OP_THRESHOLD
                                      ? 1 : 2;
}

int tex_operand_parse(const char *text, struct tex_operand *o)
{
    const char *s = text;
    char buf[64];

    memset(o, 0, sizeof *o);
    while (*s) {
        size_t n = strcspn(s, ",");
        double v;
        if (o->nc == 4 || n == 0 || n >= sizeof buf)
            return -1;
        memcpy(buf, s, n);
        buf[n] = '\0';
        if (tex_parse_real(buf, &v) < 0 || fabs(v) > 3e38)
            return -1;
        o->c[o->nc++] = (float)v;
        s += n;
        if (*s == ',' && !*++s)
            return -1;
    }
    if (o->nc == 0 || o->nc == 2)
        return -1;
    return 0;
}

static int operand_nc(const struct tex_operand *o)
{
    return o->map ? o->map->nc : o->nc;
}

/* Channel c of operand o at pixel i, seen with `nc` channels. */
static inline float val(const struct tex_operand *o, size_t i, int c, int nc)
{
    int onc = o->map ? o->map->nc : o->nc;
    const float *p = o->map ? o->map->px + i * onc : o->c;

    if (nc == 4 && c == 3)
        return onc == 4 ? p[3] : 1.0f;
    return onc == 1 ? p[0] : p[c];
}

/* Channel c of operand o as val() sees it with nc channels, for every pixel i at
 * base[i * *step]: the branches of val() taken once, not per sample. */
static const float *val_run(const struct tex_operand *o, int c, int nc, size_t *step)
{
    static const float one = 1.0f;
    int onc = o->map ? o->map->nc : o->nc;
    const float *p = o->map ? o->map->px : o->c;

    *step = o->map ? (size_t)onc : 0;
    if (nc == 4 && c == 3 && onc != 4) {
        *step = 0;
        return &one;
    }
    return onc == 1 ? p : p + c;
}

/* The channels of the result, or -1 if the operands do not combine. */
static int combine_nc(const struct tex_operand *const *ops, int n)
{
    int nc = 1;

    for (int k = 0; k < n; k++)
        if (ops[k] && operand_nc(ops[k]) > nc)
            nc = operand_nc(ops[k]);
    for (int k = 0; k < n; k++) {
        int c = ops[k] ? operand_nc(ops[k]) : nc;
        if (!(c == 1 || c == nc || (c == 3 && nc == 4)))
            return -1;
    }
    return nc;
}

static inline float bit(float x, float t)
{
    return x >= t ? 1.0f : 0.0f;
}

/* The map whose size the nops operands share, and their channels into *nc: NULL with a
 * usage error when one is missing, sizes differ, none is a map or channels do not combine. */
static const tex_map *operands_size(enum tex_op op, const struct tex_operand *const *ops,
                                    int nops, int *nc)
{
    const tex_map *size = NULL;
    for (int k = 0; k < nops; k++) {
        if (!ops[k])
            return tex_usage_error("%s needs %d operands", op_names[op], nops), NULL;
        if (!ops[k]->map)
            continue;
        if (!size)
            size = ops[k]->map;
        else if (ops[k]->map->w != size->w || ops[k]->map->h != size->h)
            return tex_usage_error("%s: operand %d is %dx%d but operand 1 is %dx%d (use "
                                   "--resize)", op_names[op], k + 1, ops[k]->map->w,
                                   ops[k]->map->h, size->w, size->h), NULL;
    }
    if (!size)
        return tex_usage_error("%s: at least one operand must be a map", op_names[op]), NULL;
    if ((*nc = combine_nc(ops, nops)) < 0)
        return tex_usage_error("%s: operands of %d, %d%s channels do not combine (1 broadcasts, "
                               "3 meets 4 as opaque)", op_names[op], operand_nc(ops[0]),
                               nops > 1 ? operand_nc(ops[1]) : 0, nops > 2 ? " and more" : ""),
               NULL;
    return size;
}

/* mix, add, sub and mul into r (n pixels, r->nc channels) a channel at a time, each
 * operand's broadcast found once a channel; an RGBA result's alpha is a's but in mix, whose
 * every channel mixes */
static void channel_runs(enum tex_op op, const struct tex_operand *const *ops, tex_map *r,
                         size_t n)
{
    int nc = r->nc;
    size_t st[3][4];
    const float *p[3][4];
    for (int k = 0; k < (op == TEX_OP_MIX ? 3 : 2); k++)
        for (int c = 0; c < nc; c++)
            p[k][c] = val_run(ops[k], c, nc, &st[k][c]);
#pragma omp parallel
    for (int c = 0; c < nc; c++) {
        const float *pa = p[0][c], *pb = p[1][c], *pw = p[2][c];
        size_t sa = st[0][c], sb = st[1][c], sw = op == TEX_OP_MIX ? st[2][c] : 0;
        float *d = r->px + c;
        enum tex_op cop = nc == 4 && c == 3 && op != TEX_OP_MIX ? TEX_OP_COUNT : op;
#define CHANNEL_RUN(z)                                                                         \
    _Pragma("omp for schedule(static) nowait") for (size_t i = 0; i < n; i++)                   \
    {                                                                                          \
        float x = pa[i * sa], y = pb[i * sb];                                                  \
        (void)y;                                                                               \
        d[i * nc] = (z);                                                                       \
    }
        switch (cop) {
        case TEX_OP_MIX: CHANNEL_RUN(x + (y - x) * pw[i * sw]) break;
        case TEX_OP_ADD: CHANNEL_RUN(x + y) break;
        case TEX_OP_SUB: CHANNEL_RUN(x - y) break;
        case TEX_OP_MUL: CHANNEL_RUN(x * y) break;
        default: CHANNEL_RUN(x) break;
        }
#undef CHANNEL_RUN
    }
}

tex_map *tex_op_apply(enum tex_op op, const struct tex_operand *a, const struct tex_operand *b,
                      const struct tex_operand *w, double t)
{
    const struct tex_operand *ops[3] = {a, b, w};
    const tex_map *size;
    int nops = tex_op_arity(op), nc;
    float ft = (float)t;
    tex_map *r;
    size_t n;

    if (op < 0 || op >= TEX_OP_COUNT)
        return tex_usage_error("unknown operator"), NULL;
    if (op == TEX_OP_THRESHOLD && b)
        nops = 2;
    if (!(size = operands_size(op, ops, nops, &nc)))
        return NULL;
    if (!(r = tex_map_new_unset(size->w, size->h, nc))) /* every sample is set below */
        return NULL;
    if (a->map && a->map->history && tex_map_set_history(r, a->map->history) < 0) {
        tex_map_free(r);
        return NULL;
    }
    n = (size_t)size->w * size->h;
    if (op == TEX_OP_MIX || op == TEX_OP_ADD || op == TEX_OP_SUB || op == TEX_OP_MUL) {
        channel_runs(op, ops, r, n);
        return r;
    }
    /* Colour channels: all but the alpha of RGBA. */
    int ncol = nc == 4 ? 3 : nc;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        float *d = r->px + i * nc;
        if (op == TEX_OP_OVER || op == TEX_OP_UNDER) {
            const struct tex_operand *top = op == TEX_OP_OVER ? a : b;
            const struct tex_operand *bot = op == TEX_OP_OVER ? b : a;
            float k = nc == 4 ? 1.0f - val(top, i, 3, 4) : 0.0f;
            for (int c = 0; c < nc; c++)
                d[c] = val(top, i, c, nc) + val(bot, i, c, nc) * k;
            continue;
        }
        for (int c = 0; c < ncol; c++) {
            float x = val(a, i, c, nc), y = nops > 1 ? val(b, i, c, nc) : 0.0f, z;
            switch (op) {
            case TEX_OP_ADD: z = x + y; break;
            case TEX_OP_SUB: z = x - y; break;
            case TEX_OP_MUL: z = x * y; break;
            case TEX_OP_DIV: z = y != 0.0f ? x / y : 0.0f; break;
            case TEX_OP_MIN: z = fminf(x, y); break;
            case TEX_OP_MAX: z = fmaxf(x, y); break;
            case TEX_OP_ABS: z = fabsf(x); break;
            case TEX_OP_INVERT: z = (nc == 4 ? val(a, i, 3, 4) : 1.0f) - x; break;
            case TEX_OP_THRESHOLD: z = bit(x, nops > 1 ? y : ft); break;
            case TEX_OP_AND: z = bit(x, ft) * bit(y, ft); break;
            case TEX_OP_OR: z = fmaxf(bit(x, ft), bit(y, ft)); break;
            case TEX_OP_XOR: z = bit(x, ft) != bit(y, ft) ? 1.0f : 0.0f; break;
            default: z = 0.0f; break;
            }
            d[c] = z;
        }
        if (nc == 4)
            d[3] = val(a, i, 3, 4);
    }
    return r;
}

tex_map *tex_fit(const tex_map *m, int w, int h, enum tex_fit fit, const char *what)
{
    static const double id[6] = {1, 0, 0, 0, 1, 0};

    if (m->w == w && m->h == h)
        return tex_map_clone(m);
    switch (fit) {
    case TEX_FIT_SCALE: return tex_resize(m, w, h);
    case TEX_FIT_TILE: return tex_affine(m, w, h, id, TEX_EDGE_WRAP, NULL);
    default:
        return tex_usage_error("%s is %dx%d but the result is %dx%d (use --resize scale|tile)",
                               what, m->w, m->h, w, h), NULL;
    }
}

/* ---- cascade ---- */

tex_map *tex_cascade(const tex_map *ids, int nregions, const tex_map *const *maps,
                     const float def[4])
{
    int nc = 1, has2 = 0;
    float d4[4];
    struct tex_operand dop = {NULL, 4, {0}};
    tex_map *r;
    size_t n = (size_t)ids->w * ids->h;

    if (ids->nc != 1)
        return tex_usage_error("the region-id map must have 1 channel (it has %d)", ids->nc), NULL;
    for (int k = 1; k <= nregions; k++) {
        if (!maps[k])
            continue;
        if (maps[k]->w != ids->w || maps[k]->h != ids->h)
            return tex_usage_error("the map of region %d is %dx%d but the ids are %dx%d (use "
                                   "--resize)", k, maps[k]->w, maps[k]->h, ids->w, ids->h), NULL;
        has2 |= maps[k]->nc == 2;
        if (maps[k]->nc > nc)
            nc = maps[k]->nc;
    }
    if (def[3] < 1.0f)
        nc = 4;
    else if ((def[0] != def[1] || def[1] != def[2]) && nc < 3)
        nc = 3;
    if (has2 && nc != 2)
        return tex_usage_error("2-channel region maps do not combine with colours"), NULL;
    /* The default as a premultiplied constant operand. */
    d4[0] = def[0] * def[3];
    d4[1] = def[1] * def[3];
    d4[2] = def[2] * def[3];
    d4[3] = def[3];
    memcpy(dop.c, d4, sizeof d4);
    if (!(r = tex_map_new(ids->w, ids->h, nc)))
        return NULL;
    if (ids->history && tex_map_set_history(r, ids->history) < 0) {
        tex_map_free(r);
        return NULL;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        float id = ids->px[i];
        int k = id >= 0.5f && id < nregions + 0.5f ? (int)lrintf(id) : 0;
        struct tex_operand o = {k ? maps[k] : NULL, 0, {0}};
        const struct tex_operand *src = o.map ? &o : &dop;
        for (int c = 0; c < nc; c++)
            r->px[i * nc + c] = val(src, src == &dop ? 0 : i, c, nc);
    }
    return r;
}

/* ---- tiling and the matrix of maps ---- */

static int rule_pick(enum tex_rule rule, int cu, int cv, int nu, int n)
{
    switch (rule) {
    case TEX_RULE_DIAGONAL: return cu == cv ? 0 : 1 % n;
    case TEX_RULE_CHECKER: return (cu + cv) % n;
    case TEX_RULE_ROWS: return cv % n;
    case TEX_RULE_COLUMNS: return cu % n;
    default: return (int)(((long long)cv * nu + cu) % n);
    }
}

tex_map *tex_tile(const tex_map *const *maps, int nmaps, enum tex_rule rule, int nu, int nv,
                  int mirror, int w, int h)
{
    int nc = 1, failed = 0;
    tex_map **conv, *r;
    struct tex_sampler *s;

    if (nmaps < 1 || nu < 1 || nv < 1)
        return tex_usage_error("tiling needs at least one map and nu, nv >= 1"), NULL;
    for (int k = 0; k < nmaps; k++)
        if (maps[k]->nc > nc)
            nc = maps[k]->nc;
    if (!(r = tex_map_new(w, h, nc)))
        return NULL;
    conv = calloc(nmaps, sizeof *conv);
    s = calloc(nmaps, sizeof *s);
    if (!conv || !s) {
        tex_error("out of memory");
        failed = 1;
    }
    for (int k = 0; k < nmaps && !failed; k++) {
        const tex_map *m = maps[k];
        if (m->nc != nc && !(m = conv[k] = tex_map_channels(m, nc)))
            failed = 1;
        else
            tex_sampler_init(&s[k], m, mirror ? TEX_EDGE_MIRROR : TEX_EDGE_WRAP, NULL);
    }
    if (!failed) {
        r->subregions = nmaps == 1 ? maps[0]->subregions : 0;
        if (maps[0]->history && tex_map_set_history(r, maps[0]->history) < 0)
            failed = 1;
    }
    if (!failed) {
#pragma omp parallel for schedule(dynamic, 4)
        for (int y = 0; y < h; y++) {
            double V = (y + 0.5) / h * nv;
            int cv = V < nv ? (int)V : nv - 1;
            double fv = V - cv;
            if (mirror && (cv & 1))
                fv = 1.0 - fv;
            for (int x = 0; x < w; x++) {
                double U = (x + 0.5) / w * nu;
                int cu = U < nu ? (int)U : nu - 1;
                double fu = U - cu;
                int k = rule_pick(rule, cu, cv, nu, nmaps);
                const tex_map *m = s[k].m;
                double du[2] = {(double)nu * m->w / w, 0}, dv[2] = {0, (double)nv * m->h / h};
                if (mirror && (cu & 1))
                    fu = 1.0 - fu;
                tex_sample(&s[k], fu * m->w, fv * m->h, du, dv, tex_map_px(r, x, y));
            }
        }
    }
    for (int k = 0; conv && k < nmaps; k++)
        tex_map_free(conv[k]);
    free(conv);
    free(s);
    if (failed) {
        tex_map_free(r);
        return NULL;
    }
    return r;
}

/* ---- domain perturbation ---- */

/* The displacement (in texture units, before the amount) at row y: sb samples BY for the
 * first lookup, sb2 for the isotropic's second (half a map away: a band of its own). */
static void warp_row(const struct tex_sampler *sb, const struct tex_sampler *sb2,
                     const struct tex_warp_opts *o, int w, int h, int y, double *d)
{
    int bw = sb->m->w, bh = sb->rows, bnc = sb->m->nc;
    double du[2] = {(double)bw / w, 0}, dv[2] = {0, (double)bh / h};
    double ca = cos(o->angle * M_PI / 180.0), sa = sin(o->angle * M_PI / 180.0);
    float v[4], v2[4];

    for (int x = 0; x <= w; x++) {
        double u = (x + 0.5) / w, vv = (y + 0.5) / h;
        tex_sample(sb, u * bw, vv * bh, du, dv, v);
        if (bnc >= 2) {
            d[2 * x] = v[0] - o->centre;
            d[2 * x + 1] = v[1] - o->centre;
        } else if (o->isotropic) {
            tex_sample(sb2, (u + 0.5) * bw, (vv + 0.5) * bh, du, dv, v2);
            d[2 * x] = v[0] - o->centre;
            d[2 * x + 1] = v2[0] - o->centre;
        } else {
            d[2 * x] = (v[0] - o->centre) * ca;
            d[2 * x + 1] = -(v[0] - o->centre) * sa;
        }
    }
}

tex_map *tex_warp(const tex_map *m, const tex_map *by, const struct tex_warp_opts *o, int w,
                  int h)
{
    struct tex_map_rows mr = {m, 0, m->h}, br = {by, 0, by->h};
    tex_map *r;

    if (!(r = tex_map_new(w, h, m->nc)))
        return NULL;
    r->subregions = m->subregions;
    if ((m->history && tex_map_set_history(r, m->history) < 0) ||
        tex_warp_rows(mr, br, br, o, r, 0, h) < 0) {
        tex_map_free(r);
        return NULL;
    }
    return r;
}

int tex_warp_rows(struct tex_map_rows m, struct tex_map_rows by, struct tex_map_rows by2,
                  const struct tex_warp_opts *o, tex_map *out, int y0, int h)
{
    struct tex_sampler sm, sb, sb2;
    int failed = 0, w = out->w, mw = m.band->w, mh = m.full_h;

    if (!isfinite(o->amount) || !isfinite(o->centre) || !isfinite(o->angle))
        return tex_usage_error("warp parameters must be finite");
    tex_sampler_init(&sm, m.band, o->edge, NULL);
    tex_sampler_init(&sb, by.band, TEX_EDGE_WRAP, NULL);
    tex_sampler_init(&sb2, by2.band, TEX_EDGE_WRAP, NULL);
    sm.row0 = m.row0, sm.rows = mh;
    sb.row0 = by.row0, sb.rows = by.full_h, sb2.row0 = by2.row0, sb2.rows = by2.full_h;
    sb.nearest = sb2.nearest = 0;
#pragma omp parallel
    {
        /* This row's displacements and the next row's, one extra column:
         * their differences give each pixel's footprint in m.  The next
         * row's become the following row's own when a thread takes
         * consecutive rows (the 4 of a chunk), so most rows cost one. */
        double *buf = malloc(4 * sizeof *buf * (w + 1)), *d0 = buf,
               *d1 = buf ? buf + 2 * (w + 1) : NULL;
        int next = -1; /* the row d1 holds */
        if (!buf) {
#pragma omp atomic write
            failed = 1;
        }
#pragma omp for schedule(dynamic, 4)
        for (int y = y0; y < y0 + out->h; y++) {
            if (!buf)
                continue;
            if (y == next) {
                double *t = d0;
                d0 = d1;
                d1 = t;
            } else
                warp_row(&sb, &sb2, o, w, h, y, d0);
            warp_row(&sb, &sb2, o, w, h, y + 1, d1);
            next = y + 1;
            for (int x = 0; x < w; x++) {
                double u = (x + 0.5) / w + o->amount * d0[2 * x];
                double v = (y + 0.5) / h + o->amount * d0[2 * x + 1];
                double du[2] = {mw * (1.0 / w + o->amount * (d0[2 * x + 2] - d0[2 * x])),
                                mh * o->amount * (d0[2 * x + 3] - d0[2 * x + 1])};
                double dv[2] = {mw * o->amount * (d1[2 * x] - d0[2 * x]),
                                mh * (1.0 / h + o->amount * (d1[2 * x + 1] - d0[2 * x + 1]))};
                tex_sample(&sm, u * mw, v * mh, du, dv, tex_map_px(out, x, y - y0));
            }
        }
        free(buf);
    }
    if (failed)
        return tex_error("out of memory");
    return 0;
}

/* floor(x) as a row index, or -1 (with *bad set) past what a row index can be */
static long row_floor(double x, int *bad)
{
    if (!(x > -1e12 && x < 1e12)) {
        *bad = 1;
        return 0;
    }
    return (long)floor(x);
}

int tex_warp_reads(const struct tex_warp_opts *o, int bnc, const double lo[4],
                   const double hi[4], int bh, int mh, int h, int y, int n,
                   struct tex_warp_reach *r)
{
    /* BY: row r's lookups at (r + 0.5) bh / h (and bh / 2 below for the second), spread
     * over bh / h rows, for rows y..y+n (the last row's footprint takes the next row's);
     * a bilinear lookup at Y reads rows floor(Y - 0.5) and the one below.  Two rows more
     * each side for the rounding of the lookups' arithmetic. */
    double s = (double)bh / h, top = y * s, end = (y + n + 1) * s;
    int c = bnc >= 2 ? 1 : 0, bad = 0;
    r->by[0] = row_floor(top - 0.5, &bad) - 2;
    r->by[1] = row_floor(end - 0.5, &bad) + 4;
    r->by2[0] = row_floor(top + 0.5 * bh - 0.5, &bad) - 2;
    r->by2[1] = row_floor(end + 0.5 * bh - 0.5, &bad) + 4;
    /* M: d_v, BY's channel c less the neutral value (times -sin angle for a push along
     * the angle), lies within [L, H], widened for the float sums of a filtered lookup.  A
     * tap of the footprint's grid looks up v + amount ((1-a-b) d + a d_right + b d_below)
     * + b / h, |a|, |b| < 1/2: weights of sum 1, the positive ones below 2 in all and
     * the negative ones above -1, so within amount [L - R, H + R] (R = H - L), and half
     * a row of the output either side of the row's own v. */
    double eps = 1e-4 * fmax(fabs(lo[c]), fabs(hi[c])), L = lo[c] - eps - o->centre,
           H = hi[c] + eps - o->centre;
    if (bnc == 1 && !o->isotropic) {
        double sa = sin(o->angle * M_PI / 180.0), a = -L * sa, b = -H * sa;
        L = fmin(a, b), H = fmax(a, b);
    }
    double R = H - L, dlo = o->amount * (L - R), dhi = o->amount * (H + R);
    if (dlo > dhi) {
        double t = dlo;
        dlo = dhi, dhi = t;
    }
    r->m[0] = row_floor(mh * ((double)y / h + dlo) - 0.5, &bad) - 2;
    r->m[1] = row_floor(mh * ((double)(y + n) / h + dhi) - 0.5, &bad) + 4;
    return bad || !isfinite(R) ? -1 : 0;
}

/* ---- blur ---- */

tex_map *tex_blur(const tex_map *m, double sigma)
{
    if (!(sigma >= 0 && sigma <= TEX_BLUR_MAX))
        return tex_usage_error("blur radius must be 0..%d (got %g)", TEX_BLUR_MAX, sigma), NULL;
    return sigma == 0 ? tex_map_clone(m) : tex_filter_gaussian(m, sigma, TEX_EDGE_CLAMP);
}
