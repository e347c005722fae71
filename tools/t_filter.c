/* t_filter - blur, sharpen, edges, emboss, median, noise and normal maps of a texture map */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ops/filter.h"
#include "textura.h"

struct opts {
    double sigma, strength, amount, angle;
    int radius, edge, direction;
};

static const struct tex_param rows[] = {
    TEX_REAL(struct opts, sigma, 0, 1, 0.01, 1000, "S",
             "blur, sharpen: standard deviation of the Gaussian in pixels"),
    TEX_INT(struct opts, radius, 'r', 1, 1, 1000, "R",
            "box, median: half-width of the square window (median: at most 15)"),
    TEX_REAL(struct opts, strength, 'k', 1, -1000, 1000, "K",
             "sharpen, edges: amount of enhancement; sobel: scale of the magnitude; emboss: "
             "relief; normal: height scale (per pixel)"),
    TEX_REAL(struct opts, amount, 0, 0.05, 0, 100, "SD",
             "noise: standard deviation of the added Gaussian noise"),
    TEX_REAL(struct opts, angle, 0, 135, -360, 360, "DEG",
             "emboss: direction of the light, degrees counter-clockwise from +x"),
    TEX_FLAG(struct opts, direction, 0, "sobel: write the gradient direction (0..1 = 0..360 "
                                        "degrees) instead of the magnitude"),
    TEX_ENUM(struct opts, edge, 0, "clamp", "clamp|wrap|mirror",
             "pixels beyond the border: repeat the border, wrap around (keeps tileable maps "
             "tileable) or mirror"),
    {0}};

static const struct tex_tool tool = {
    "t_filter", "OP [MAP]",
    "filter a texture map; OP is blur, box, smooth, sharpen, sobel, edges, emboss, median, "
    "noise, normal or gradient",
    TEX_OPT_OUTPUT | TEX_OPT_SEED, rows, 1, 2};

static const char *const ops[] = {"blur",   "box",    "smooth", "sharpen", "sobel",    "edges",
                                  "emboss", "median", "noise",  "normal",  "gradient", NULL};

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    const char *op = NULL;
    char **av = argv;
    int i, k;
    tex_map *m, *out = NULL;
    enum tex_edge e;

    /* "t_filter blur --sigma 2 MAP": take the operation first, then the options. */
    if (argc > 1 && argv[1][0] != '-') {
        if (!(av = malloc((size_t)argc * sizeof *av)))
            return 1;
        op = argv[1];
        av[0] = argv[0];
        memcpy(av + 1, argv + 2, (size_t)(argc - 2) * sizeof *av);
        argc--;
    }
    {
        struct tex_tool t = tool;
        if (op)
            t.min_operands = 0, t.max_operands = 1;
        i = tex_cli_parse(&t, argc, av, &c, &o);
    }
    if (!op) {
        op = av[i++];
    } else { /* put the operation back into the history line */
        size_t n = strlen(c.cmdline) + strlen(op) + 2, p = strlen(tex_progname);
        char *s = malloc(n);
        if (!s)
            return 1;
        snprintf(s, n, "%s %s%s", tex_progname, op, c.cmdline + p);
        free(c.cmdline);
        c.cmdline = s;
    }
    for (k = 0; ops[k] && strcmp(ops[k], op); k++)
        ;
    if (!ops[k])
        tex_usage_die("unknown operation '%s' (blur, box, smooth, sharpen, sobel, edges, emboss, "
                      "median, noise, normal or gradient)", op);
    m = tex_cli_read(i < argc ? av[i] : "-");
    e = (enum tex_edge)o.edge;
    switch (k) {
    case 0: out = tex_filter_blur(m, o.sigma, e); break;
    case 1: out = tex_filter_box(m, o.radius, e); break;
    case 2: out = tex_filter_smooth(m, e); break;
    case 3: out = tex_filter_sharpen(m, o.sigma, o.strength, e); break;
    case 4: out = tex_filter_sobel(m, o.direction, o.strength, e); break;
    case 5: out = tex_filter_edges(m, o.strength, e); break;
    case 6: out = tex_filter_emboss(m, o.angle, o.strength, e); break;
    case 7: out = tex_filter_median(m, o.radius, e); break;
    case 8: out = tex_filter_noise(m, o.amount, (uint64_t)c.seed); break;
    case 9: out = tex_filter_normal(m, o.strength, e); break;
    case 10: out = tex_filter_gradient(m, e); break;
    }
    if (!out)
        tex_die();
    tex_cli_write(out, &c);
    tex_map_free(out);
    tex_map_free(m);
    free(c.cmdline);
    if (av != argv)
        free(av);
    return 0;
}
