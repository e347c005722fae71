/* t_fft - the forward Fourier transform of a map as a viewable spectrum */
#include <stdlib.h>

#include "prim/spectral.h"
#include "textura.h"

struct opts {
    int as, window;
};

static const struct tex_param rows[] = {
    TEX_ENUM(struct opts, as, 0, "logmag", "logmag|mag|phase|complex",
             "what to write: log magnitude in [0,1], magnitude, phase in turns, or the lossless "
             "real and imaginary parts as two channels (centred, DC in the middle)"),
    TEX_ENUM_N("window_function", struct opts, window, 0, "none", "none|hann",
               "window the map first against leakage from its edges", .old = "window"),
    {0}};

static const struct tex_tool tool = {
    "t_fft", "[MAP]",
    "the Fourier spectrum of a map, centred with the DC term in the middle (FFTW, any size)",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 0, 1};

int main(int argc, char **argv)
{
    static const enum tex_fft_output outs[] = {TEX_FFT_LOGMAG, TEX_FFT_MAG, TEX_FFT_PHASE,
                                               TEX_FFT_COMPLEX};
    struct tex_common c;
    struct opts o;
    int i;

    i = tex_cli_parse(&tool, argc, argv, &c, &o);
    const char *name = i < argc ? argv[i] : "-";
    tex_map *m = tex_cli_read(name), *s;

    if (!(s = tex_fft(m, outs[o.as], o.window == 1))) {
        tex_error_context(name);
        tex_die();
    }
    tex_map_free(m);
    tex_cli_write(s, &c);
    tex_map_free(s);
    free(c.cmdline);
    return 0;
}
