/* remap.c - bias, gain, gamma, levels, quantise, invert, clamp */
#include <math.h>

#include "base/error.h"
#include "base/simd.h"
#include "ops/remap.h"
#include "ops/x86/remap_x86.h"

static double unit(double t)
{
    return t > 0 ? (t < 1 ? t : 1) : 0; /* NaN -> 0 */
}

double tex_bias(double b, double t)
{
    t = unit(t);
    /* bias_b(0.5) = b exactly, which pow's rounding does not promise */
    return t == 0 ? 0 : t == 0.5 ? b : pow(t, log(b) / log(0.5));
}

double tex_gain(double g, double t)
{
    t = unit(t);
    return t < 0.5 ? tex_bias(1 - g, 2 * t) / 2 : 1 - tex_bias(1 - g, 2 - 2 * t) / 2;
}

double tex_remap_value(const struct tex_remap *r, double v)
{
    if (r->in0 != 0 || r->in1 != 1 || r->out0 != 0 || r->out1 != 1)
        v = r->out0 + unit((v - r->in0) / (r->in1 - r->in0)) * (r->out1 - r->out0);
    if (r->bias != 0.5)
        v = tex_bias(r->bias, v);
    if (r->gain != 0.5)
        v = tex_gain(r->gain, v);
    if (r->gamma != 1)
        v = pow(unit(v), 1 / r->gamma);
    if (r->quantize >= 2) {
        double k = floor(unit(v) * r->quantize);
        v = (k < r->quantize ? k : r->quantize - 1) / (r->quantize - 1);
    }
    if (r->invert)
        v = 1 - v;
    if (r->clamp)
        v = v < r->lo ? r->lo : v > r->hi ? r->hi : v;
    return v;
}

int tex_remap_check(const struct tex_remap *r)
{
    if (!(r->bias > 0 && r->bias < 1))
        return tex_usage_error("bias must be in (0,1) (got %g)", r->bias);
    if (!(r->gain > 0 && r->gain < 1))
        return tex_usage_error("gain must be in (0,1) (got %g)", r->gain);
    if (!(r->gamma > 0) || !isfinite(r->gamma))
        return tex_usage_error("gamma must be > 0 (got %g)", r->gamma);
    if (!(r->in0 != r->in1) || !isfinite(r->in0 + r->in1 + r->out0 + r->out1))
        return tex_usage_error("levels: IN0 and IN1 must differ (got %g,%g)", r->in0, r->in1);
    if (r->quantize == 1 || r->quantize < 0)
        return tex_usage_error("quantize needs at least 2 levels (got %d)", r->quantize);
    if (r->clamp && !(r->lo <= r->hi))
        return tex_usage_error("clamp: LO must be <= HI (got %g,%g)", r->lo, r->hi);
    return 0;
}

/* Whether gamma is the remap's one power, and pow8 takes its exponent */
static int gamma_alone(const struct tex_remap *r)
{
    return r->bias == 0.5 && r->gain == 0.5 && r->gamma != 1 && 1 / r->gamma <= 64;
}

int tex_remap_map(tex_map *m, const struct tex_remap *r)
{
    size_t n = (size_t)m->w * m->h;
    int nc = m->nc, cc = nc == 4 ? 3 : nc;

    if (tex_remap_check(r) < 0)
        return -1;
    m->subregions = 0;
#ifdef TEX_X86
    if (cc == nc && gamma_alone(r) && tex_simd_level() >= TEX_SIMD_AVX512) {
        size_t all = n * nc;
        for (size_t i = tex_remap_gamma_avx512(r, m->px, all); i < all; i++)
            m->px[i] = (float)tex_remap_value(r, m->px[i]);
        return 0;
    }
#endif
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < cc; c++)
            m->px[i * nc + c] = (float)tex_remap_value(r, m->px[i * nc + c]);
    return 0;
}
