/* t_convert - read a texture map in any format and write it in another */
#include <stdlib.h>

#include "textura.h"

static const struct tex_tool tool = {
    "t_convert", "[MAP]", "read a map (EXR, PNG, TIFF, PNM, PFM, BMP, TGA, HDR, JPEG...) and "
                          "write it in the format of the output's extension",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, NULL, 0, 1};

static tex_map *same(tex_map *band, void *arg)
{
    (void)arg;
    return band;
}

int main(int argc, char **argv)
{
    struct tex_common c;
    int i = tex_cli_parse(&tool, argc, argv, &c, NULL);

    /* EXR to EXR goes a band of rows at a time: a map of any size in little memory */
    tex_cli_stream(i < argc ? argv[i] : "-", &c, same, NULL);
    free(c.cmdline);
    return 0;
}
