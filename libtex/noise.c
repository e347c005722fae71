/* noise.c - gradient noise and the noise primitive */
#include <math.h>
#include <stdlib.h>

#include "error.h"
#include "noise.h"
#include "prim.h"
#include "rng.h"

int tex_noise_init(tex_noise_table *t, uint64_t seed, int n, int period)
{
    tex_rng r;

    if (n < 2 || n > TEX_NOISE_MAX_GRADIENTS)
        return tex_usage_error("the number of gradients must be 2..%d (got %d)",
                               TEX_NOISE_MAX_GRADIENTS, n);
    t->n = n;
    t->period = period;
    t->perm = malloc(n * sizeof *t->perm);
    t->grad = malloc(n * sizeof *t->grad);
    if (!t->perm || !t->grad) {
        tex_noise_free(t);
        return tex_error("out of memory");
    }
    tex_rng_seed(&r, seed);
    for (int i = 0; i < n; i++) {
        /* Uniform on the sphere: z uniform in [-1,1], longitude uniform. */
        double z = 2.0 * tex_rng_uniform(&r) - 1.0, phi = 2.0 * M_PI * tex_rng_uniform(&r);
        double s = sqrt(1.0 - z * z);
        t->grad[i][0] = (float)(s * cos(phi));
        t->grad[i][1] = (float)(s * sin(phi));
        t->grad[i][2] = (float)z;
        t->perm[i] = i;
    }
    tex_rng_shuffle(&r, t->perm, n);
    return 0;
}

void tex_noise_free(tex_noise_table *t)
{
    free(t->perm);
    free(t->grad);
    t->perm = NULL;
    t->grad = NULL;
}

static inline int imod(long long a, int n)
{
    int m = (int)(a % n);
    return m < 0 ? m + n : m;
}

static inline double weight(double t)
{
    t = fabs(t);
    return t < 1.0 ? (2.0 * t - 3.0) * t * t + 1.0 : 0.0;
}

double tex_noise3(const tex_noise_table *t, double x, double y, double z)
{
    double fx = floor(x), fy = floor(y), fz = floor(z), sum = 0.0;
    long long ix = (long long)fx, iy = (long long)fy, iz = (long long)fz;
    int n = t->n;

    for (int c = 0; c < 8; c++) {
        long long i = ix + (c & 1), j = iy + (c >> 1 & 1), k = iz + (c >> 2);
        double u = x - (double)i, v = y - (double)j, w = z - (double)k;
        const float *g;
        if (t->period) {
            i = imod(i, t->period);
            j = imod(j, t->period);
        }
        g = t->grad[t->perm[imod(i + t->perm[imod(j + t->perm[imod(k, n)], n)], n)]];
        sum += weight(u) * weight(v) * weight(w) * (g[0] * u + g[1] * v + g[2] * w);
    }
    return sum;
}

/* ---- the primitive ---- */

struct noise_params {
    double frequency;
    double z;
    int gradients;
};

static const struct tex_param noise_rows[] = {
    TEX_REAL(struct noise_params, frequency, 'f', 8, 0, 1e6, "F",
             "lattice cells across the map (an integer with --tile)"),
    TEX_REAL(struct noise_params, z, 0, 0, -1e6, 1e6, "Z", "the slice of the solid noise"),
    TEX_INT(struct noise_params, gradients, 0, 256, 2, TEX_NOISE_MAX_GRADIENTS, "N",
            "gradients on the sphere (the thesis's n)"),
    {0}};

static int noise_init(struct tex_field *f)
{
    const struct noise_params *p = f->params;
    tex_noise_table *t = malloc(sizeof *t);
    int period = 0;

    if (!t)
        return tex_error("out of memory");
    if (f->tile) {
        if (p->frequency != floor(p->frequency) || p->frequency < 1) {
            free(t);
            return tex_usage_error("--frequency must be a whole number >= 1 with --tile (got %g)",
                                   p->frequency);
        }
        period = (int)p->frequency;
    }
    if (tex_noise_init(t, f->seed, p->gradients, period) < 0) {
        free(t);
        return -1;
    }
    f->state = t;
    return 0;
}

static void noise_fini(struct tex_field *f)
{
    if (f->state)
        tex_noise_free(f->state);
    free(f->state);
}

static inline float to_unit(double s)
{
    s = 0.5 + 0.5 * s;
    return (float)(s < 0 ? 0 : s > 1 ? 1 : s);
}

static void noise_eval3(const struct tex_field *f, int n, const double *u, const double *v,
                        const double *w, float *out)
{
    const struct noise_params *p = f->params;

    for (int i = 0; i < n; i++)
        out[i] = to_unit(tex_noise3(f->state, u[i] * p->frequency, v[i] * p->frequency,
                                    w[i] * p->frequency));
}

static void noise_eval2(const struct tex_field *f, int n, const double *u, const double *v,
                        float *out)
{
    const struct noise_params *p = f->params;

    for (int i = 0; i < n; i++)
        out[i] = to_unit(tex_noise3(f->state, u[i] * p->frequency, v[i] * p->frequency, p->z));
}

const struct tex_primitive tex_prim_noise = {
    .name = "noise",
    .summary = "gradient noise of the thesis (Perlin), rescaled to [0,1]",
    .flags = TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_TILE,
    .params_size = sizeof(struct noise_params),
    .params = noise_rows,
    .init = noise_init,
    .fini = noise_fini,
    .eval2 = noise_eval2,
    .eval3 = noise_eval3,
};
