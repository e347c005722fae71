/* t_remap - bias, gain, gamma, levels, clamp, quantise or invert the values of a map */
#include <stdlib.h>

#include "ops/remap.h"
#include "textura.h"

struct opts {
    double bias, gain, gamma;
    struct tex_reals levels, clamp;
    int quantize, invert;
};

static const struct tex_param rows[] = {
    TEX_REAL(struct opts, bias, 'b', 0.5, 0.001, 0.999, "B",
             "Perlin's bias: t^(ln B / ln 0.5), so that 0.5 becomes B"),
    TEX_REAL_N("perlin_gain", struct opts, gain, 0, 0.5, 0.001, 0.999, "G",
               "Perlin's gain: two bias halves; G > 0.5 steepens the middle", .old = "-g gain"),
    TEX_REAL(struct opts, gamma, 0, 1, 0.001, 1000, "G", "gamma: t^(1/G)"),
    TEX_REALS(struct opts, levels, 0, "0,1,0,1", -1e30, 1e30, 4, "IN0,IN1,OUT0,OUT1",
              "levels: map [IN0,IN1] (clamped) linearly onto [OUT0,OUT1]"),
    TEX_REALS(struct opts, clamp, 0, NULL, -1e30, 1e30, 2, "LO,HI",
              "clamp the result to [LO,HI] (keep a parameter within its valid range)"),
    TEX_INT_N("quantise", struct opts, quantize, 0, 0, 0, 65536, "N",
              "quantise [0,1] to N levels (0: off)"),
    TEX_FLAG(struct opts, invert, 0, "invert: 1 - t"),
    {0}};

static const struct tex_tool tool = {
    "t_remap", "[MAP]",
    "remap the values of a map: levels, bias, gain, gamma, quantise, invert, clamp (in that order)",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 0, 1};

static tex_map *remap(tex_map *band, void *arg)
{
    if (tex_remap_map(band, arg) < 0) {
        tex_map_free(band);
        return NULL;
    }
    return band;
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o);
    struct tex_remap r = TEX_REMAP_IDENTITY;

    if (o.levels.n != 4)
        tex_usage_die("--levels needs 4 values IN0,IN1,OUT0,OUT1 (got %d)", o.levels.n);
    if (o.clamp.n != 0 && o.clamp.n != 2)
        tex_usage_die("--clamp needs 2 values LO,HI (got %d)", o.clamp.n);
    r.bias = o.bias;
    r.gain = o.gain;
    r.gamma = o.gamma;
    r.in0 = o.levels.v[0];
    r.in1 = o.levels.v[1];
    r.out0 = o.levels.v[2];
    r.out1 = o.levels.v[3];
    r.quantize = o.quantize;
    r.invert = o.invert;
    if ((r.clamp = o.clamp.n == 2)) {
        r.lo = o.clamp.v[0];
        r.hi = o.clamp.v[1];
    }
    if (tex_remap_check(&r) < 0)
        tex_die();
    /* every operation is per pixel: a band of rows at a time */
    tex_cli_stream(i < argc ? argv[i] : "-", &c, remap, &r);
    free(c.cmdline);
    return 0;
}
