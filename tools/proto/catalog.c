/* catalog.c - the primitives and their parameter rows, as JSON for the page */
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
        tex_str_add(b, "}");
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

void api_prims(struct tex_str *b)
{
    char names[4096];
    tex_str_add(b, "{\"primitives\":[");
    for (int i = 0; tex_primitives[i]; i++)
        json_prim(b, tex_primitives[i], 0, i == 0);
    for (int i = 0; tex_procs_get(proto.procs, i); i++)
        json_prim(b, tex_procs_get(proto.procs, i), 1, 0);
    tex_str_add(b, "],\"palettes\":");
    tex_json_string(b, tex_palette_names(names, sizeof names) >= 0 ? names : "");
    tex_str_add(b, "}");
}
