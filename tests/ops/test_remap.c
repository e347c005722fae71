/* test_remap - Perlin's bias and gain, levels, quantise, invert, clamp */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "base/simd.h"
#include "ops/remap.h"
#include "unit.h"

/* A gamma remap of a map (its powers eight at a time where the CPU has AVX-512) gives
 * tex_remap_value's floats: gammas whose exponent runs from 1/40 to 64 and past it, with
 * levels, quantise, invert and clamp after; 0, 1, NaN, tiny and outside values, subnormal
 * ones after levels; 1 and 3 channels of an odd count. */
static void gamma_maps(void)
{
    static const double gammas[] = {1.5, 0.4, 2.2, 40, 0.0157, 1.0 / 64, 0.01, 0.1, 7};
    enum { N = 3001 };
    tex_map *m = tex_map_new(N, 1, 3), *o = tex_map_new(N, 1, 3);
    uint64_t x = 9;
    for (int i = 0; m && i < 3 * N; i++) {
        x = x * 6364136223846793005ULL + 1442695040888963407ULL;
        m->px[i] = i % 4 ? (float)(x >> 40) / (1 << 24) : -0.2f + 1.4f * i / (3 * N);
    }
    if (!m || !o)
        return;
    m->px[5] = NAN, m->px[6] = 0, m->px[7] = 1, m->px[8] = 1e-40f, m->px[9] = 1e-30f;
    for (int level = tex_simd_level(); level >= TEX_SIMD_SCALAR; level--) {
        int same = 1;
        tex_simd_limit(level);
        for (size_t g = 0; g < sizeof gammas / sizeof *gammas; g++)
            for (int post = 0; post < 5; post++) {
                struct tex_remap r = TEX_REMAP_IDENTITY;
                r.gamma = gammas[g];
                r.quantize = post == 1 ? 7 : 0;
                r.invert = post == 2 || post == 3;
                r.clamp = post == 3, r.lo = 0.1, r.hi = 0.8;
                if (post == 3)
                    r.in0 = 0.1, r.in1 = 0.9, r.out0 = 0.2, r.out1 = 0.95;
                if (post == 4) /* values of 1e-300 and below: subnormal doubles */
                    r.in1 = 1e300, r.out1 = 1e-8;
                for (int nc = 1; nc <= 3; nc += 2) {
                    o->nc = nc, o->w = 3 * N / nc;
                    memcpy(o->px, m->px, sizeof *o->px * 3 * N);
                    tex_remap_map(o, &r);
                    for (int i = 0; i < 3 * N; i++) {
                        float want = (float)tex_remap_value(&r, m->px[i]);
                        same &= !memcmp(&want, o->px + i, sizeof want);
                    }
                }
            }
        CHECKF(same, "level %d: gamma remaps of maps are tex_remap_value's floats", level);
    }
    tex_simd_limit(TEX_SIMD_AVX512);
    o->nc = 3, o->w = N;
    tex_map_free(m);
    tex_map_free(o);
}

int main(void)
{
    struct tex_remap id = TEX_REMAP_IDENTITY, r;
    int ok = 1;

    for (double b = 0.05; b < 1; b += 0.1)
        ok &= fabs(tex_bias(b, 0.5) - b) < 1e-12;
    CHECK(ok, "bias_b(0.5) = b");
    ok = 1;
    for (double g = 0.05; g < 1; g += 0.1)
        ok &= fabs(tex_gain(g, 0.5) - 0.5) < 1e-12 && fabs(tex_gain(g, 0.25) - tex_bias(1 - g, 0.5) / 2) < 1e-12 &&
              fabs(tex_gain(g, 0.3) + tex_gain(g, 0.7) - 1) < 1e-12;
    CHECK(ok, "gain_g(0.5) = 0.5, gain_g(0.25) = (1-g)/2, odd symmetry about 0.5");
    CHECK(tex_bias(0.3, 0) == 0 && tex_bias(0.3, 1) == 1 && tex_gain(0.8, 0) == 0 &&
              tex_gain(0.8, 1) == 1,
          "bias and gain fix 0 and 1");
    CHECK(tex_bias(0.3, 0.2) < 0.2 && tex_bias(0.7, 0.2) > 0.2, "bias above 0.5 raises values");
    ok = 1;
    for (double t = -0.5; t <= 1.5; t += 0.01)
        ok &= tex_remap_value(&id, t) == t;
    CHECK(ok, "the identity remap changes nothing, outside [0,1] too");

    r = id;
    r.in0 = 0.2, r.in1 = 0.6, r.out0 = 1, r.out1 = 3;
    CHECKF(fabs(tex_remap_value(&r, 0.4) - 2) < 1e-12 && tex_remap_value(&r, 0) == 1 &&
               tex_remap_value(&r, 1) == 3,
           "levels 0.2,0.6,1,3 (0.4 -> %g)", tex_remap_value(&r, 0.4));
    r = id;
    r.quantize = 4;
    CHECK(tex_remap_value(&r, 0.1) == 0 && tex_remap_value(&r, 0.3) == 1.0 / 3 &&
              tex_remap_value(&r, 0.99) == 1 && tex_remap_value(&r, 1) == 1,
          "quantize 4: 0, 1/3, 2/3, 1");
    r = id;
    r.gamma = 2;
    CHECK(fabs(tex_remap_value(&r, 0.25) - 0.5) < 1e-12, "gamma 2: 0.25 -> 0.5");
    r = id;
    r.invert = 1, r.clamp = 1, r.lo = 0.2, r.hi = 0.7;
    CHECK(tex_remap_value(&r, 0.1) == 0.7 && fabs(tex_remap_value(&r, 0.5) - 0.5) < 1e-12,
          "invert, then clamp to 0.2..0.7");
    r = id;
    r.bias = 1;
    CHECK(tex_remap_check(&r) < 0, "bias 1 is refused");
    {
        tex_map *m = tex_map_new(8, 8, 4);
        for (size_t i = 0; i < tex_map_samples(m); i++)
            m->px[i] = 0.25f;
        r = id;
        r.invert = 1;
        tex_remap_map(m, &r);
        CHECK(m->px[0] == 0.75f && m->px[3] == 0.25f, "RGBA: colours remapped, alpha kept");
        tex_map_free(m);
    }
    gamma_maps();
    return unit_done();
}
