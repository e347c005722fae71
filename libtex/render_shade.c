/* render_shade.c - Whitted-Phong and the table of shading models */
#include <math.h>
#include <string.h>

#include "render_shade.h"
#include "render_ct.h"

/* x^n: by squaring for whole n up to 4096 (the usual Phong exponents), a few
 * multiplications instead of pow's tens of cycles; pow otherwise. */
static double powi(double x, double n)
{
    if (!(n >= 0 && n <= 4096) || n != (int)n)
        return pow(x, n);
    double r = 1;
    for (int k = (int)n; k; k >>= 1, x *= x)
        if (k & 1)
            r *= x;
    return r;
}

static void phong_direct(const struct tex_material *m, const double N[3], const double V[3],
                         const double L[3], const tex_colour *E, int n, tex_colour *out)
{
    double nl = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
    if (nl <= 0)
        return;
    tex_colour_mmadd(out, n, &m->kd, E, (float)nl);
    double h[3] = {L[0] + V[0], L[1] + V[1], L[2] + V[2]};
    double hh = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    double q = N[0] * h[0] + N[1] * h[1] + N[2] * h[2];
    if (!(hh > 0) || q <= 0)
        return;
    /* skip where the highlight (N.H)^n = x^(n/2), x = (N.H)^2, is below 1e-13:
     * ln x <= -(y + y^2/2 + y^3/3) with y = 1 - x; no square root for those */
    double x = q * q / hh, y = 1 - x;
    if (0.5 * m->n * y * (1 + y * (0.5 + y * (1.0 / 3))) < 30)
        tex_colour_mmadd(out, n, &m->ks, E, (float)powi(q / sqrt(hh), m->n));
}

static void phong_weights(const struct tex_material *m, double cosi, int n, tex_colour *kr,
                          tex_colour *kt)
{
    (void)cosi;
    tex_colour_set(kr, n, (float)m->kr);
    tex_colour_set(kt, n, (float)m->kt);
}

const struct tex_shading_model tex_shading_phong = {"phong", phong_direct, phong_weights};

static const struct tex_shading_model *const models[] = {&tex_shading_phong,
                                                         &tex_shading_cook_torrance, NULL};

const struct tex_shading_model *tex_shading_find(const char *name)
{
    for (int i = 0; models[i]; i++)
        if (!strcmp(models[i]->name, name))
            return models[i];
    return NULL;
}
