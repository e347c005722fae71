/* points.c - point sets: random (uniform, Poisson-disk, clusters), radii, files of points */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/rng.h"
#include "io/file.h"
#include "io/limit.h"
#include "prim/cellular.h"
#include "prim/cellular_impl.h"

static int points_alloc(tex_points *ps, int dim, long n)
{
    ps->dim = dim;
    ps->n = n;
    ps->axes = NULL;
    if (!(ps->x = malloc((size_t)n * dim * sizeof *ps->x)))
        return tex_error("out of memory for %ld points", n);
    return 0;
}

void tex_points_free(tex_points *ps)
{
    free(ps->x);
    free(ps->axes);
    ps->x = ps->axes = NULL;
    ps->n = 0;
}

void tex_points_wrap(tex_points *ps)
{
    for (long i = 0; i < ps->n * ps->dim; i++)
        ps->x[i] = wrap1(ps->x[i]);
}

/* Dart throwing on a background grid whose cells (side <= r/sqrt(dim))
 * hold at most one point each. */
static int poisson(tex_points *ps, tex_rng *rng, int tile)
{
    int dim = ps->dim;
    long n = ps->n, placed = 0;
    double cover = dim == 2 ? 0.35 : 0.2; /* dart throwing saturates at 0.547 and 0.38 */
    double r = dim == 2 ? 2 * sqrt(cover / (M_PI * n)) : 2 * cbrt(cover * 3 / (4 * M_PI * n));
    int g = (int)ceil(sqrt((double)dim) / r), reach = 2;
    long cells = (long)g * g * (dim == 3 ? g : 1);
    long *owner = malloc(cells * sizeof *owner);
    long tries = 0, budget = 1000 * n + 100000;

    if (!owner)
        return tex_error("out of memory for the Poisson-disk grid");
    for (long i = 0; i < cells; i++)
        owner[i] = -1;
    while (placed < n && tries++ < budget) {
        double p[3] = {0, 0, 0};
        int k[3] = {0, 0, 0}, ok = 1;
        for (int j = 0; j < dim; j++) {
            p[j] = tex_rng_uniform(rng);
            k[j] = (int)(p[j] * g);
            if (k[j] >= g)
                k[j] = g - 1;
        }
        for (int dz = dim == 3 ? -reach : 0; ok && dz <= (dim == 3 ? reach : 0); dz++)
            for (int dy = -reach; ok && dy <= reach; dy++)
                for (int dx = -reach; ok && dx <= reach; dx++) {
                    int o[3] = {dx, dy, dz}, kk[3] = {0, 0, 0};
                    long cell = 0;
                    for (int j = 0; j < dim; j++) {
                        kk[j] = k[j] + o[j];
                        if (tile)
                            kk[j] = (kk[j] % g + g) % g;
                        else if (kk[j] < 0 || kk[j] >= g)
                            goto next;
                    }
                    cell = kk[0] + (long)g * (kk[1] + (long)g * kk[2]);
                    if (owner[cell] >= 0) {
                        const double *q = ps->x + owner[cell] * dim;
                        double d2 = 0;
                        for (int j = 0; j < dim; j++) {
                            double d = fabs(p[j] - q[j]);
                            if (tile && d > 0.5)
                                d = 1 - d;
                            d2 += d * d;
                        }
                        if (d2 < r * r)
                            ok = 0;
                    }
                next:;
                }
        if (ok) {
            owner[k[0] + (long)g * (k[1] + (long)g * k[2])] = placed;
            memcpy(ps->x + placed * dim, p, dim * sizeof *p);
            placed++;
        }
    }
    free(owner);
    if (placed < n)
        return tex_error("Poisson-disk sampling placed only %ld of %ld points", placed, n);
    return 0;
}

int tex_points_random(tex_points *ps, int dim, long n, enum tex_pointdist dist, int clusters,
                      uint64_t seed, int tile)
{
    tex_rng rng;

    memset(ps, 0, sizeof *ps);
    if (dim != 2 && dim != 3)
        return tex_usage_error("points must have 2 or 3 dimensions (got %d)", dim);
    if (n < 1 || n > TEX_POINTS_MAX)
        return tex_usage_error("the number of points must be 1..%d (got %ld)", TEX_POINTS_MAX, n);
    if (points_alloc(ps, dim, n) < 0)
        return -1;
    tex_rng_seed(&rng, seed);
    if (dist == TEX_POINTS_POISSON) {
        if (poisson(ps, &rng, tile) < 0) {
            tex_points_free(ps);
            return -1;
        }
    } else if (dist == TEX_POINTS_CLUSTER) {
        long k = clusters > 0 ? clusters : lround(sqrt((double)n));
        double sigma = 0.25 / pow((double)k, 1.0 / dim), *parent;
        if (k < 1)
            k = 1;
        if (!(parent = malloc((size_t)k * dim * sizeof *parent))) {
            tex_points_free(ps);
            return tex_error("out of memory");
        }
        for (long i = 0; i < k * dim; i++)
            parent[i] = tex_rng_uniform(&rng);
        for (long i = 0; i < n; i++) {
            const double *c = parent + (long)tex_rng_below(&rng, (uint32_t)k) * dim;
            for (int j = 0; j < dim; j++)
                ps->x[i * dim + j] = wrap1(c[j] + sigma * tex_rng_gauss(&rng));
        }
        free(parent);
    } else {
        for (long i = 0; i < n * dim; i++)
            ps->x[i] = tex_rng_uniform(&rng);
    }
    return 0;
}

int tex_points_vary(tex_points *ps, double size, double shape, uint64_t seed)
{
    tex_rng rng;
    int dim = ps->dim;

    if (!(size >= 0 && size <= 0.95 && shape >= 0 && shape <= 0.95))
        return tex_usage_error("size and shape spreads must be 0..0.95");
    if (size == 0 && shape == 0)
        return 0;
    if (!ps->axes) {
        if (!(ps->axes = malloc((size_t)ps->n * dim * sizeof *ps->axes)))
            return tex_error("out of memory");
        for (long i = 0; i < ps->n * dim; i++)
            ps->axes[i] = 1;
    }
    /* A stream of its own, so that the positions do not move with the spreads. */
    tex_rng_seed(&rng, tex_hash64(seed ^ 0x6275626231657331ULL));
    for (long i = 0; i < ps->n; i++) {
        double s = 1 + size * (2 * tex_rng_uniform(&rng) - 1);
        for (int j = 0; j < dim; j++)
            ps->axes[i * dim + j] *= s * (1 + shape * (2 * tex_rng_uniform(&rng) - 1));
    }
    return 0;
}

/* The numbers of one line of a point file into v, its comment cut: x y [z] and an optional
 * radius w.  Returns how many, 0 for a blank line, or -1 with the error recorded. */
static int point_line(char *line, double *v, int dim, const char *path, long lineno)
{
    int cols = 0;
    char *s = line, *hash = strchr(line, '#');

    if (hash)
        *hash = '\0';
    for (;;) {
        char *end;
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
            s++;
        if (!*s)
            break;
        if (cols == dim + 1)
            return tex_error("%s:%ld: too many columns (want %s)", path, lineno,
                             dim == 2 ? "x y [w]" : "x y z [w]");
        errno = 0;
        v[cols] = strtod(s, &end);
        if (end == s || (*end && !strchr(" \t\r\n", *end))) {
            int len = (int)strcspn(s, " \t\r\n");
            return tex_error("%s:%ld: not a number: '%.*s'", path, lineno, len < 20 ? len : 20,
                             s);
        }
        if (!isfinite(v[cols]))
            return tex_error("%s:%ld: not a finite number: '%.*s'", path, lineno,
                             (int)(end - s), s);
        cols++;
        s = end;
    }
    if (cols == 0)
        return 0;
    if (cols < dim)
        return tex_error("%s:%ld: %d column%s, want %s", path, lineno, cols,
                         cols == 1 ? "" : "s", dim == 2 ? "x y [w]" : "x y z [w]");
    if (cols == dim + 1 && !(v[dim] > 0))
        return tex_error("%s:%ld: the radius must be > 0 (got %g)", path, lineno, v[dim]);
    return cols;
}

/* Store point n (cols numbers in v) in ps, which has room for *alloc.  The axes start
 * with the first radius, at 1 for the points before it. */
static int add_point(tex_points *ps, const double *v, int cols, long n, size_t *alloc,
                     const char *path, long lineno)
{
    int dim = ps->dim;

    if (n == TEX_POINTS_MAX)
        return tex_error("%s:%ld: more than %d points", path, lineno, TEX_POINTS_MAX);
    if ((size_t)n == *alloc) {
        size_t na = *alloc ? 2 * *alloc : 1024;
        int ok = 1;
        ps->x = grown(ps->x, na * dim, sizeof *ps->x, &ok);
        if (ps->axes)
            ps->axes = grown(ps->axes, na * dim, sizeof *ps->axes, &ok);
        if (!ok)
            return tex_error("out of memory reading %s", path);
        *alloc = na;
    }
    if (cols == dim + 1 && !ps->axes) {
        if (!(ps->axes = malloc(*alloc * dim * sizeof *ps->axes)))
            return tex_error("out of memory reading %s", path);
        for (long i = 0; i < n * dim; i++)
            ps->axes[i] = 1;
    }
    for (int j = 0; j < dim; j++) {
        ps->x[n * dim + j] = v[j];
        if (ps->axes)
            ps->axes[n * dim + j] = cols == dim + 1 ? v[dim] : 1;
    }
    return 0;
}

/* The file is read whole under the one input limit (io/limit.h): getline
 * grew one line of /dev/zero to 5.3 GB. */
int tex_points_read(tex_points *ps, const char *path, int dim)
{
    char *text, *line, *next;
    size_t len, max, alloc = 0;
    long lineno = 0, n = 0;
    int ret = -1;

    memset(ps, 0, sizeof *ps);
    ps->dim = dim;
    if (tex_input_max(&max) < 0 || !(text = tex_read_text(path, max, &len, "a points file")))
        return -1;
    if (memchr(text, 0, len)) {
        free(text);
        return tex_error("%s: binary data in a points file", path);
    }
    for (line = text; line < text + len; line = next) {
        double v[5];
        int cols;
        if ((next = strchr(line, '\n')))
            *next++ = '\0';
        else
            next = text + len;
        if ((cols = point_line(line, v, dim, path, ++lineno)) < 0)
            goto out;
        if (cols == 0)
            continue;
        if (add_point(ps, v, cols, n, &alloc, path, lineno) < 0)
            goto out;
        n++;
    }
    if (n == 0) {
        tex_error("%s:%ld: no points in the file", path, lineno);
        goto out;
    }
    ps->n = n;
    ret = 0;
out:
    free(text);
    if (ret < 0)
        tex_points_free(ps);
    return ret;
}
