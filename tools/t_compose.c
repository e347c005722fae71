/* t_compose - run a pattern composition script (man 5 t_compose) */
#include <stdlib.h>
#include <string.h>

#include "lang/script.h"
#include "textura.h"

struct opts {
    int max_pixels;
};

static const struct tex_param rows[] = {
    TEX_INT(struct opts, max_pixels, 0, 64 << 20, 1, 1 << 30, "N",
            "refuse any image of the script larger than N pixels"),
    {0}};

static const struct tex_tool tool = {
    "t_compose", "[SCRIPT]",
    "build a texture map from a pattern composition script: a tessellation of images from "
    "files and primitives, transformed and combined",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 0, 1};

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o);
    const char *path = i < argc ? argv[i] : "-";
    int from_stdin = !strcmp(path, "-");
    struct tex_script_opts so = TEX_SCRIPT_DEFAULTS;
    size_t len;
    char *text = tex_read_text(path, (size_t)1 << 28, &len, "a script");
    tex_map *m;

    if (!text)
        tex_die();
    so.max_pixels = o.max_pixels;
    so.allow_stdin = !from_stdin;
    if (!(m = tex_script_run(text, len, from_stdin ? "stdin" : path, &so)))
        tex_die();
    free(text);
    tex_cli_write(m, &c);
    tex_map_free(m);
    free(c.cmdline);
    return 0;
}
