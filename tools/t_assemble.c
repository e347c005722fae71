/* t_assemble - put the windows of a map back together, a band of rows at a time */
#include <stdlib.h>
#include <string.h>

#include "textura.h"

static const struct tex_tool tool = {
    "t_assemble", "WINDOW...", "assemble the EXR windows of a map (as t_noise --window or "
                               "t_apply --region make them) into the whole map, holding one "
                               "band of windows at a time",
    TEX_OPT_OUTPUT, NULL, 1, -1};

int main(int argc, char **argv)
{
    struct tex_common c;
    struct tex_out out = {.fd = 1};
    const char *name = "standard output";
    int i = tex_cli_parse(&tool, argc, argv, &c, NULL), r;

    if (c.mipmap) /* levels need the whole map: t_convert --mipmap makes them */
        tex_usage_die("--mipmap needs the whole map in memory: assemble, then t_convert "
                      "--mipmap");

    const char *file;
    enum tex_format f = tex_output_format(c.output, c.format, &file);
    if (f == TEX_FMT_UNKNOWN || tex_map_write_check(c.output, c.format) < 0)
        tex_die();
    if (f != TEX_FMT_EXR)
        tex_usage_die("%s: assembled maps are written as EXR", c.format ? c.format : c.output);
    if (file) {
        if (tex_out_open(&out, file) < 0) {
            tex_out_close(&out, -1);
            tex_die();
        }
        name = file;
    }
    r = tex_assemble((const char *const *)argv + i, argc - i, out.fd, name,
                     c.exr_tiles ? TEX_EXR_TILE : 0, (enum tex_compression)c.compression,
                     c.cmdline);
    if (out.fd != 1 && tex_out_close(&out, r) < 0)
        tex_die();
    if (r < 0)
        tex_die();
    free(c.cmdline);
    return 0;
}
