/* t_apply - render a scene: texture maps applied to CSG objects (Whitted ray tracer) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "textura.h"

struct opts {
    const char *size;
    int spp;
    int linear;
    const char *spectral;
    int rgb;
    const char *model;
    const char *region;
    const char *help_scene;
    const char *help_scene_mdoc;
    int list_materials;
    int check_energy;
};

static const struct tex_param rows[] = {
    TEX_STRING(struct opts, size, 's', NULL, "WxH",
               "image size, overriding the scene's 'image' (1..16384 a side)"),
    TEX_INT(struct opts, spp, 0, 0, 0, 4096, "N",
            "samples per pixel, overriding the scene's 'samples' (0: the scene's)"),
    TEX_FLAG(struct opts, linear, 0,
             "write linear values to 8/16-bit formats too (default: sRGB-encode them)"),
    TEX_STRING(struct opts, spectral, 0, NULL, "N",
               "shade with N spectral samples (1..64), overriding the scene's 'colour'"),
    TEX_FLAG(struct opts, rgb, 0, "shade in RGB, overriding the scene's 'colour'"),
    TEX_STRING(struct opts, model, 0, NULL, "NAME",
               "shade every surface with this model "
               "(phong|cook-torrance|ward|ashikhmin-shirley)"),
    TEX_STRING(struct opts, region, 0, NULL, "X,Y,W,H",
               "render only the W x H region at X,Y of the image, the same pixels as the whole "
               "render (for render farms: t_assemble puts regions together)"),
    TEX_STRING(struct opts, help_scene, 0, NULL, "BLOCK",
               "list the words of a scene block (settings|camera|light|environment|texture|"
               "surface|apply|targets|object|hypertexture|hyperfunctions|density), or of "
               "application functions' expressions "
               "(quantities|functions), and exit"),
    TEX_STRING(struct opts, help_scene_mdoc, 0, NULL, "BLOCK",
               "the same list as mdoc, for t_apply(5)"),
    TEX_ENUM(struct opts, check_energy, 0, "warn", "warn|off",
             "warn of each surface whose Kd + max(Ks, Kr) + Kt can pass 1 (thesis 4.4), its "
             "own values or its textures', or not",
             .bare = "warn"),
    TEX_FLAG(struct opts, list_materials, 0,
             "list the materials of the database a scene reads by default (or SCENE's), "
             "and exit"),
    {0}};

static const struct tex_tool tool = {
    "t_apply", "SCENE", "render a scene of CSG objects with texture maps applied through "
                        "application functions (Whitted ray tracer, t_apply(5))",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 0, 1};

/* --list-materials: name, kind and source of each material, one a line. */
__attribute__((noreturn)) static void list_materials(const char *scene)
{
    char path[4096];
    struct tex_matdb db;

    if (tex_matdb_read(&db, tex_scene_materials_path(scene, path, sizeof path)) < 0)
        tex_die();
    for (int i = 0; i < db.count; i++)
        printf("%-16s %-10s %s\n", db.m[i].name,
               db.m[i].kind == TEX_CONDUCTOR ? "conductor" : "dielectric",
               db.m[i].source ? db.m[i].source : "");
    tex_matdb_free(&db);
    exit(0);
}

/* Integer formats get the sRGB transfer function; float formats stay linear. */
static int wants_srgb(const struct tex_common *c, const struct opts *o)
{
    if (o->linear || tex_cli_depth(c) == 32)
        return 0;
    const char *file;
    enum tex_format f = tex_output_format(c->output, c->format, &file);
    return !(f == TEX_FMT_EXR || f == TEX_FMT_PFM || f == TEX_FMT_HDR);
}

/* A row's default as the scene writes it: "0 0 -5", not "0,0,-5". */
static const char *scene_default(const struct tex_param *p, char *buf, size_t n)
{
    tex_param_default(p, buf, n);
    for (char *c = buf; *c; c++)
        if (*c == ',')
            *c = ' ';
    return buf;
}

/* A row's range, also for rows the parser reads itself; "" if any value goes. */
static const char *scene_range(const struct tex_param *p, char *buf, size_t n)
{
    if (p->type == TEX_P_SPECIAL && p->max > p->min)
        snprintf(buf, n, "%.10g..%.10g", p->min, p->max);
    else if (p->type == TEX_P_SPECIAL || p->type == TEX_P_FLAG)
        buf[0] = '\0';
    else
        tex_param_range(p, buf, n);
    return buf;
}

/* One word of an expression: "  mix(a, b, t)   help", or its mdoc item. */
static void help_word(const struct tex_scene_word *w, int mdoc)
{
    char lhs[64];
    if (!mdoc) {
        snprintf(lhs, sizeof lhs, "%s%s%s%s", w->name, w->args ? "(" : "", w->args ? w->args : "",
                 w->args ? ")" : "");
        printf("  %-28s %s\n", lhs, w->help);
        return;
    }
    if (w->args) { /* .Fn takes each argument on its own */
        printf(".It Fn %s", w->name);
        for (const char *a = w->args, *e; *a; a = *e ? e + 2 : e) {
            e = strchr(a, ',');
            e = e ? e : a + strlen(a);
            printf(" %.*s", (int)(e - a), a);
        }
        putchar('\n');
    } else
        printf(".It Ic %s\n", w->name);
    printf("%c%s.\n", w->help[0] >= 'a' && w->help[0] <= 'z' ? w->help[0] - 32 : w->help[0],
           w->help + 1);
}

/* --help-scene quantities|functions: the words of application functions. */
__attribute__((noreturn)) static void help_words(int functions, int mdoc)
{
    struct tex_scene_word w;
    if (mdoc)
        puts(".Bl -tag -width Ds");
    for (int i = 0; functions ? tex_scene_function(i, &w) : !!tex_quantities[i].name; i++)
        help_word(functions ? &w : &tex_quantities[i], mdoc);
    if (mdoc)
        puts(".El");
    exit(0);
}

/* --help-scene BLOCK and --help-scene-mdoc BLOCK: the block's rows. */
__attribute__((noreturn)) static void help_scene(const char *block, int mdoc)
{
    const struct tex_scene_block *b = tex_scene_blocks;
    if (!strcmp(block, "quantities") || !strcmp(block, "functions"))
        help_words(block[0] == 'f', mdoc);
    while (b->name && strcmp(b->name, block))
        b++;
    if (!b->name)
        tex_usage_die("--help-scene%s must be settings|camera|light|environment|texture|surface|"
                      "apply|targets|object|hypertexture|hyperfunctions|density|quantities|functions "
                      "(got '%s')", mdoc ? "-mdoc" : "", block);
    if (mdoc)
        puts(".Bl -tag -width Ds");
    for (const struct tex_param *p = b->rows; p->name; p++) {
        char rng[128], def[64];
        const char *meta = p->type == TEX_P_ENUM ? p->choices : p->meta;
        int has_def = p->type != TEX_P_FLAG && (p->type != TEX_P_SPECIAL || p->defstr);
        scene_range(p, rng, sizeof rng);
        scene_default(p, def, sizeof def);
        if (!mdoc) {
            char lhs[64];
            snprintf(lhs, sizeof lhs, "%s %s", p->name, meta ? meta : "");
            printf("  %-28s %s", lhs, p->help);
            if (*rng && p->type != TEX_P_ENUM)
                printf(" [%s]", rng);
            if (has_def)
                printf(" (default %s)", def);
            putchar('\n');
            continue;
        }
        printf(".It Ic %s", p->name);
        if (meta)
            printf(" Ar %s", meta);
        printf("\n%c%s", p->help[0] >= 'a' && p->help[0] <= 'z' ? p->help[0] - 32 : p->help[0],
               p->help + 1);
        if (*rng && p->type != TEX_P_ENUM)
            printf(", %s", rng);
        if (has_def)
            printf("; default %s", def);
        puts(".");
    }
    if (mdoc)
        puts(".El");
    exit(0);
}

__attribute__((noreturn)) static void die_freeing(struct tex_scene *s)
{
    tex_scene_free(s); /* keeps the error message */
    tex_die();
}

/* The image's region r (x, y, w, h) of scene s, a band of rows at a time. */
struct bands {
    struct tex_scene *s;
    const int *r;
};

static int render_band(void *arg, int y, int n, float *rows)
{
    const struct bands *b = arg;
    if (tex_render_rows(b->s, b->r[0], b->r[1] + y, b->r[2], n, rows) < 0)
        return -1;
    tex_progress_add(n);
    return 0;
}

/* The whole image's tiles, as the rest of the one bar (tex_render reports them). */
static void tiles_done(long done, long total, void *arg)
{
    static long last = -1;
    (void)arg;
    if (last < 0)
        tex_progress_stage(1, total);
    tex_progress_add(done - (last < 0 ? 0 : last));
    last = done;
}

/* Region r of the render written out: to a scanline EXR in bands, the image never held
 * whole (less memory to take and clear: the same pixels, each band a region); else whole,
 * sRGB-encoded for 8- and 16-bit formats. */
static void render_out(struct tex_scene *s, const int r[4], const struct tex_common *c,
                       const struct opts *o)
{
    int w, h;
    tex_scene_size(s, &w, &h);
    if (tex_cli_streams(c)) {
        struct bands b = {s, r};
        tex_map head = {.w = r[2], .h = r[3], .nc = 3};
        if (r[2] != w || r[3] != h)
            head.x0 = r[0], head.y0 = r[1], head.full_w = w, head.full_h = h;
        tex_progress_stage(1, r[3]);
        tex_cli_write_rows(&head, c, render_band, &b);
        free(head.history);
        return;
    }
    tex_map *img = tex_render_region(s, r[0], r[1], r[2], r[3], tiles_done, NULL);
    if (!img)
        tex_die();
    if (wants_srgb(c, o))
        for (size_t k = 0; k < tex_map_samples(img); k++)
            img->px[k] = tex_srgb_encode(img->px[k]);
    tex_cli_write(img, c);
    tex_map_free(img);
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o);
    if (o.help_scene || o.help_scene_mdoc)
        help_scene(o.help_scene ? o.help_scene : o.help_scene_mdoc, !o.help_scene);
    if (o.list_materials)
        list_materials(i < argc ? argv[i] : NULL);
    if (i >= argc)
        tex_usage_die("missing operand (usage: %s [options] %s)", tool.name, tool.operands);
    if (tex_map_write_check(c.output, c.format) < 0)
        tex_die(); /* now, not after the render */
    /* options first: a usage error must not leave the scene allocated (LSan) */
    int w = 0, h = 0;
    long bands = 0;
    if (o.size && (tex_parse_size(o.size, &w, &h) < 0 || w > TEX_SCENE_MAX_SIDE ||
                   h > TEX_SCENE_MAX_SIDE))
        tex_usage_die("--size '%s' must be N or WxH with 1..%d a side", o.size, TEX_SCENE_MAX_SIDE);
    if (o.spectral && o.rgb)
        tex_usage_die("--spectral and --rgb exclude each other");
    if (o.spectral) {
        char *end;
        bands = strtol(o.spectral, &end, 10);
        if (*end || end == o.spectral || bands < 1 || bands > TEX_COLOUR_MAX)
            tex_usage_die("--spectral '%s' must be a sample count in 1..%d", o.spectral,
                          TEX_COLOUR_MAX);
    }
    const struct tex_shading_model *model = NULL;
    if (o.model && !(model = tex_shading_find(o.model)))
        tex_usage_die("--model '%s' must be phong, cook-torrance, ward or ashikhmin-shirley",
                      o.model);
    /* one bar: the scene's loading (its maps sampled, read, mip-mapped) a tenth of it */
    tex_progress_stage(0.1, 1);
    tex_progress_hold(1);
    struct tex_scene *s = tex_scene_load(argv[i]);
    if (!s)
        tex_die();
    if ((o.size && tex_scene_set_size(s, w, h) < 0) || (o.spp && tex_scene_set_samples(s, o.spp) < 0))
        die_freeing(s);
    if ((o.spectral || o.rgb) && tex_scene_set_colour(s, (int)bands) < 0)
        die_freeing(s);
    tex_scene_set_model(s, model);
    if (c.threads)
        tex_scene_set_threads(s, c.threads);
    if (tex_scene_prepare(s) < 0)
        die_freeing(s);
    tex_progress_hold(0);
    tex_progress_add(1);
    int r[4] = {0, 0, 0, 0};
    tex_scene_size(s, &r[2], &r[3]);
    if (o.region && tex_parse_window(o.region, r[2], r[3], r) < 0) {
        tex_usage_error("--region must be X,Y,W,H with W, H >= 1 inside the %dx%d image (got '%s')",
                        r[2], r[3], o.region);
        die_freeing(s);
    }
    if (o.check_energy == 0)
        tex_scene_check_energy(s);
    if (!c.quiet)
        fputs(tex_scene_warnings(s), stderr);
    render_out(s, r, &c, &o);
    tex_scene_free(s);
    free(c.cmdline);
    return 0;
}
