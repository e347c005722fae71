/* catalog.c - the primitives and their parameter rows, as JSON for the page */
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "io/json.h"
#include "textura.h"
#include "proto.h"

static void json_rows(struct tex_str *b, const struct tex_param *t)
{
    static const char *const types[] = {"int", "real", "flag", "enum", "reals", "colour",
                                        "string", "real", "special"};
    char buf[256];
    tex_str_add(b, "[");
    for (int i = 0; t && t[i].name; i++) {
        tex_str_add(b, "%s{\"name\":", i ? "," : "");
        tex_json_string(b, t[i].name);
        tex_str_add(b, ",\"type\":\"%s\",\"min\":%.17g,\"max\":%.17g,\"default\":", types[t[i].type],
             t[i].min, t[i].max);
        tex_json_string(b, tex_param_default(&t[i], buf, sizeof buf));
        tex_str_add(b, ",\"help\":");
        tex_json_string(b, t[i].help);
        tex_str_add(b, ",\"choices\":");
        tex_json_string(b, t[i].choices);
        /* the modes of the "mode" row it applies to, bit k for mode k (0: every mode) */
        tex_str_add(b, ",\"kinds\":%u}", t[i].kinds);
    }
    tex_str_add(b, "]");
}

static void json_prim(struct tex_str *b, const struct tex_primitive *p, int composed, int first)
{
    tex_str_add(b, "%s{\"name\":", first ? "" : ",");
    tex_json_string(b, p->name);
    tex_str_add(b, ",\"summary\":");
    tex_json_string(b, p->summary);
    tex_str_add(b, ",\"composed\":%d,\"grid\":%d,\"tile\":%d,\"params\":", composed,
         !!(p->flags & TEX_PRIM_GRID), !!(p->flags & TEX_PRIM_TILE));
    json_rows(b, p->params);
    tex_str_add(b, "}");
}

/* The palette names: the installed ones ("brick, clouds, ...") and NAME.pal files the
 * editor saved in the working folder, each a JSON string. */
static void json_palettes(struct tex_str *b)
{
    char names[4096];
    int first = 1;
    if (tex_palette_names(names, sizeof names) < 0)
        names[0] = 0;
    for (const char *k = names; *k;) {
        char one[128];
        size_t len = strcspn(k, ",");
        snprintf(one, sizeof one, "%.*s", (int)len, k);
        tex_str_add(b, first ? "" : ",");
        tex_json_string(b, one);
        first = 0;
        k += len;
        k += strspn(k, ", ");
    }
    int fd = openat(proto.workfd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC); /* its own offset */
    DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
    struct dirent *e;
    if (!d && fd >= 0)
        close(fd);
    for (int n = 0; d && n < 1000 && (e = readdir(d)); n++) /* bounded: a huge folder */
        if (is_saved_palette(e->d_name)) {
            tex_str_add(b, first ? "" : ",");
            tex_json_string(b, e->d_name);
            first = 0;
        }
    if (d)
        closedir(d);
}

void api_prims(struct tex_str *b)
{
    tex_str_add(b, "{\"primitives\":[");
    for (int i = 0; tex_primitives[i]; i++)
        json_prim(b, tex_primitives[i], 0, i == 0);
    for (int i = 0; tex_procs_get(proto.procs, i); i++)
        json_prim(b, tex_procs_get(proto.procs, i), 1, 0);
    tex_str_add(b, "],\"palettes\":[");
    json_palettes(b);
    tex_str_add(b, "]}");
}
