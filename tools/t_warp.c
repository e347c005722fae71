/* t_warp - domain perturbation: displace a map's lookups by another map */
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    double amount, centre, angle;
    int isotropic, edge;
    const char *size;
};

static const struct tex_param rows[] = {
    TEX_REAL_N("displacement", struct opts, amount, 0, 0.1, -100, 100, "A",
               "displacement in texture units (map widths) per unit of BY", .old = "-a amount"),
    TEX_REAL_N("neutral", struct opts, centre, 0, 0, -1e6, 1e6, "C",
               "value of BY that displaces nothing (0.5 for a symmetric push)", .old = "centre"),
    TEX_REAL(struct opts, angle, 0, 0, -1e6, 1e6, "DEG",
             "direction of the push of a 1-channel BY, degrees counter-clockwise from u"),
    TEX_FLAG(struct opts, isotropic, 0,
             "a 1-channel BY displaces along both axes (two decorrelated lookups)"),
    TEX_ENUM(struct opts, edge, 0, "wrap", "wrap|clamp",
             "lookups of MAP outside the unit square"),
    TEX_STRING(struct opts, size, 's', NULL, "N|WxH", "size of the result (default: MAP's)"),
    {0}};

static const struct tex_tool tool = {
    "t_warp", "MAP BY",
    "domain perturbation: MAP looked up at (u,v) + amount * BY(u,v), as turbulence makes "
    "marble from stripes",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 2, 2};

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), w, h;
    tex_map *m, *by, *r;
    struct tex_warp_opts wo;

    if (!strcmp(argv[i], "-") && !strcmp(argv[i + 1], "-"))
        tex_usage_die("standard input (-) can be read only once");
    w = h = 0;
    if (o.size && tex_parse_size(o.size, &w, &h) < 0)
        tex_usage_die("-s must be N or WxH with each side 1..%d (got '%s')", TEX_MAP_MAX_SIDE,
                      o.size);
    m = tex_cli_read(argv[i]);
    by = tex_cli_read(argv[i + 1]);
    if (!o.size) {
        w = m->w;
        h = m->h;
    }
    wo = (struct tex_warp_opts){o.amount, o.centre, o.angle, o.isotropic,
                                o.edge ? TEX_EDGE_CLAMP : TEX_EDGE_WRAP};
    if (!(r = tex_warp(m, by, &wo, w, h)))
        tex_die();
    tex_map_free(m);
    tex_map_free(by);
    tex_cli_write(r, &c);
    tex_map_free(r);
    free(c.cmdline);
    return 0;
}
