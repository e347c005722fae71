/* t_xform - rotate, scale, shift, expand and clip a texture map, filtered */
#include <math.h>
#include <stdlib.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    double rotate;
    struct tex_reals around, scale, shift, clip;
    int wrap;
    const char *expand;
    float background[4];
};

static const struct tex_param rows[] = {
    TEX_STRING(struct opts, expand, 0, NULL, "WxH",
               "first, centre the map on a W x H canvas of the background colour"),
    TEX_REAL(struct opts, rotate, 0, 0, -1e6, 1e6, "DEG",
             "then rotate counter-clockwise by DEG degrees"),
    TEX_REALS(struct opts, around, 0, NULL, -1e6, 1e6, 2, "X,Y",
              "centre of rotation in pixels (default: the centre of the map)"),
    TEX_REALS(struct opts, scale, 0, NULL, 1e-4, 1e4, 2, "SX[,SY]",
              "then scale to round(SX W) x round(SY H) pixels, filtered"),
    TEX_REALS(struct opts, shift, 0, NULL, -1e6, 1e6, 2, "DX,DY",
              "then move the content by DX,DY pixels (right, down)"),
    TEX_FLAG(struct opts, wrap, 0, "shifted content re-enters at the opposite side"),
    TEX_REALS(struct opts, clip, 0, NULL, 0, 65536, 4, "X0,Y0,X1,Y1",
              "last, keep the window [X0,X1) x [Y0,Y1) in whole pixels"),
    TEX_COLOR(struct opts, background, 0, "#000000",
              "colour of uncovered canvas; alpha < 1 adds an alpha channel"),
    {0}};

static const struct tex_tool tool = {
    "t_xform", "[MAP]",
    "expand, rotate, scale, shift and clip a texture map (in that order), with area-filtered "
    "resampling",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 0, 1};

static void step(tex_map **m, tex_map *next)
{
    if (!next)
        tex_die();
    tex_map_free(*m);
    *m = next;
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), ew = 0, eh = 0;
    tex_map *m;

    if (o.expand) {
        char *e;
        long a = strtol(o.expand, &e, 10), b = a;
        if (*e == 'x' || *e == 'X')
            b = strtol(e + 1, &e, 10);
        if (*e || a < 1 || b < 1 || a > TEX_MAP_MAX_SIDE || b > TEX_MAP_MAX_SIDE)
            tex_usage_die("--expand must be N or WxH with each side 1..%d (got '%s')",
                          TEX_MAP_MAX_SIDE, o.expand);
        ew = (int)a;
        eh = (int)b;
    }
    if (o.around.n == 1)
        tex_usage_die("--around needs X,Y (got one value)");
    if (o.shift.n == 1)
        tex_usage_die("--shift needs DX,DY (got one value)");
    if (o.clip.n && o.clip.n != 4)
        tex_usage_die("--clip needs X0,Y0,X1,Y1 (got %d values)", o.clip.n);
    for (int k = 0; k < o.clip.n; k++)
        if (o.clip.v[k] != floor(o.clip.v[k]))
            tex_usage_die("--clip takes whole pixels (got %g)", o.clip.v[k]);
    m = tex_cli_read(i < argc ? argv[i] : "-");
    if (o.expand)
        step(&m, tex_expand(m, ew, eh, o.background));
    if (o.rotate != 0) {
        double cx = o.around.n ? o.around.v[0] : m->w / 2.0;
        double cy = o.around.n ? o.around.v[1] : m->h / 2.0;
        step(&m, tex_rotate(m, o.rotate, cx, cy, o.background));
    }
    if (o.scale.n)
        step(&m, tex_scale(m, o.scale.v[0], o.scale.n > 1 ? o.scale.v[1] : o.scale.v[0]));
    if (o.shift.n)
        step(&m, tex_shift(m, o.shift.v[0], o.shift.v[1], o.wrap, o.background));
    if (o.clip.n)
        step(&m, tex_clip(m, (int)o.clip.v[0], (int)o.clip.v[1], (int)o.clip.v[2],
                          (int)o.clip.v[3]));
    tex_cli_write(m, &c);
    tex_map_free(m);
    free(c.cmdline);
    return 0;
}
