/* filter_ops.c - the registry of neighbourhood filters (manual: filter_ops.h) */
#include <string.h>

#include "base/error.h"
#include "ops/filter.h"
#include "ops/filter_ops.h"

#define A struct tex_filter_args
const struct tex_param tex_filter_rows[] = {
    TEX_REAL(A, sigma, 0, 1, 0.01, 1000, "S",
             "blur, sharpen: standard deviation of the Gaussian in pixels", .kinds = 0x009),
    TEX_INT(A, radius, 'r', 1, 1, 1000, "R",
            "box, median: half-width of the square window (median: at most 15)",
            .kinds = 0x082),
    TEX_REAL(A, strength, 0, 1, -1000, 1000, "K",
             "sharpen, edges: amount of enhancement; sobel: scale of the magnitude; emboss: "
             "relief; normal: height scale (per pixel)", .old = "-k", .kinds = 0x278),
    TEX_REAL_N("stddev", A, amount, 0, 0.05, 0, 100, "SD",
               "noise: standard deviation of the added Gaussian noise", .old = "amount",
               .kinds = 0x100),
    TEX_REAL(A, angle, 0, 135, -360, 360, "DEG",
             "emboss: direction of the light, degrees counter-clockwise from +x", .kinds = 0x040),
    TEX_FLAG(A, direction, 0, "sobel: write the gradient direction (0..1 = 0..360 "
                              "degrees) instead of the magnitude",
              .kinds = 0x010),
    TEX_ENUM(A, edge, 0, "clamp", "clamp|wrap|mirror",
             "pixels beyond the border: repeat the border, wrap around (keeps tileable maps "
             "tileable) or mirror", .kinds = 0x6ff),
    {0}};
#undef A

/* The operations, in tex_filter_ops's order. */
enum { BLUR, BOX, SMOOTH, SHARPEN, SOBEL, EDGES, EMBOSS, MEDIAN, NOISE, NORMAL, GRADIENT };

const struct tex_filter_op tex_filter_ops[] = {
    {"blur", TEX_REACH_SIGMA, "Gaussian blur (--sigma)", "sigma"},
    {"box", TEX_REACH_RADIUS, "box filter (--radius)", "radius"},
    {"smooth", TEX_REACH_ONE, "3x3 binomial smoothing", NULL},
    {"sharpen", TEX_REACH_SIGMA, "unsharp mask (--sigma, --strength)", "strength"},
    {"sobel", TEX_REACH_ONE, "gradient magnitude or direction (--strength, --direction)",
     "strength"},
    {"edges", TEX_REACH_ONE, "edge enhancement (--strength)", "strength"},
    {"emboss", TEX_REACH_ONE, "relief lit from --angle (--strength)", "strength"},
    {"median", TEX_REACH_RADIUS, "median of a window (--radius)", "radius"},
    {"noise", TEX_REACH_NONE, "added Gaussian noise (--stddev, --seed)", "stddev"},
    {"normal", TEX_REACH_ONE, "a height map's tangent-space normal map (--strength)",
     "strength"},
    {"gradient", TEX_REACH_ONE, "a height map's gradient", NULL},
    {NULL, 0, NULL, NULL}};

const struct tex_filter_op *tex_filter_op_find(const char *name)
{
    for (const struct tex_filter_op *op = tex_filter_ops; op->name; op++)
        if (!strcmp(op->name, name))
            return op;
    return NULL;
}

int tex_filter_op_index(const struct tex_filter_op *op)
{
    return (int)(op - tex_filter_ops);
}

tex_map *tex_filter_op_apply(const struct tex_filter_op *op, const tex_map *m,
                             const struct tex_filter_args *a, int y0, int full_h, int margin)
{
    enum tex_edge e = (enum tex_edge)a->edge;
    switch (tex_filter_op_index(op)) {
    case BLUR: return tex_filter_blur_rows(m, a->sigma, e, margin);
    case BOX: return tex_filter_box_rows(m, a->radius, e, margin);
    case SMOOTH: return tex_filter_smooth_rows(m, e, margin);
    case SHARPEN: return tex_filter_sharpen(m, a->sigma, a->strength, e);
    case SOBEL: return tex_filter_sobel(m, a->direction, a->strength, e);
    case EDGES: return tex_filter_edges(m, a->strength, e);
    case EMBOSS: return tex_filter_emboss(m, a->angle, a->strength, e);
    case MEDIAN: return tex_filter_median(m, a->radius, e);
    case NOISE: return tex_filter_noise_rows(m, a->amount, a->seed, y0);
    case NORMAL: return tex_filter_normal(m, a->strength, e);
    case GRADIENT: return tex_filter_gradient_rows(m, e, full_h);
    }
    tex_usage_error("no filter number %d", tex_filter_op_index(op));
    return NULL;
}

int tex_filter_margin(const struct tex_filter_op *op, const struct tex_filter_args *a)
{
    switch (op->reach) {
    case TEX_REACH_ONE: return 1;
    case TEX_REACH_SIGMA: return tex_blur_radius(a->sigma);
    case TEX_REACH_RADIUS: return a->radius;
    default: return 0;
    }
}
