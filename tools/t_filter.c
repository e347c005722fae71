/* t_filter - blur, sharpen, edges, emboss, median, noise and normal maps of a texture map */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ops/filter.h"
#include "textura.h"

struct opts {
    double sigma, strength, amount, angle;
    int radius, edge, direction;
    uint64_t seed; /* -S, for noise */
};

static const struct tex_param rows[] = {
    TEX_REAL(struct opts, sigma, 0, 1, 0.01, 1000, "S",
             "blur, sharpen: standard deviation of the Gaussian in pixels", .kinds = 0x009),
    TEX_INT(struct opts, radius, 'r', 1, 1, 1000, "R",
            "box, median: half-width of the square window (median: at most 15)",
            .kinds = 0x082),
    TEX_REAL(struct opts, strength, 0, 1, -1000, 1000, "K",
             "sharpen, edges: amount of enhancement; sobel: scale of the magnitude; emboss: "
             "relief; normal: height scale (per pixel)", .old = "-k", .kinds = 0x278),
    TEX_REAL_N("stddev", struct opts, amount, 0, 0.05, 0, 100, "SD",
               "noise: standard deviation of the added Gaussian noise", .old = "amount",
               .kinds = 0x100),
    TEX_REAL(struct opts, angle, 0, 135, -360, 360, "DEG",
             "emboss: direction of the light, degrees counter-clockwise from +x", .kinds = 0x040),
    TEX_FLAG(struct opts, direction, 0, "sobel: write the gradient direction (0..1 = 0..360 "
                                        "degrees) instead of the magnitude",
              .kinds = 0x010),
    TEX_ENUM(struct opts, edge, 0, "clamp", "clamp|wrap|mirror",
             "pixels beyond the border: repeat the border, wrap around (keeps tileable maps "
             "tileable) or mirror", .kinds = 0x6ff),
    {0}};

/* Each operation over a map, or a band of one (b: where it sits; noise and gradient
 * depend on the place) */
typedef tex_map *filter_fn(const tex_map *m, const struct opts *o, const struct tex_band *b);

static tex_map *blur(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_blur(m, o->sigma, (enum tex_edge)o->edge);
}
static tex_map *box(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_box(m, o->radius, (enum tex_edge)o->edge);
}
static tex_map *smooth(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_smooth(m, (enum tex_edge)o->edge);
}
static tex_map *sharpen(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_sharpen(m, o->sigma, o->strength, (enum tex_edge)o->edge);
}
static tex_map *sobel(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_sobel(m, o->direction, o->strength, (enum tex_edge)o->edge);
}
static tex_map *edges(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_edges(m, o->strength, (enum tex_edge)o->edge);
}
static tex_map *emboss(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_emboss(m, o->angle, o->strength, (enum tex_edge)o->edge);
}
static tex_map *median(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_median(m, o->radius, (enum tex_edge)o->edge);
}
static tex_map *noise(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    return tex_filter_noise_rows(m, o->amount, o->seed, b->y - b->margin);
}
static tex_map *normal(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    (void)b;
    return tex_filter_normal(m, o->strength, (enum tex_edge)o->edge);
}
static tex_map *gradient(const tex_map *m, const struct opts *o, const struct tex_band *b)
{
    return tex_filter_gradient_rows(m, (enum tex_edge)o->edge, b->full_h);
}

/* How far an operation reaches above and below a row: nothing, the 3x3 neighbours, the
 * Gaussian's ceil(4 sigma), or --radius rows */
enum reach { NONE, ONE, SIGMA, RADIUS };

/* The operations: name, function, reach, what it takes (see t_filter(1)).  The rows'
 * kinds are bits in this order. */
static const struct {
    const char *name;
    filter_fn *fn;
    enum reach reach;
    const char *help;
} ops[] = {
    {"blur", blur, SIGMA, "Gaussian blur (--sigma)"},
    {"box", box, RADIUS, "box filter (--radius)"},
    {"smooth", smooth, ONE, "3x3 binomial smoothing"},
    {"sharpen", sharpen, SIGMA, "unsharp mask (--sigma, --strength)"},
    {"sobel", sobel, ONE, "gradient magnitude or direction (--strength, --direction)"},
    {"edges", edges, ONE, "edge enhancement (--strength)"},
    {"emboss", emboss, ONE, "relief lit from --angle (--strength)"},
    {"median", median, RADIUS, "median of a window (--radius)"},
    {"noise", noise, NONE, "added Gaussian noise (--stddev, --seed)"},
    {"normal", normal, ONE, "a height map's tangent-space normal map (--strength)"},
    {"gradient", gradient, ONE, "a height map's gradient"},
};
enum { NOPS = sizeof ops / sizeof *ops };

struct job {
    filter_fn *fn;
    const struct opts *o;
};

/* A band's rows filtered: the filter over the band, of which the caller keeps the middle */
static tex_map *filter_band(tex_map *band, const struct tex_band *b, void *arg)
{
    const struct job *j = arg;
    return j->fn(band, j->o, b);
}

/* --help's summary, from the table: each operation and what it takes. */
static const char *summary(void)
{
    static char text[1024];
    size_t n = snprintf(text, sizeof text, "filter a texture map by OP, one of:");
    for (int k = 0; k < NOPS && n < sizeof text; k++)
        n += snprintf(text + n, sizeof text - n, "\n  %-10s %s", ops[k].name, ops[k].help);
    return text;
}

int main(int argc, char **argv)
{
    const struct tex_tool tool = {"t_filter", "OP [MAP]", summary(), TEX_OPT_OUTPUT | TEX_OPT_MAPS | TEX_OPT_SEED,
                                  rows, 1, 2};
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), k = 0;
    const char *op = argv[i++];
    char choices[256] = "";

    for (int j = 0; j < NOPS; j++)
        snprintf(choices + strlen(choices), sizeof choices - strlen(choices), "%s%s",
                 j ? "|" : "", ops[j].name);
    while (k < NOPS && strcmp(ops[k].name, op))
        k++;
    if (k == NOPS)
        tex_usage_die("unknown operation '%s' (one of %s)", op, choices);
    tex_cli_check_kinds(&tool, choices, k, "the operation");
    o.seed = (uint64_t)c.seed;
    struct job j = {ops[k].fn, &o};
    int margin = ops[k].reach == ONE      ? 1
                 : ops[k].reach == SIGMA  ? tex_blur_radius(o.sigma)
                 : ops[k].reach == RADIUS ? o.radius
                                          : 0;
    tex_cli_stream_window(i < argc ? argv[i] : "-", &c, margin, (enum tex_edge)o.edge, filter_band,
                          &j);
    free(c.cmdline);
    return 0;
}
