/* t_ifft - a texture map from a painted (or computed) Fourier spectrum */
#include <stdlib.h>
#include <string.h>

#include "prim/spectral.h"
#include "textura.h"

struct opts {
    const char *phase;
    int symmetric, as, scale;
};

static const struct tex_param rows[] = {
    TEX_STRING(struct opts, phase, 0, NULL, "random|zero|MAP",
               "phase of a magnitude spectrum: random (from the seed), zero, or a map of turns in "
               "[0,1) of the spectrum's size (default random)"),
    TEX_FLAG(struct opts, symmetric, 0,
             "complete the spectrum by Hermitian symmetry so that the texture is real: painting "
             "one half (two quadrants) is enough"),
    TEX_ENUM(struct opts, as, 0, "real", "real|mag|logmag|phase|complex",
             "what to write: the real part, magnitude, log(1 + magnitude), phase in turns, or real "
             "and imaginary parts as two channels"),
    TEX_ENUM_N("rescale", struct opts, scale, 0, "auto", "auto|unit|none",
               "unit rescales real to [0,1] by min and max and mag, logmag by their max; none "
               "keeps raw values; auto is none for a complex spectrum, unit otherwise",
               .old = "scale"),
    {0}};

static const struct tex_tool tool = {
    "t_ifft", "[SPECTRUM]",
    "the texture of a centred spectrum: a painted magnitude (1, 3 or 4 channels) with a phase, or "
    "a complex spectrum (2 channels) from t_fft --as complex, by the inverse FFT",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS | TEX_OPT_SEED, rows, 0, 1};

int main(int argc, char **argv)
{
    static const enum tex_ifft_output outs[] = {TEX_IFFT_REAL, TEX_IFFT_MAG, TEX_IFFT_LOGMAG,
                                                TEX_IFFT_PHASE, TEX_IFFT_COMPLEX};
    struct tex_common c;
    struct opts o;
    struct tex_ifft_opts io = TEX_IFFT_DEFAULTS;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o);
    const char *name = i < argc ? argv[i] : "-";
    tex_map *s, *phase = NULL, *t;

    if (o.phase && !strcmp(o.phase, "zero"))
        io.phase = TEX_PHASE_ZERO;
    else if (o.phase && strcmp(o.phase, "random")) {
        if (!strcmp(o.phase, "-") && !strcmp(name, "-"))
            tex_usage_die("--phase and the spectrum cannot both be standard input");
        io.phase = TEX_PHASE_MAP;
    }
    s = tex_cli_read(name);
    if (s->nc == 2 && o.phase)
        tex_usage_die("--phase does not apply to a complex spectrum (2 channels: Re, Im)");
    if (io.phase == TEX_PHASE_MAP)
        phase = tex_cli_read(o.phase);
    io.phase_map = phase;
    io.seed = (uint64_t)c.seed;
    io.symmetric = o.symmetric;
    io.output = outs[o.as];
    io.scale = (enum tex_ifft_scale)o.scale;
    if (!(t = tex_ifft(s, &io))) {
        if (!strstr(tex_errmsg(), "phase map"))
            tex_error_context(name);
        tex_die();
    }
    tex_map_free(s); /* before writing: the encoder can reuse the memory */
    tex_map_free(phase);
    tex_cli_write(t, &c);
    tex_map_free(t);
    free(c.cmdline);
    return 0;
}
