/* pipeline.c - a request made into a pipeline of tools: the primitive's tool with its
 * parameters, the steps, and the standard scene; every word checked as the tool will */
#include <limits.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "textura.h"
#include "proto.h"

/* Words go one after the other in pl->words: a path is as long as the folder's. */
const char *word(struct pipeline *pl, const char *fmt, ...)
{
    va_list ap;
    size_t room = sizeof pl->words - pl->used;
    char *w = pl->words + pl->used;
    va_start(ap, fmt);
    int n = vsnprintf(w, room, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= room)
        return NULL;
    pl->used += (size_t)n + 1;
    return w;
}

int arg(struct pipeline *pl, const char *w)
{
    struct stage *s = &pl->st[pl->n - 1];
    if (!w || s->n == MAX_WORDS) {
        snprintf(pl->err, sizeof pl->err, "too many words in one step (at most %d)", MAX_WORDS);
        return -1;
    }
    s->argv[s->n++] = w;
    return 0;
}

int stage(struct pipeline *pl, const char *tool)
{
    if (pl->n == MAX_STAGES) {
        snprintf(pl->err, sizeof pl->err, "too many steps (at most %d)", MAX_STEPS);
        return -1;
    }
    pl->st[pl->n++].n = 0;
    return arg(pl, word(pl, "%s", tool));
}

int fail(struct pipeline *pl, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pl->err, sizeof pl->err, fmt, ap);
    va_end(ap);
    return -1;
}

/* A file a row names (meta "FILE"): a plain file inside the working folder, whole path
 * resolved, within the input limit; the resolved path into w (NULL with pl->err). */
const char *inside(struct pipeline *pl, const char *opt, const char *v)
{
    char rel[PATH_MAX + 128], real[PATH_MAX];
    struct stat st;
    size_t max, n = strlen(proto.dir);
    snprintf(rel, sizeof rel, "%s%s%s", v[0] == '/' ? "" : proto.dir, v[0] == '/' ? "" : "/", v);
    if (!realpath(rel, real) || strncmp(real, proto.dir, n) || (real[n] != '/' && real[n]))
        return fail(pl, "--%s: '%.60s' is not a file inside the working folder", opt, v), NULL;
    if (stat(real, &st) < 0 || !S_ISREG(st.st_mode))
        return fail(pl, "--%s: '%.60s' is not a plain file", opt, v), NULL;
    if (tex_input_max(&max) < 0 || (unsigned long long)st.st_size > max)
        return fail(pl, "--%s: '%.60s' is over the input limit of %zu bytes", opt, v, max), NULL;
    return word(pl, "--%s=%s", opt, real);
}

/* A value for a row: checked by the row itself, as the tool will; no control characters
 * (a newline would end a scene's comment line). */
int plain_value(struct pipeline *pl, const char *name, const char *v)
{
    for (const char *c = v; *c; c++)
        if ((unsigned char)*c < 0x20 || *c == 0x7f)
            return fail(pl, "the value of %s has a control character (byte 0x%02x)", name,
                        (unsigned char)*c);
    if (strlen(v) > 100)
        return fail(pl, "value too long (%.20s...)", v);
    return 0;
}

static int check_value(struct pipeline *pl, const struct tex_param *p, const char *v)
{
    void *scratch = calloc(1, p->off + 4096); /* room for the row's value */
    int rc = plain_value(pl, p->name, v);
    if (rc)
        ;
    else if (!scratch || tex_param_parse(p, scratch, v, TEX_PARAM_OPTION) < 0)
        rc = fail(pl, "%s", tex_errmsg());
    free(scratch);
    return rc;
}

int is_name(const char *s)
{
    if (!*s || strlen(s) > 64)
        return 0;
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_' || *s == '-'))
            return 0;
    return 1;
}

/* A primitive's parameter as the option word of its row, the value checked by the row. */
int param_arg(struct pipeline *pl, const struct tex_param *row, const char *value)
{
    char name[72];
    snprintf(name, sizeof name, "%s", row->name);
    for (char *c = name; *c; c++) /* the option's spelling */
        if (*c == '_')
            *c = '-';
    if (row->type == TEX_P_FLAG) {
        if (strcmp(value, "0") && strcmp(value, "1"))
            return fail(pl, "--%s is 0 or 1 (got '%.20s')", name, value);
        return !strcmp(value, "1") ? arg(pl, word(pl, "--%s", name)) : 0;
    }
    if (check_value(pl, row, value) < 0)
        return -1;
    if (row->type == TEX_P_STRING && row->meta && !strcmp(row->meta, "FILE")) {
        const char *w = inside(pl, name, value);
        return w ? arg(pl, w) : -1;
    }
    return arg(pl, word(pl, "--%s=%s", name, value));
}

struct req {
    struct MHD_Connection *c;
    struct pipeline *pl;
    int size, failed;
};

/* p=NAME:VALUE: one parameter of the primitive. */
static enum MHD_Result each_param(void *cls, enum MHD_ValueKind kind, const char *key,
                                  const char *value)
{
    struct req *r = cls;
    const struct tex_primitive *prim = NULL;
    const char *colon;
    char name[72];
    (void)kind;
    if (r->failed || strcmp(key, "p") || !value)
        return MHD_YES;
    prim = tex_procs_find(proto.procs,
                          MHD_lookup_connection_value(r->c, MHD_GET_ARGUMENT_KIND, "prim"));
    if (!(colon = strchr(value, ':')) || colon - value >= (long)sizeof name - 1) {
        r->failed = fail(r->pl, "malformed parameter '%.40s' (NAME:VALUE)", value);
        return MHD_NO;
    }
    memcpy(name, value, colon - value);
    name[colon - value] = 0;
    const struct tex_param *row = tex_param_find(prim->params, name);
    if (!row) {
        r->failed = fail(r->pl, "%s has no parameter '%s'", prim->name, name);
        return MHD_NO;
    }
    r->failed = param_arg(r->pl, row, colon + 1);
    return r->failed ? MHD_NO : MHD_YES;
}

/* step=KIND:ARG:ARG...: one pipeline step, each word checked. */
static int step(struct pipeline *pl, const char *spec, int size)
{
    char buf[256], *w[8], *save = NULL; /* strtok_r: requests run on threads at once */
    int n = 0;
    double x;
    if (strlen(spec) >= sizeof buf)
        return fail(pl, "step too long");
    strcpy(buf, spec);
    for (char *s = strtok_r(buf, ":", &save); s && n < 8; s = strtok_r(NULL, ":", &save))
        w[n++] = s;
    if (!n)
        return fail(pl, "empty step");
    for (int i = 1; i < n; i++)
        if (tex_parse_real(w[i], &x) < 0 && !is_name(w[i]) && !is_saved_palette(w[i]))
            return fail(pl, "malformed step argument '%.40s'", w[i]);
    if (!strcmp(w[0], "palette") && n == 2 && is_saved_palette(w[1])) /* one the editor saved */
        return stage(pl, "t_palette") | arg(pl, word(pl, "%s/%s", proto.dir, w[1])) |
               arg(pl, "-");
    if (!strcmp(w[0], "palette") && n == 2) {
        char path[PATH_MAX];
        if (!is_name(w[1]) || tex_palette_find(w[1], path, sizeof path) < 0)
            return fail(pl, "unknown palette '%.40s'", w[1]);
        return stage(pl, "t_palette") | arg(pl, word(pl, "%s", w[1])) | arg(pl, "-");
    }
    if (!strcmp(w[0], "remap") && n == 3 && (!strcmp(w[1], "gamma") || !strcmp(w[1], "bias") ||
                                             !strcmp(w[1], "gain")))
        return stage(pl, "t_remap") |
               arg(pl, word(pl, "--%s=%s", !strcmp(w[1], "gain") ? "perlin-gain" : w[1], w[2])) |
               arg(pl, "-");
    if (!strcmp(w[0], "invert") && n == 1)
        return stage(pl, "t_remap") | arg(pl, "--invert") | arg(pl, "-");
    if (!strcmp(w[0], "filter") && n >= 2 && n <= 3) { /* filter:OP[:X], X its one parameter */
        static const char *const ops[][2] = {
            {"blur", "sigma"},      {"sharpen", "sigma"},      {"box", "radius"},
            {"median", "radius"},   {"sobel", "strength"},     {"edges", "strength"},
            {"emboss", "strength"}, {"normal", "strength"},    {"noise", "stddev"},
            {"smooth", NULL},       {"gradient", NULL}};
        for (size_t k = 0; k < sizeof ops / sizeof *ops; k++)
            if (!strcmp(w[1], ops[k][0])) {
                if ((n == 3) != (ops[k][1] != NULL))
                    return fail(pl, "filter %s takes %s", ops[k][0],
                                ops[k][1] ? "one value" : "no value");
                return stage(pl, "t_filter") | arg(pl, word(pl, "%s", w[1])) |
                       (n == 3 ? arg(pl, word(pl, "--%s=%s", ops[k][1], w[2])) : 0) |
                       arg(pl, "-");
            }
        return fail(pl, "unknown filter '%.40s'", w[1]);
    }
    if (!strcmp(w[0], "blur") && n == 2)
        return stage(pl, "t_filter") | arg(pl, "blur") | arg(pl, word(pl, "--sigma=%s", w[1])) |
               arg(pl, "-");
    if (!strcmp(w[0], "tile") && n == 3)
        return stage(pl, "t_tile") | arg(pl, word(pl, "--nu=%s", w[1])) |
               arg(pl, word(pl, "--nv=%s", w[2])) | arg(pl, word(pl, "-s%d", size)) | arg(pl, "-");
    return fail(pl, "unknown step '%.40s'", spec);
}

static enum MHD_Result each_step(void *cls, enum MHD_ValueKind kind, const char *key,
                                 const char *value)
{
    struct req *r = cls;
    (void)kind;
    if (r->failed || strcmp(key, "step") || !value)
        return MHD_YES;
    if (++r->pl->nsteps > MAX_STEPS) {
        r->failed = fail(r->pl, "too many steps (at most %d)", MAX_STEPS);
        return MHD_NO;
    }
    if (step(r->pl, value, r->size) < 0) {
        r->failed = -1;
        return MHD_NO;
    }
    return MHD_YES;
}

/* The pipeline of a request: the primitive's tool, its parameters, the steps. */
int build(struct MHD_Connection *c, struct pipeline *pl, int size)
{
    const char *name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "prim");
    const char *seed = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "seed");
    const char *tile = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "tile");
    const struct tex_primitive *p;
    struct req r = {c, pl, size, 0};
    double s;

    if (!name || !is_name(name) || !(p = tex_procs_find(proto.procs, name)))
        return fail(pl, "unknown primitive '%.40s'", name ? name : "");
    if (tex_primitive_get(name)) {
        if (stage(pl, word(pl, "t_%s", name)) < 0)
            return -1;
    } else if (stage(pl, "t_expr") | arg(pl, "--defs") | arg(pl, proto.defs) | arg(pl, name)) {
        return -1;
    }
    if (arg(pl, word(pl, "-s%d", size)) < 0)
        return -1;
    if (seed && (tex_parse_real(seed, &s) < 0 || s != (int)s || s < 0 || s > TEX_SEED_MAX))
        return fail(pl, "seed must be 0..%d (got '%.20s')", TEX_SEED_MAX, seed);
    if (seed && arg(pl, word(pl, "-S%d", (int)s)) < 0)
        return -1;
    if (tile && !strcmp(tile, "1") && arg(pl, "--tile") < 0)
        return -1;
    MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, each_param, &r);
    if (!r.failed)
        MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, each_step, &r);
    return r.failed ? -1 : 0;
}

/* Words as a shell reads them back: plain ones bare, others in single quotes, a quote
 * inside written '\'' */
void cmdline(const struct pipeline *pl, struct tex_str *b)
{
    for (int i = 0; i < pl->n; i++) {
        if (i)
            tex_str_add(b, " | ");
        for (int k = 0; k < pl->st[i].n; k++) {
            const char *w = pl->st[i].argv[k];
            int plain = *w && strspn(w, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                        "0123456789_-=.,/:") == strlen(w);
            tex_str_add(b, "%s%s", k ? " " : "", plain ? w : "'");
            for (; !plain && *w; w++)
                tex_str_bytes(b, *w == '\'' ? "'\\''" : w, *w == '\'' ? 4 : 1);
            if (!plain)
                tex_str_add(b, "'");
        }
    }
}

/* A scene's string: '"' and '\\' escaped; a control character cannot be written */
static int scene_string(struct tex_str *b, const char *s)
{
    tex_str_add(b, "\"");
    for (; *s; s++) {
        if ((unsigned char)*s < 0x20 || *s == 0x7f)
            return -1;
        if (*s == '"' || *s == '\\')
            tex_str_bytes(b, "\\", 1);
        tex_str_bytes(b, s, 1);
    }
    tex_str_add(b, "\"");
    return 0;
}

/* The standard scene (thesis 4.3.7): the map on a sphere and a box over a plane, through the
 * application function chosen.  Each view lights its function's effect: Ks on a dull surface
 * lit wide so the highlight spreads over the map; Kr with the floor textured, for the objects
 * to mirror it; bump with the strength given (t_apply's bump target's range). */
static const struct view {
    const char *fn, *light, *kd, *n, *floor_kd, *floor_n, *floor_apply;
} views[] = {
    {"Kd", "-3 5 -4", "0.8", "40", "0.7", "10", NULL},
    {"Ks", "0 1.6 -3.4", "0.08", "2", "0.08", "2", NULL},
    {"Kr", "-3 5 -4", "0.25", "40", "0.7", "10", "Kd = f"},
    {"bump", "-3 5 -4", "0.8", "40", "0.7", "10", NULL},
};

int scene_text(struct pipeline *pl, struct tex_str *s, const char *fn, const char *strength,
               const char *map)
{
    const struct view *v = NULL;
    char apply[64];
    double k = 0.2;
    for (size_t i = 0; i < sizeof views / sizeof *views; i++)
        if (!strcmp(fn ? fn : "Kd", views[i].fn))
            v = &views[i];
    if (!v)
        return fail(pl, "the application function must be Kd, Ks, Kr or bump (got '%.20s')", fn);
    if (strength && (tex_parse_real(strength, &k) < 0 || k < -1000 || k > 1000))
        return fail(pl, "the bump strength must be -1000..1000 (got '%.20s')", strength);
    if (!strcmp(v->fn, "bump"))
        snprintf(apply, sizeof apply, "bump = %.17g", k);
    else
        snprintf(apply, sizeof apply, "%s = f", v->fn);
    tex_str_add(s, "image 192 144\nsamples 1\nambient 0.25 0.25 0.25\nbackground 0.15 0.15 0.17\n"
             "camera { eye 0 1.3 -3.6 look 0 0.55 0 fov 42 }\n"
             "light point { position %s intensity 1 }\n"
             "texture m file ", v->light);
    if (scene_string(s, map) < 0)
        return fail(pl, "the map's path has a control character");
    tex_str_add(s, "\n"
             "surface ball { Kd %s Ks 0.3 n %s apply m { mapping sphere %s } }\n"
             "surface cube { Kd %s Ks 0.3 n %s apply m { mapping box %s } }\n"
             "surface floor { Kd %s Ks 0.1 n %s apply m { scale 0.5 %s } }\n"
             "sphere { centre -0.55 0.6 0 radius 0.6 surface ball }\n"
             "box { min 0.2 0 -0.35 max 0.9 0.7 0.35 surface cube }\n"
             "plane { surface floor }\n",
             v->kd, v->n, apply, v->kd, v->n, apply, v->floor_kd, v->floor_n,
             v->floor_apply ? v->floor_apply : apply);
    return 0;
}

int scene_stage(struct pipeline *pl, const char *fn, const char *strength, const char *map)
{
    char scene[PATH_MAX + 64];
    struct tex_str s = {0};
    if (scene_text(pl, &s, fn, strength, map) < 0) {
        free(s.s);
        return -1;
    }
    snprintf(scene, sizeof scene, "%s/scene.%lx.scene", proto.tmpdir,
             (unsigned long)pthread_self());
    FILE *f = fopen(scene, "w");
    if (!f || fwrite(s.s, 1, s.n, f) != s.n || fclose(f) != 0) {
        free(s.s);
        return fail(pl, "cannot write the scene");
    }
    free(s.s);
    pl->n = 0;
    return stage(pl, "t_apply") | arg(pl, word(pl, "%s", scene)) | arg(pl, "-q") |
           arg(pl, "--format=png");
}
