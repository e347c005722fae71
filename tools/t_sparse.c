/* t_sparse - Lewis's sparse convolution: grow a field with a sample's spectrum */
#include <stdlib.h>

#include "prim/spectral.h"
#include "textura.h"

struct opts {
    double density, falloff;
};

static const struct tex_param rows[] = {
    TEX_REAL(struct opts, density, 0, 30, 0.001, 1e6, "N",
             "random impulses per area of the sample", .old = "-d"),
    TEX_REAL(struct opts, falloff, 0, 2, 0, 100, "K",
             "the window exp(-K rho) over the sample, rho = 1 at the middle of its edges"),
    {0}};

static const struct tex_tool tool = {
    "t_sparse", "[SAMPLE]",
    "Lewis's sparse convolution: the sample, windowed by a radial exp(-K rho), summed at "
    "white-noise positions with white-noise weights into a larger map with the sample's spectrum "
    "(tiles)",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS | TEX_OPT_SIZE | TEX_OPT_SEED | TEX_OPT_WINDOW, rows, 0, 1};

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i;

    i = tex_cli_parse(&tool, argc, argv, &c, &o);
    if (c.win[2] > 0) /* accepted for the generators' sake, refused with the reason */
        tex_usage_die("sparse convolution cannot make a window of its map (--window): it "
                      "convolves the whole periodic map at once with one FFT");
    const char *name = i < argc ? argv[i] : "-";
    tex_map *s = tex_cli_read(name), *m;
    struct tex_sparse_spec sp = {o.density, o.falloff, (uint64_t)c.seed};

    if (!(m = tex_sparse_convolve(s, c.w, c.h, &sp))) {
        if (tex_errkind() == TEX_ERR_RUNTIME)
            tex_error_context(name);
        tex_die();
    }
    tex_map_free(s);
    tex_cli_write(m, &c);
    tex_map_free(m);
    free(c.cmdline);
    return 0;
}
