/* matdb.c - the materials database */
#include "render/matdb.h"

#include "base/error.h"
#include "base/names.h"
#include "io/file.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct pending {
    struct tex_matdb_entry mat;
    int form; /* 0 none, 1 ior, 2 cauchy, 3 sellmeier, 4 nk */
    double c[6];
    int nrows, cap;
    double *wl, *n, *k;
    int mcap;               /* room in db->m */
    struct tex_names names; /* the names so far */
};

void tex_matdb_free(struct tex_matdb *db)
{
    for (int i = 0; i < db->count; i++)
        free(db->m[i].source);
    free(db->m);
    db->m = NULL;
    db->count = 0;
}

static int read_numbers(char *p, double *v, int max, int *count)
{
    int n = 0;
    for (;;) {
        while (isspace((unsigned char)*p))
            p++;
        if (!*p || *p == '#')
            break;
        if (n == max)
            return -1;
        char *e;
        errno = 0;
        v[n] = strtod(p, &e);
        if (e == p || errno || !isfinite(v[n]) || (*e && !isspace((unsigned char)*e)))
            return -1;
        n++;
        p = e;
    }
    *count = n;
    return 0;
}

static double formula_n(const struct pending *p, double nm)
{
    double l2 = (nm / 1000) * (nm / 1000);
    if (p->form == 1)
        return p->c[0];
    if (p->form == 2)
        return p->c[0] + p->c[1] / l2 + p->c[2] / (l2 * l2);
    double s = 1;
    for (int i = 0; i < 3; i++)
        s += p->c[i] * l2 / (l2 - p->c[3 + i]);
    return s > 0 ? sqrt(s) : -1;
}

/* Turn the pending material into curves. */
static int finish(struct pending *p, const char *file, int line)
{
    struct tex_matdb_entry *m = &p->mat;
    if (p->form == 0)
        return tex_usage_error("%s:%d: material '%s' has no data (ior, cauchy, sellmeier or nk)",
                               file, line, m->name);
    if (m->kind == TEX_CONDUCTOR && p->form != 4)
        return tex_usage_error("%s:%d: conductor '%s' needs nk rows", file, line, m->name);
    if (p->form == 4) {
        if (tex_curve_from_table(&m->n, p->wl, p->n, p->nrows) < 0 ||
            tex_curve_from_table(&m->k, p->wl, p->k, p->nrows) < 0)
            return tex_usage_error("%s:%d: %s", file, line, tex_errmsg());
        return 0;
    }
    tex_curve_constant(&m->k, 0);
    for (int i = 0; i < TEX_CURVE_N; i++) {
        double v = formula_n(p, TEX_LAMBDA_MIN + i);
        if (!(v > 0) || !isfinite((float)v)) /* the curve holds floats */
            return tex_usage_error("%s:%d: material '%s': index %g at %d nm is not > 0", file,
                                   line, m->name, v, TEX_LAMBDA_MIN + i);
        m->n.v[i] = (float)v;
    }
    return 0;
}

/* db->m grows by doubling, and a name defined twice is found through p's table: a search of
 * every name before it took 20 s for 2 10^5 materials. */
static int add(struct tex_matdb *db, struct pending *p)
{
    if (db->count == p->mcap) {
        int cap = p->mcap ? 2 * p->mcap : 16;
        struct tex_matdb_entry *nm = realloc(db->m, (size_t)cap * sizeof *nm);
        if (!nm)
            return tex_error("out of memory");
        db->m = nm;
        p->mcap = cap;
    }
    if (tex_names_put(&p->names, p->mat.name, p) < 0)
        return -1;
    db->m[db->count++] = p->mat;
    p->mat.source = NULL;
    return 0;
}

/* 'material NAME conductor|dielectric': opens p. */
static int begin_material(struct pending *p, int in, const char *q,
                          const char *file, int line)
{
    char name[64], kind[64], extra[2];
    int got = sscanf(q, "%63s %63s %1s", name, kind, extra);
    if (in)
        return tex_usage_error("%s:%d: 'material' inside '%s' (missing 'end')", file, line,
                               p->mat.name);
    if (got != 2 || (strcmp(kind, "conductor") && strcmp(kind, "dielectric")))
        return tex_usage_error("%s:%d: expected 'material NAME conductor|dielectric'", file, line);
    if (strlen(name) >= TEX_MATDB_NAME)
        return tex_usage_error("%s:%d: material name longer than %d characters", file, line,
                               TEX_MATDB_NAME - 1);
    if (tex_names_get(&p->names, name))
        return tex_usage_error("%s:%d: material '%s' defined twice", file, line, name);
    memset(&p->mat, 0, sizeof p->mat);
    strcpy(p->mat.name, name);
    p->mat.kind = kind[0] == 'c' ? TEX_CONDUCTOR : TEX_DIELECTRIC;
    p->form = 0;
    p->nrows = 0;
    return 0;
}

/* 'ior N', 'cauchy A B [C]' or 'sellmeier B1 B2 B3 C1 C2 C3'. */
static int index_formula(struct pending *p, const char *kw, char *q, const char *file,
                         int line)
{
    double v[8];
    int nv = 0, form = kw[0] == 'i' ? 1 : kw[0] == 'c' ? 2 : 3;
    int lo = form == 1 ? 1 : form == 2 ? 2 : 6, hi = form == 2 ? 3 : lo;
    if (read_numbers(q, v, 8, &nv) < 0 || nv < lo || nv > hi)
        return tex_usage_error("%s:%d: '%s' takes %d%s numbers", file, line, kw, lo,
                               hi > lo ? " or 3" : "");
    if (p->form)
        return tex_usage_error("%s:%d: material '%s' already has index data", file, line,
                               p->mat.name);
    if (form == 1 && !(v[0] > 0))
        return tex_usage_error("%s:%d: ior %g must be > 0", file, line, v[0]);
    memset(p->c, 0, sizeof p->c);
    memcpy(p->c, v, nv * sizeof *v);
    p->form = form;
    return 0;
}

/* 'nk WAVELENGTH_NM N K': one row of a measured table. */
static int nk_row(struct pending *p, char *q, const char *file, int line)
{
    double v[8];
    int nv = 0;
    if (read_numbers(q, v, 8, &nv) < 0 || nv != 3)
        return tex_usage_error("%s:%d: expected 'nk WAVELENGTH_NM N K'", file, line);
    if (p->form && p->form != 4)
        return tex_usage_error("%s:%d: material '%s' already has index data", file, line,
                               p->mat.name);
    if (!(v[0] >= 0))
        return tex_usage_error("%s:%d: wavelength %g nm is negative", file, line, v[0]);
    if (p->nrows > 0 && !(v[0] > p->wl[p->nrows - 1]))
        return tex_usage_error("%s:%d: wavelength %g nm not after %g nm (rows must be "
                               "sorted by increasing wavelength)",
                               file, line, v[0], p->wl[p->nrows - 1]);
    if (!(v[1] > 0))
        return tex_usage_error("%s:%d: n = %g must be > 0", file, line, v[1]);
    if (!(v[2] >= 0))
        return tex_usage_error("%s:%d: k = %g must be >= 0", file, line, v[2]);
    if (p->nrows == p->cap) {
        int cap = p->cap ? 2 * p->cap : 16;
        double *a = realloc(p->wl, cap * sizeof *a), *b = NULL, *c = NULL;
        if (a) {
            p->wl = a;
            b = realloc(p->n, cap * sizeof *b);
        }
        if (b) {
            p->n = b;
            c = realloc(p->k, cap * sizeof *c);
        }
        if (!c)
            return tex_error("out of memory");
        p->k = c;
        p->cap = cap;
    }
    p->wl[p->nrows] = v[0];
    p->n[p->nrows] = v[1];
    p->k[p->nrows] = v[2];
    p->nrows++;
    p->form = 4;
    return 0;
}

/* One line inside a material, keyword kw and the rest q. */
static int material_line(struct tex_matdb *db, struct pending *p, int *in, const char *kw,
                         char *q, const char *file, int line)
{
    int rc = 0;
    if (!strcmp(kw, "end")) {
        if ((rc = finish(p, file, line)) == 0)
            rc = add(db, p);
        *in = 0;
    } else if (!strcmp(kw, "source")) {
        while (isspace((unsigned char)*q))
            q++;
        free(p->mat.source);
        if (!(p->mat.source = strdup(q)))
            rc = tex_error("out of memory");
    } else if (!strcmp(kw, "ior") || !strcmp(kw, "cauchy") || !strcmp(kw, "sellmeier")) {
        rc = index_formula(p, kw, q, file, line);
    } else if (!strcmp(kw, "nk")) {
        rc = nk_row(p, q, file, line);
    } else {
        rc = tex_usage_error("%s:%d: unknown keyword '%s' (expected source, ior, cauchy, "
                             "sellmeier, nk or end)",
                             file, line, kw);
    }
    return rc;
}

int tex_matdb_parse(struct tex_matdb *db, const char *text, const char *file)
{
    db->count = 0;
    db->m = NULL;
    struct pending p;
    memset(&p, 0, sizeof p);
    int in = 0, line = 0, rc = 0;
    const char *s = text;
    char buf[1024];
    while (*s && rc == 0) {
        const char *e = strchr(s, '\n');
        size_t len = e ? (size_t)(e - s) : strlen(s);
        line++;
        if (len >= sizeof buf) {
            rc = tex_usage_error("%s:%d: line longer than %zu characters", file, line,
                                 sizeof buf - 1);
            break;
        }
        memcpy(buf, s, len);
        buf[len] = 0;
        s += len + (e ? 1 : 0);
        char *q = buf;
        while (isspace((unsigned char)*q))
            q++;
        if (!*q || *q == '#')
            continue;
        char *kw = q;
        while (*q && !isspace((unsigned char)*q))
            q++;
        if (*q)
            *q++ = 0;
        if (!strcmp(kw, "material"))
            in = (rc = begin_material(&p, in, q, file, line)) == 0 || in;
        else if (!in)
            rc = tex_usage_error("%s:%d: '%s' outside a material (expected 'material')", file,
                                 line, kw);
        else
            rc = material_line(db, &p, &in, kw, q, file, line);
    }
    if (rc == 0 && in)
        rc = tex_usage_error("%s:%d: material '%s' has no 'end'", file, line, p.mat.name);
    free(p.mat.source);
    free(p.wl);
    free(p.n);
    free(p.k);
    tex_names_free(&p.names);
    if (rc < 0)
        tex_matdb_free(db);
    return rc;
}

int tex_matdb_read(struct tex_matdb *db, const char *path)
{
    db->count = 0;
    db->m = NULL;
    size_t len;
    char *text = tex_read_text(path, 1u << 26, &len, "a materials file");
    if (!text)
        return -1;
    if (memchr(text, 0, len)) {
        free(text);
        return tex_usage_error("%s: binary data in a materials file", path);
    }
    int rc = tex_matdb_parse(db, text, path);
    free(text);
    return rc;
}

const struct tex_matdb_entry *tex_matdb_find(const struct tex_matdb *db, const char *name)
{
    for (int i = 0; i < db->count; i++)
        if (!strcmp(db->m[i].name, name))
            return &db->m[i];
    char known[512] = "";
    size_t at = 0;
    for (int i = 0; i < db->count && at < sizeof known; i++)
        at += snprintf(known + at, sizeof known - at, "%s%s", i ? ", " : "", db->m[i].name);
    tex_usage_error("unknown material '%s' (known: %s)", name, db->count ? known : "none");
    return NULL;
}
