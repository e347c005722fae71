/* t_synth - texture synthesis from an example: a map of any size that looks like the sample */
#include <stdlib.h>

#include "textura.h"

struct opts {
    int neighbourhood, levels, candidates, passes, search;
    double randomness, guide_weight;
    const char *guide, *mask;
};

static const struct tex_param rows[] = {
    TEX_INT(struct opts, neighbourhood, 0, 5, 3, 15, "N",
            "side of the square neighbourhood compared (odd)", .old = "-n"),
    TEX_INT_N("pyramid_levels", struct opts, levels, 0, 4, 1, 10, "N",
              "most pyramid levels (fewer when the sample is too small for them)",
              .old = "-l levels"),
    TEX_INT(struct opts, candidates, 'k', 4, 1, 16, "K",
            "k-coherence candidates per sample pixel"),
    TEX_INT(struct opts, passes, 0, 2, 1, 8, "N", "correction passes per level"),
    TEX_REAL(struct opts, randomness, 0, 0.1, 0, 1, "R",
             "jitter of the upsampled positions, in units of two level pixels", .old = "-r"),
    TEX_STRING(struct opts, guide, 0, NULL, "MAP",
               "follow this map (the output's size): its light parts take the sample's light "
               "parts"),
    TEX_REAL(struct opts, guide_weight, 0, 0.2, 0, 100, "W",
             "weight of the guide against the neighbourhood"),
    TEX_STRING(struct opts, mask, 0, NULL, "MAP",
               "fill the sample's pixels where MAP > 0.5 from the rest (the output is the "
               "sample's size)"),
    TEX_ENUM(struct opts, search, 0, "coherent", "coherent|exhaustive",
             "k-coherence candidates (FLANN), or every sample position (slow reference)"),
    {0}};

static const struct tex_tool tool = {
    "t_synth", "[SAMPLE]",
    "texture synthesis from an example: multi-resolution neighbourhood matching with "
    "k-coherence candidates found by FLANN (Wei-Levoy, Lefebvre-Hoppe, Tong et al.)",
    TEX_OPT_OUTPUT | TEX_OPT_SIZE | TEX_OPT_SEED | TEX_OPT_TILE, rows, 0, 1};

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o);
    const char *name = i < argc ? argv[i] : "-";
    tex_map *s = tex_cli_read(name), *g = o.guide ? tex_cli_read(o.guide) : NULL;
    tex_map *k = o.mask ? tex_cli_read(o.mask) : NULL, *m;
    struct tex_synth_opts so = {o.neighbourhood, o.levels, o.candidates, o.passes, o.randomness,
                                o.guide_weight, c.tile, (uint64_t)c.seed, o.search,
                                tex_cli_progress_wanted(&c) ? tex_cli_progress : NULL, NULL};

    if (!(m = tex_synth(s, c.w, c.h, &so, g, k))) {
        if (tex_errkind() == TEX_ERR_RUNTIME)
            tex_error_context(name);
        tex_die();
    }
    tex_map_free(s);
    tex_map_free(g);
    tex_map_free(k);
    tex_cli_write(m, &c);
    tex_map_free(m);
    free(c.cmdline);
    return 0;
}
