/* render_scene.c - the scene language of t_apply(5)
 *
 * A recursive-descent parser over the one lexer of Textura's languages (lang/lex.h), its
 * expressions through lang/expr.h and its blocks through their parameter rows
 * (render_params.c).  Every error names file:line:column of the token at fault.  All
 * memory of a scene hangs from it (a pool), so an error anywhere frees everything at once.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/colour_spectral.h"
#include "base/error.h"
#include "base/paths.h"
#include "io/file.h"
#include "render/matdb.h"
#include "ops/palette.h"
#include "render/scene.h"
#include "render/render_ct.h"
#include "render/anisotropic.h"
#include "render/appfn.h"
#include "render/hypertexture.h"
#include "lang/expr.h"
#include "lang/lex.h"
#include "lang/proc.h"

#define MAX_NEST 64

struct parser {
    const char *name;
    struct tex_scene *s;
    jmp_buf jb;
    int nest;
    int stdin_used;
    struct tex_matdb db; /* the materials database, read on first use */
    int have_db;
    struct tex_lexer lx; /* lx.t: the current token */
    /* read_row takes every number of a vector row or fails at the first one
     * missing ("expected a number"), as the shapes' words always have */
    int whole_vectors;
    int sample_size; /* tex_scene_opts */
    struct tex_tok kt; /* the word of the row a reader reads (struct tex_param's read) */
    size_t caplights, capsurfaces; /* room in s->lights and s->surfaces (pgrow) */
    int hyper_fn; /* 1 + the hypertexture function being read (enum tex_hyper_fn), or 0 */
};

/* The block a row's reader reads into (struct tex_param's read, ctx): the block's struct
 * (the scene, a light, a surface, an apply block, an object), and what its rows share */
struct block {
    void *obj;
    tex_xform *acc;          /* apply blocks and objects: the transforms read so far */
    int *placed;             /* apply blocks: 1 once one is read */
    struct tex_apply **tail; /* surfaces: where the next apply block goes */
    struct tex_object *ob;   /* objects */
};

static void fail_at(struct parser *ps, const struct tex_tok *t, int runtime, const char *fmt, ...)
    __attribute__((noreturn, format(printf, 4, 5)));

static void fail_at(struct parser *ps, const struct tex_tok *t, int runtime, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tex_lex_vfail(&ps->lx, runtime ? TEX_ERR_RUNTIME : TEX_ERR_USAGE, t->line, t->col, fmt, ap);
}
#define FAIL(ps, ...) fail_at(ps, &(ps)->lx.t, 0, __VA_ARGS__)

static void *palloc(struct parser *ps, size_t n)
{
    struct tex_scene *s = ps->s;
    if (s->npool == s->cpool) {
        size_t c = s->cpool ? 2 * s->cpool : 64;
        void **np = realloc(s->pool, c * sizeof *np);
        if (!np)
            fail_at(ps, &ps->lx.t, 1, "out of memory");
        s->pool = np;
        s->cpool = c;
    }
    void *m = calloc(1, n ? n : 1);
    if (!m)
        fail_at(ps, &ps->lx.t, 1, "out of memory");
    s->pool[s->npool++] = m;
    return m;
}

/* a, an array of n elements of size bytes from the pool, with room for one more: a copy at
 * twice the capacity *cap when it is full.  The old copies stay in the pool until the scene
 * goes, a geometric sum: a copy one longer per element took 990 MB for 2,000 lights. */
static void *pgrow(struct parser *ps, void *a, size_t n, size_t *cap, size_t size)
{
    if (n < *cap)
        return a;
    *cap = *cap ? 2 * *cap : 8;
    void *b = palloc(ps, *cap * size);
    if (n)
        memcpy(b, a, n * size);
    return b;
}

static char *pstrdup(struct parser *ps, const char *t, size_t n)
{
    char *d = palloc(ps, n + 1);
    memcpy(d, t, n);
    return d;
}

/* ---- lexer ---------------------------------------------------------------------- */

static void *lex_alloc(void *ctx, size_t n)
{
    return palloc(ctx, n);
}

static double number(struct parser *ps)
{
    char b[64];
    if (ps->lx.t.kind != TEX_TOK_NUM)
        FAIL(ps, "expected a number, found %s", tex_tok_desc(&ps->lx.t, b, sizeof b));
    double v = ps->lx.t.num;
    tex_lex_next(&ps->lx);
    return v;
}

static tex_v3 vec(struct parser *ps)
{
    double x = number(ps), y = number(ps), z = number(ps);
    return tex_v3_make(x, y, z);
}

static char *word(struct parser *ps, const char *what)
{
    char b[64];
    if (ps->lx.t.kind != TEX_TOK_NAME)
        FAIL(ps, "expected %s, found %s", what, tex_tok_desc(&ps->lx.t, b, sizeof b));
    char *w = pstrdup(ps, ps->lx.t.text, ps->lx.t.len);
    tex_lex_next(&ps->lx);
    return w;
}

/* ---- blocks read through parameter rows (render_params.c) ------------------------ */

/* "NAME must be LO..HI (got V)" at t unless lo <= v <= hi (whole: an integer). */
static double ranged(struct parser *ps, const char *name, double lo, double hi, int whole)
{
    struct tex_tok t = ps->lx.t;
    double v = number(ps);
    if (!(v >= lo && v <= hi) || (whole && v != floor(v)))
        fail_at(ps, &t, 0, "%s must be %.10g..%.10g (got %g)", name, lo, hi, v);
    return v;
}

/* Row name written as t, or in its other spelling (colour as color). */
static int is_row_word(const struct tex_tok *t, const char *name)
{
    static const char *const also[][2] = {{"colour", "color"}, {"centre", "center"}};
    if (tex_tok_is_word(t, name))
        return 1;
    for (size_t i = 0; i < sizeof also / sizeof also[0]; i++)
        if (!strcmp(name, also[i][0]) && tex_tok_is_word(t, also[i][1]))
            return 1;
    return 0;
}

/* The row of table rows for word t, for a block of the given kind (-1: any). */
static const struct tex_param *row_of(const struct tex_param *rows, const struct tex_tok *t,
                                      int kind)
{
    if (t->kind != TEX_TOK_NAME)
        return NULL;
    for (const struct tex_param *p = rows; p->name; p++)
        if (is_row_word(t, p->name) && (kind < 0 || !p->kinds || (p->kinds >> kind & 1)))
            return p;
    return NULL;
}

/* For an unknown word: "; did you mean NAME?" with the nearest row of the kind, or "". */
static const char *nearest_row(const struct tex_param *rows, int kind, const struct tex_tok *t)
{
    static _Thread_local char msg[96];
    char word[64], near[64];
    snprintf(word, sizeof word, "%.*s", (int)(t->len < 63 ? t->len : 63), t->text);
    msg[0] = 0;
    /* a word of the block's kind, else of another kind (which then says it does not apply) */
    if (t->kind == TEX_TOK_NAME && (tex_param_nearest(rows, kind, word, near, sizeof near) ||
                                    tex_param_nearest(rows, -1, word, near, sizeof near)))
        snprintf(msg, sizeof msg, "; did you mean %s?", near);
    return msg;
}

/* Row p's numbers, from vt, refused (tex_param_store's error); next, the word that ended
 * them short, or NULL.  "eye 0 1.5 inf": inf and nan are names to the lexer, and the count
 * alone ("eye takes 3 numbers (got 2)") hid what was wrong with the third. */
static void short_row(struct parser *ps, const struct tex_param *p, const struct tex_tok *vt,
                      const struct tex_tok *next)
{
    char name[64], text[64];
    if (next && next->kind == TEX_TOK_NAME && next->len < sizeof text) {
        char *end;
        memcpy(text, next->text, next->len);
        text[next->len] = '\0';
        double x = strtod(text, &end);
        if (*end == '\0' && !isfinite(x))
            fail_at(ps, next, 0, "%s takes finite numbers (got %s)",
                    tex_param_name(p, name, sizeof name, TEX_PARAM_WORD), text);
    }
    fail_at(ps, vt, 0, "%s", tex_errmsg());
}

/* Row p's value into obj: as many numbers as it stores, a word, or nothing (a flag). */
static void read_row(struct parser *ps, const struct tex_param *p, void *obj)
{
    struct tex_tok vt = ps->lx.t;
    double v[8];
    int k = 0, n = tex_param_count(p);
    if (p->type == TEX_P_ENUM || p->type == TEX_P_STRING) {
        char *w;
        if (vt.kind == TEX_TOK_STR) {
            w = pstrdup(ps, vt.text, vt.len);
            tex_lex_next(&ps->lx);
        } else {
            w = word(ps, "a name");
        }
        if (tex_param_parse(p, obj, w, TEX_PARAM_WORD) < 0)
            fail_at(ps, &vt, 0, "%s", tex_errmsg());
        return;
    }
    if (p->type == TEX_P_FLAG)
        v[k++] = 1;
    else
        do
            v[k++] = number(ps);
        while (k < n && k < 8 && (ps->lx.t.kind == TEX_TOK_NUM || ps->whole_vectors));
    if (tex_param_store(p, obj, v, k, TEX_PARAM_WORD) < 0)
        short_row(ps, p, &vt, k < n ? &ps->lx.t : NULL);
}

/* A block's own reading of a word kt of no row: 1 if it took it. */
typedef int (*words_fn)(struct parser *ps, const struct tex_tok *kt, struct block *b);

/* The value of row p (its word kt just taken) into block b: a SPECIAL row's through its
 * reader. */
static void read_value(struct parser *ps, const struct tex_param *p, const struct tex_tok *kt,
                       struct block *b)
{
    if (p->type != TEX_P_SPECIAL) {
        read_row(ps, p, b->obj);
        return;
    }
    ps->kt = *kt;
    p->read(ps, p, b);
}

/* `{ word value ... }` through rows (for kind, -1: any) into block b; words reads the
 * block's words of no row (or NULL).  Returns the rows seen, bit i for row i. */
static unsigned long long read_block(struct parser *ps, const struct tex_param *rows, int kind,
                                     struct block *b, words_fn words, const char *what)
{
    unsigned long long seen = 0;
    tex_lex_expect(&ps->lx, '{');
    while (!tex_tok_is_punct(&ps->lx.t, '}')) {
        struct tex_tok kt = ps->lx.t;
        const struct tex_param *p = row_of(rows, &kt, kind);
        if (p) {
            tex_lex_next(&ps->lx);
            seen |= 1ull << (p - rows);
            read_value(ps, p, &kt, b);
        } else if (kt.kind == TEX_TOK_EOF) {
            fail_at(ps, &kt, 0, "expected '}' to end %s, found the end of the file", what);
        } else if (!words || !words(ps, &kt, b)) {
            char b[64];
            fail_at(ps, &kt, 0, "unknown word %s in %s%s", tex_tok_desc(&kt, b, sizeof b), what,
                    nearest_row(rows, kind, &kt));
        }
    }
    tex_lex_next(&ps->lx);
    return seen;
}

/* Bit of row name in a read_block result. */
static unsigned long long row_bit(const struct tex_param *rows, const char *name)
{
    const struct tex_param *p = tex_param_find(rows, name);
    return p ? 1ull << (p - rows) : 0;
}

/* ---- textures ------------------------------------------------------------------- */

static struct tex_texture *find_texture(struct parser *ps, const struct tex_tok *t)
{
    for (int i = 0; i < ps->s->ntextures; i++)
        if (strlen(ps->s->textures[i]->name) == t->len &&
            !memcmp(ps->s->textures[i]->name, t->text, t->len))
            return ps->s->textures[i];
    return NULL;
}

static void add_texture(struct parser *ps, struct tex_texture *tx)
{
    struct tex_scene *s = ps->s;
    struct tex_texture **a = realloc(s->textures, (s->ntextures + 1) * sizeof *a);
    if (!a)
        fail_at(ps, &ps->lx.t, 1, "out of memory");
    s->textures = a;
    a[s->ntextures++] = tx;
}

/* The palette named by the current token (a name or a string), loaded once per scene. */
static const tex_palette *scene_palette(struct parser *ps)
{
    struct tex_tok at = ps->lx.t;
    struct tex_scene *s = ps->s;
    if (at.kind != TEX_TOK_NAME && at.kind != TEX_TOK_STR)
        FAIL(ps, "expected a palette name or file");
    char *name = pstrdup(ps, at.text, at.len);
    tex_lex_next(&ps->lx);
    for (int i = 0; i < s->npalettes; i++)
        if (!strcmp(s->palettes[i]->name, name))
            return s->palettes[i];
    tex_palette **a = realloc(s->palettes, (s->npalettes + 1) * sizeof *a);
    if (!a)
        fail_at(ps, &at, 1, "out of memory");
    s->palettes = a;
    if (!(a[s->npalettes] = tex_palette_load(name)))
        fail_at(ps, &at, tex_errkind() == TEX_ERR_RUNTIME, "%s", tex_errmsg());
    /* found again by the name the scene gives */
    char *n = strdup(name);
    if (!n) {
        tex_palette_free(a[s->npalettes]);
        fail_at(ps, &at, 1, "out of memory");
    }
    free(a[s->npalettes]->name);
    a[s->npalettes]->name = n;
    return a[s->npalettes++];
}

/* A sampled or read map through the texture's palette, as t_palette colours it: a scalar
 * map over its own range, a region map by indexed colours.  A geometric primitive's map is
 * already in the palette's colours (texture_field).  Takes m, returns the map to use. */
static tex_map *texture_colour(struct parser *ps, struct tex_texture *tx, tex_map *m,
                               const struct tex_tok *at)
{
    const struct tex_field *f = tx->field;
    if (!tx->palette || (f && f->colors && (f->prim->flags & TEX_PRIM_REGIONS) && !f->ids))
        return m;
    if (m->nc != 1) {
        int nc = m->nc;
        tex_map_free(m);
        fail_at(ps, at, 0, "palette colours a map of 1 channel, and texture '%s' has %d",
                tx->name, nc);
    }
    tex_map *c = tex_palette_map(tx->palette, m, NAN, NAN, TEX_OUTSIDE_CLAMP);
    tex_map_free(m);
    if (!c)
        fail_at(ps, at, 1, "%s", tex_errmsg());
    return c;
}

static void texture_map(struct parser *ps, struct tex_texture *tx, tex_map *m, const struct tex_tok *at)
{
    m = texture_colour(ps, tx, m, at);
    tx->mip = malloc(sizeof *tx->mip);
    if (!tx->mip) {
        tex_map_free(m);
        fail_at(ps, at, 1, "out of memory");
    }
    tx->mip[0] = m;
    tx->nlevels = 1;
    tx->subregions = m->subregions;
    if (tex_texture_build_mip(tx) < 0)
        fail_at(ps, at, 1, "%s", tex_errmsg());
}

/* 'texture NAME file PATH': the texture map read from a file, or '-' for standard input
 * (at most once per scene). */
static void texture_file(struct parser *ps, struct tex_texture *tx)
{
    struct tex_tok ft = ps->lx.t;
    char *path;
    if (tex_tok_is_punct(&ft, '-')) {
        path = pstrdup(ps, "-", 1);
        tex_lex_next(&ps->lx);
    } else if (ft.kind == TEX_TOK_STR || ft.kind == TEX_TOK_NAME) {
        path = pstrdup(ps, ft.text, ft.len);
        tex_lex_next(&ps->lx);
    } else {
        FAIL(ps, "expected a file name or '-' after 'file'");
    }
    if (!strcmp(path, "-")) {
        if (ps->stdin_used)
            fail_at(ps, &ft, 0, "only one texture can come from standard input");
        ps->stdin_used = 1;
    }
    if (tex_tok_is_word(&ps->lx.t, "palette")) {
        tex_lex_next(&ps->lx);
        tx->palette = scene_palette(ps);
    }
    /* A mip-mapped EXR brings its levels: used as the pyramid when they are
     * the ones tex_texture_build_mip would make (sizes halved, rounded down),
     * and the texture is not recoloured through a palette nor of region ids. */
    int n = 0;
    tex_map **lv = tex_map_read_levels(path, &n);
    if (!lv)
        fail_at(ps, &ft, 1, "cannot read map '%s': %s", path, tex_errmsg());
    int usable = n > 1 && !tx->palette && !lv[0]->subregions;
    for (int l = 1; usable && l < n; l++)
        usable = lv[l]->w == (lv[l - 1]->w > 1 ? lv[l - 1]->w / 2 : 1) &&
                 lv[l]->h == (lv[l - 1]->h > 1 ? lv[l - 1]->h / 2 : 1) && lv[l]->nc == lv[0]->nc;
    usable = usable && lv[n - 1]->w == 1 && lv[n - 1]->h == 1;
    if (!usable) {
        tex_map *m = lv[0];
        for (int l = 1; l < n; l++)
            tex_map_free(lv[l]);
        free(lv);
        texture_map(ps, tx, m, &ft);
        return;
    }
    tx->mip = lv;
    tx->nlevels = n;
    tx->subregions = 0;
    tx->levels_read = 1;
}

/* The block '{ KEY VALUE ... }' of a primitive's texture: 'solid', the flags of
 * tex_field_rows (no value), and the others with a value. */
static void texture_params(struct parser *ps, struct tex_texture *tx,
                           const struct tex_primitive *prim, const char *pname)
{
    struct tex_field *f = tx->field;
    tex_lex_expect(&ps->lx, '{');
    while (!tex_tok_is_punct(&ps->lx.t, '}')) {
        struct tex_tok kt = ps->lx.t;
        char *key = word(ps, "a parameter name");
        const struct tex_param *fr = tex_param_find(tex_field_rows, key);
        if (!strcmp(key, "solid")) {
            if (!(prim->flags & TEX_PRIM_3D))
                fail_at(ps, &kt, 0, "primitive '%s' has no solid (3D) form", pname);
            tx->solid = 1;
        } else if (!strcmp(key, "palette")) {
            tx->palette = scene_palette(ps);
        } else if (fr && fr->type == TEX_P_FLAG) { /* tile, ids: no value */
            if (tex_field_set(f, key, "") < 0)
                fail_at(ps, &kt, 0, "%s", tex_errmsg());
        } else {
            struct tex_tok vt = ps->lx.t;
            char *val;
            if (vt.kind == TEX_TOK_NUM || vt.kind == TEX_TOK_STR || vt.kind == TEX_TOK_NAME)
                val = pstrdup(ps, vt.text, vt.len);
            else
                FAIL(ps, "expected a value for '%s'", key);
            tex_lex_next(&ps->lx);
            /* seed, size (tex_field_rows) or a parameter of the primitive */
            if (tex_field_set(f, key, val) < 0)
                fail_at(ps, fr ? &vt : &kt, 0, "%s", tex_errmsg());
        }
    }
    tex_lex_next(&ps->lx);
}

/* Start the primitive's field, and sample it into a texture map unless it is evaluated
 * at each hit (a solid texture, or a 2D primitive without a size). */
static void texture_field(struct parser *ps, struct tex_texture *tx,
                          const struct tex_primitive *prim, const char *pname,
                          const struct tex_tok *pt)
{
    struct tex_field *f = tx->field;
    int size = f->size;
    /* a grid primitive is sampled into a map, unless solid: then its point form at each hit
     * (a solid fBm has its noise's detail at every distance, band-limited there) */
    if (prim->flags & TEX_PRIM_GRID && !size && !(tx->solid && prim->eval3))
        size = ps->sample_size;
    if (!(prim->flags & (TEX_PRIM_2D | TEX_PRIM_3D | TEX_PRIM_GRID)))
        fail_at(ps, pt, 0, "primitive '%s' cannot be evaluated", pname);
    if (!size && !tx->solid && !(prim->flags & TEX_PRIM_2D))
        size = ps->sample_size;
    /* a geometric primitive's colours come from sampling (antialiased coverage); at points
     * it gives only region ids */
    if (!size && !tx->solid && (prim->flags & TEX_PRIM_REGIONS) && !f->ids)
        size = ps->sample_size;
    if (tex_field_init(f, size, size) < 0)
        fail_at(ps, pt, 0, "%s", tex_errmsg());
    if (tx->palette && (prim->flags & TEX_PRIM_REGIONS) && !f->ids) { /* as t_checker --palette */
        float *c = tex_palette_region_colours(tx->palette, f->nregions);
        if (!c)
            fail_at(ps, pt, 1, "%s", tex_errmsg());
        float *pc = palloc(ps, sizeof *c * 3 * (f->nregions > 0 ? f->nregions : 1));
        memcpy(pc, c, sizeof *c * 3 * f->nregions);
        free(c);
        f->colors = (const float(*)[3])pc;
    }
    if (size) {
        tex_map *m;
        if (prim->flags & TEX_PRIM_GRID) {
            m = tex_map_new(size, size, f->nc);
            if (m && prim->grid(f, m) < 0) {
                tex_map_free(m);
                m = NULL;
            }
        } else {
            m = tex_field_sample(f);
        }
        if (!m)
            fail_at(ps, pt, 1, "%s", tex_errmsg());
        if (f->ids && (prim->flags & TEX_PRIM_REGIONS))
            m->subregions = f->nregions > 0 ? f->nregions : 1;
        texture_map(ps, tx, m, pt);
    }
}

/* 'primitive NAME(...) = EXPR', a composed primitive (lang/proc.h), or
 * 'primitives "FILE"', a file of them: named by later textures. */
static void parse_primitive(struct parser *ps, const struct tex_tok *kt)
{
    if (!ps->s->procs && !(ps->s->procs = tex_procs_new()))
        fail_at(ps, kt, 1, "out of memory");
    if (tex_tok_is_word(kt, "primitive")) {
        tex_procs_define(ps->s->procs, &ps->lx);
        return;
    }
    struct tex_tok ft = ps->lx.t;
    if (ft.kind != TEX_TOK_STR)
        FAIL(ps, "expected a file name in quotes after 'primitives'");
    char *path = pstrdup(ps, ft.text, ft.len);
    if (tex_procs_read(ps->s->procs, path) < 0)
        fail_at(ps, &ft, tex_errkind() == TEX_ERR_RUNTIME, "%s", tex_errmsg());
    tex_lex_next(&ps->lx);
}

static void parse_texture(struct parser *ps)
{
    struct tex_tok at = ps->lx.t;
    char *name = word(ps, "a texture name");
    if (find_texture(ps, &at))
        fail_at(ps, &at, 0, "texture '%s' is defined twice", name);
    struct tex_texture *tx = calloc(1, sizeof *tx);
    if (!tx)
        fail_at(ps, &at, 1, "out of memory");
    add_texture(ps, tx); /* freed with the scene from here on */
    tx->name = name;
    tx->line = at.line;
    tx->col = at.col;
    if (tex_tok_is_word(&ps->lx.t, "file")) {
        tex_lex_next(&ps->lx);
        texture_file(ps, tx);
        return;
    }
    struct tex_tok pt = ps->lx.t;
    char *pname = word(ps, "'file' or a primitive name");
    const struct tex_primitive *prim = tex_procs_find(ps->s->procs, pname);
    if (!prim)
        fail_at(ps, &pt, 0, "%s", tex_errmsg());
    if (!(tx->field = tex_field_new(prim)))
        fail_at(ps, &pt, 1, "out of memory");
    tx->field->style = TEX_PARAM_WORD;
    texture_params(ps, tx, prim, pname);
    texture_field(ps, tx, prim, pname, &pt);
}

/* ---- expressions ---------------------------------------------------------------- */

/* palette(NAME, x): x's mean through a palette, x clamped to [0, 1]. */
static struct tex_enode *palette_call(struct tex_expr_parser *xp)
{
    struct parser *ps = xp->ctx;
    struct tex_enode *e = tex_expr_node(&ps->lx, TEX_EK_CALL, &ps->lx.t);
    e->op = TEX_EOP_PALETTE;
    tex_lex_next(&ps->lx);
    tex_lex_expect(&ps->lx, '(');
    e->ptr = scene_palette(ps);
    if (tex_tok_is_punct(&ps->lx.t, ')'))
        FAIL(ps, "palette takes 2 arguments: a palette and a value");
    tex_lex_expect(&ps->lx, ',');
    tex_expr_enter(xp);
    e->a = tex_expr_parse(xp);
    tex_expr_leave(xp);
    if (tex_tok_is_punct(&ps->lx.t, ','))
        FAIL(ps, "palette takes 2 arguments: a palette and a value");
    tex_lex_expect(&ps->lx, ')');
    return e;
}

/* An operand of an application function: f, p, a quantity of the hit (tex_quantities),
 * palette(NAME, x) or a texture's name (a cascade).  Numbers, parentheses, minus and
 * functions are lang/expr.c's. */
static struct tex_enode *operand(struct tex_expr_parser *xp)
{
    struct parser *ps = xp->ctx;
    char b[64];
    struct tex_enode *e;
    struct tex_tok t = ps->lx.t;
    if (t.kind != TEX_TOK_NAME)
        FAIL(ps, "expected an expression, found %s", tex_tok_desc(&t, b, sizeof b));
    if (tex_tok_is_word(&t, "palette")) {
        struct tex_lexer peek = ps->lx;
        tex_lex_next(&peek);
        if (tex_tok_is_punct(&peek.t, '('))
            return palette_call(xp);
    }
    e = tex_expr_node(&ps->lx, TEX_EK_LEAF, &ps->lx.t);
    e->op = -1;
    for (int q = 0; q < TEX_Q_COUNT; q++)
        if (tex_tok_is_word(&t, tex_quantities[q].name))
            e->op = TEX_LEAF_Q + q;
    if (tex_tok_is_word(&t, "f")) {
        e->op = TEX_LEAF_F;
    } else if (tex_tok_is_word(&t, "p")) {
        e->op = TEX_LEAF_P;
    } else if (e->op < 0) {
        e->op = TEX_LEAF_TEX;
        if (!(e->ptr = find_texture(ps, &t))) {
            struct tex_lexer peek = ps->lx;
            tex_lex_next(&peek);
            if (tex_tok_is_punct(&peek.t, '(')) {
                char known[512];
                size_t k = 0;
                for (const struct tex_expr_func *fn = tex_expr_funcs; fn->name; fn++)
                    k += (size_t)snprintf(known + k, sizeof known - k, "%s, ", fn->name);
                FAIL(ps, "unknown function '%.*s' (%spalette)", (int)t.len, t.text, known);
            }
            FAIL(ps, "unknown name '%.*s' in an expression (f, p, a quantity such as dist or "
                     "ndotv, a number, a function or a texture)", (int)t.len, t.text);
        }
    }
    tex_lex_next(&ps->lx);
    return e;
}

/* An application function, compiled for the renderer. */
static struct tex_expr *expr(struct parser *ps)
{
    static const struct tex_expr_lang lang = {tex_expr_arith_binops, operand};
    struct tex_expr_parser xp = {&ps->lx, &lang, ps, 0, 0};
    struct tex_expr *x = tex_expr_compile(&ps->lx, tex_expr_parse(&xp));
    return x;
}

/* ---- surfaces ------------------------------------------------------------------- */

/* The application-function parameter named by t (rows Ka..ior, bump or normal), or -1. */
static int sparam(const struct tex_tok *t)
{
    for (int i = 0; i < TEX_SP_COUNT; i++)
        if (tex_tok_is_word(t, tex_sparam_row(i)->name))
            return i;
    return -1;
}

static void parse_fns(struct parser *ps, struct tex_apply *ap, int region)
{
    char b[64];
    for (;;) {
        int sp = sparam(&ps->lx.t);
        if (sp < 0)
            return;
        tex_lex_next(&ps->lx);
        if (!tex_tok_is_punct(&ps->lx.t, '='))
            FAIL(ps, "expected '=' after %s, found %s", tex_sparam_row(sp)->name,
                 tex_tok_desc(&ps->lx.t, b, sizeof b));
        tex_lex_next(&ps->lx);
        struct tex_appfn *fn = palloc(ps, sizeof *fn), **tail = &ap->fns;
        fn->region = region;
        fn->param = sp;
        fn->lo = tex_sparam_row(sp)->min; /* looked up once, not per hit */
        fn->hi = tex_sparam_row(sp)->max;
        struct tex_tok et = ps->lx.t;
        fn->e = expr(ps);
        int nc = ap->tex->mip ? ap->tex->mip[0]->nc : ap->tex->palette ? 3 : ap->tex->field->nc;
        for (int i = 0; sp == TEX_SP_NORMAL && i < fn->e->n; i++)
            if (fn->e->code[i].op == TEX_EOP_LEAF && fn->e->code[i].leaf == TEX_LEAF_F && nc < 3)
                fail_at(ps, &et, 0, "a normal map needs 3 channels, and texture '%s' has %d",
                        ap->tex->name, nc);
        while (*tail)
            tail = &(*tail)->next;
        *tail = fn;
    }
}

static const struct tex_surface *find_surface(struct parser *ps, const struct tex_tok *t);

/* The application functions of an apply block: its words of no row */
static int apply_words(struct parser *ps, const struct tex_tok *kt, struct block *b)
{
    if (sparam(kt) < 0)
        return 0;
    parse_fns(ps, b->obj, 0);
    return 1;
}

void tex_scene_read_cross(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_apply *ap = ((struct block *)ctx)->obj;
    struct tex_tok ct = ps->lx.t;
    if (ct.kind != TEX_TOK_NAME || !(ap->cross = find_texture(ps, &ct)))
        FAIL(ps, "%s needs a texture's name", p->name);
    tex_lex_next(&ps->lx);
}

void tex_scene_read_stretch(void *reader, const struct tex_param *p, void *ctx)
{
    struct tex_apply *ap = ((struct block *)ctx)->obj;
    (void)reader, (void)p;
    ap->nu = ap->nv = 1;
}

void tex_scene_read_region(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    int r = (int)ranged(ps, p->name, p->min, p->max, 1);
    tex_lex_expect(&ps->lx, '{');
    parse_fns(ps, ((struct block *)ctx)->obj, r);
    tex_lex_expect(&ps->lx, '}');
}

/* The projection's frame (thesis 5.2.1.3): y along the axis, then the block's rotations and
 * translations, as POV-Ray's texture transforms; checked against the mapping. */
static void apply_projection(struct parser *ps, struct tex_apply *ap, unsigned long long seen,
                             const struct tex_tok *at)
{
    tex_v3 a = ap->axis;
    if (!(tex_v3_dot(a, a) > 1e-24))
        fail_at(ps, at, 0, "the projection axis must not be zero (got %g %g %g)", a.x, a.y, a.z);
    if (!(ap->wave[1] > 0))
        fail_at(ps, at, 0, "wave needs a wavelength L > 0 (got %g)", ap->wave[1]);
    if (ap->mapping == TEX_MAP_CROSS && !ap->cross)
        fail_at(ps, at, 0, "mapping cross needs 'cross TEXTURE', the map on the y-z plane");
    if (seen & row_bit(tex_apply_rows, "axis")) {
        tex_xform f;
        tex_xform_frame(&f, tex_v3_make(0, 0, 0), a, 1, 1);
        tex_xform_mul(&ap->place, &ap->place, &f);
        ap->placed = 1;
    }
    if (ap->placed && ap->mapping == TEX_MAP_NATURAL)
        fail_at(ps, at, 0, "axis, translate and rotate place projections; mapping natural "
                           "follows the shape's own (u,v)");
    if (ap->placed && tex_xform_invert(&ap->to_tex, &ap->place) < 0)
        fail_at(ps, at, 0, "the texture's transform is singular");
}

static struct tex_apply *parse_apply(struct parser *ps)
{
    struct tex_tok at = ps->lx.t;
    const struct tex_texture *tx = at.kind == TEX_TOK_NAME ? find_texture(ps, &at) : NULL;
    if (!tx) {
        char b[64];
        FAIL(ps, "unknown texture %s", tex_tok_desc(&at, b, sizeof b));
    }
    tex_lex_next(&ps->lx);
    struct tex_apply *ap = palloc(ps, sizeof *ap);
    if (tex_params_defaults(tex_apply_rows, ap) < 0)
        fail_at(ps, &at, 0, "%s", tex_errmsg());
    ap->tex = tx;
    ap->line = at.line;
    ap->col = at.col;
    tex_xform_identity(&ap->place);
    struct block b = {.obj = ap, .acc = &ap->place, .placed = &ap->placed};
    unsigned long long seen = read_block(ps, tex_apply_rows, -1, &b, apply_words, "an apply block");
    if ((seen & row_bit(tex_apply_rows, "window")) && !(ap->u2 > ap->u1 && ap->v2 > ap->v1))
        fail_at(ps, &at, 0, "window needs u1 < u2 and v1 < v2");
    apply_projection(ps, ap, seen, &at);
    if ((seen & row_bit(tex_apply_rows, "size")) && !(ap->size[0] > 0 && ap->size[1] > 0))
        fail_at(ps, &at, 0, "size needs W > 0 and H > 0 (got %g %g)", ap->size[0], ap->size[1]);
    if (ap->size[0] > 0 && ap->mapping != TEX_MAP_NATURAL)
        fail_at(ps, &at, 0, "size sets a natural mapping's map size; planar and world mappings "
                            "take scale");
    if (ap->mapping == TEX_MAP_SOLID && tx->field && !tx->solid && !tx->mip)
        fail_at(ps, &at, 0, "texture '%s' is 2D; add 'solid' to it", tx->name);
    return ap;
}

/* ---- Cook-Torrance parameters and the materials database ---------------------------- */

static struct tex_ct *surface_ct(struct parser *ps, struct tex_surface *sf)
{
    if (!sf->ct) {
        sf->ct = palloc(ps, sizeof *sf->ct);
        sf->ct->facets.dist = TEX_FACET_BECKMANN; /* render_ct.h's defaults */
        sf->ct->facets.m = TEX_CT_M;
        sf->ct->s = TEX_CT_S;
    }
    return sf->ct;
}

static void load_materials(struct parser *ps, const char *path, const struct tex_tok *at)
{
    if (ps->have_db)
        tex_matdb_free(&ps->db);
    ps->have_db = 0;
    if (tex_matdb_read(&ps->db, path) < 0)
        fail_at(ps, at, tex_errkind() == TEX_ERR_RUNTIME, "materials: %s", tex_errmsg());
    ps->have_db = 1;
}

const char *tex_scene_materials_path(const char *scene, char *path, size_t n)
{
    const char *env = getenv("TEXTURA_MATERIALS");
    const char *slash = scene ? strrchr(scene, '/') : NULL;
    int dl = slash ? (int)(slash - scene) + 1 : 0;
    FILE *f;

    if (env && *env) {
        snprintf(path, n, "%s", env);
        return path;
    }
    snprintf(path, n, "%.*smaterials.txt", dl, scene ? scene : "");
    if (scene && (f = fopen(path, "rb")))
        fclose(f);
    else
        snprintf(path, n, "%s/patterns/materials.txt", tex_install_dir(TEX_DIR_DATA));
    return path;
}

static void default_materials(struct parser *ps, const struct tex_tok *at)
{
    char path[4096];
    load_materials(ps, tex_scene_materials_path(ps->name, path, sizeof path), at);
}

/* A copy of the named material in the scene's pool (the database is freed after parsing). */
static const struct tex_matdb_entry *find_material(struct parser *ps, const struct tex_tok *at,
                                                   const char *name)
{
    if (!ps->have_db)
        default_materials(ps, at);
    const struct tex_matdb_entry *e = tex_matdb_find(&ps->db, name);
    if (!e)
        fail_at(ps, at, 0, "%s", tex_errmsg());
    struct tex_matdb_entry *c = palloc(ps, sizeof *c);
    *c = *e;
    c->source = NULL;
    return c;
}

/* facets beckmann M | facets blinn NS, either with `beta DEG` instead of the number: row
 * p's value (its range Beckmann's) */
static void parse_facets(struct parser *ps, const struct tex_param *p, struct tex_ct *ct)
{
    struct tex_tok dt = ps->lx.t;
    if (tex_tok_is_word(&dt, "beckmann"))
        ct->facets.dist = TEX_FACET_BECKMANN;
    else if (tex_tok_is_word(&dt, "blinn"))
        ct->facets.dist = TEX_FACET_BLINN;
    else
        FAIL(ps, "%s takes beckmann M or blinn NS", p->name);
    tex_lex_next(&ps->lx);
    int beckmann = ct->facets.dist == TEX_FACET_BECKMANN;
    if (tex_tok_is_word(&ps->lx.t, "beta")) {
        tex_lex_next(&ps->lx);
        double b = ranged(ps, "beta", TEX_CT_BETA_MIN, TEX_CT_BETA_MAX, 0) * M_PI / 180;
        if (beckmann)
            ct->facets.m = tex_beckmann_m_from_beta(b);
        else
            ct->facets.ns = tex_blinn_ns_from_beta(b);
    } else if (beckmann) {
        ct->facets.m = ranged(ps, "beckmann M", p->min, p->max, 0);
    } else {
        ct->facets.ns = ranged(ps, "blinn NS", 0, TEX_CT_NS_MAX, 0);
    }
}

void tex_scene_read_material(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_surface *sf = ((struct block *)ctx)->obj;
    struct tex_tok mt = ps->lx.t;
    (void)p;
    char *m = mt.kind == TEX_TOK_STR ? pstrdup(ps, mt.text, mt.len) : word(ps, "a material");
    if (mt.kind == TEX_TOK_STR)
        tex_lex_next(&ps->lx);
    surface_ct(ps, sf)->entry = find_material(ps, &mt, m);
}

void tex_scene_read_facets(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    parse_facets(ps, p, surface_ct(ps, ((struct block *)ctx)->obj));
}

void tex_scene_read_specular(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    surface_ct(ps, ((struct block *)ctx)->obj)->s = ranged(ps, p->name, p->min, p->max, 0);
}

void tex_scene_read_model(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_surface *sf = ((struct block *)ctx)->obj;
    struct tex_tok mt = ps->lx.t;
    char *m = word(ps, "a shading model");
    if (!(sf->model = tex_shading_find(m)))
        fail_at(ps, &mt, 0, "%s must be %s (got %s)", p->name, p->meta, m);
}

/* tangent u | v | X Y Z (anisotropic.h) */
void tex_scene_read_tangent(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_surface *sf = ((struct block *)ctx)->obj;
    struct tex_tok t = ps->lx.t;
    char b[64];
    if (tex_tok_is_word(&t, "u") || tex_tok_is_word(&t, "v")) {
        sf->tangent_from = tex_tok_is_word(&t, "v") ? TEX_TANGENT_V : TEX_TANGENT_U;
        tex_lex_next(&ps->lx);
        return;
    }
    if (t.kind != TEX_TOK_NUM)
        FAIL(ps, "%s takes %s, found %s", p->name, p->meta, tex_tok_desc(&t, b, sizeof b));
    tex_v3 d = vec(ps);
    if (!(tex_v3_dot(d, d) > 0))
        fail_at(ps, &t, 0, "%s X Y Z must not be zero (got %g %g %g)", p->name, d.x, d.y, d.z);
    sf->tangent_from = TEX_TANGENT_FIXED;
    sf->tangent = tex_v3_norm(d);
}

void tex_scene_read_character(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_surface *sf = ((struct block *)ctx)->obj;
    struct tex_tok mt = ps->lx.t;
    char *m = word(ps, "an optical character"), near[64];
    for (int i = 0; tex_characters[i].name; i++)
        if (!strcmp(tex_characters[i].name, m)) {
            sf->character = i + 1;
            return;
        }
    if (tex_choice_nearest(p->meta, m, near, sizeof near))
        fail_at(ps, &mt, 0, "%s must be %s (got %s); did you mean %s?", p->name, p->meta, m,
                near);
    fail_at(ps, &mt, 0, "%s must be %s (got %s)", p->name, p->meta, m);
}

/* The surface's character's words, for those the surface did not give (seen) */
static void apply_character(struct parser *ps, struct tex_surface *sf, unsigned long long seen,
                            const struct tex_tok *at)
{
    const struct tex_character *c = &tex_characters[sf->character - 1];
    for (int i = 0; i < 8 && c->words[i][0]; i++) {
        const struct tex_param *row = tex_param_find(tex_surface_rows, c->words[i][0]);
        if (!(seen & row_bit(tex_surface_rows, c->words[i][0])) &&
            tex_param_set(row, sf, c->words[i][1]) < 0)
            fail_at(ps, at, 0, "%s", tex_errmsg());
    }
}

void tex_scene_read_blend(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_surface *sf = ((struct block *)ctx)->obj;
    struct tex_tok mt = ps->lx.t;
    const struct tex_surface *o = mt.kind == TEX_TOK_NAME ? find_surface(ps, &mt) : NULL;
    if (!o)
        FAIL(ps, "%s names a surface defined above (got %.*s)", p->name, (int)mt.len, mt.text);
    if (o == sf || o->blend)
        FAIL(ps, "%s mixes in a surface without a %s of its own", p->name, p->name);
    sf->blend = o;
    tex_lex_next(&ps->lx);
}

void tex_scene_read_apply(void *reader, const struct tex_param *p, void *ctx)
{
    struct block *b = ctx;
    (void)p;
    *b->tail = parse_apply(reader);
    b->tail = &(*b->tail)->next;
}

/* A surface with the rows' defaults and the Phong model. */
static void surface_defaults(struct parser *ps, struct tex_surface *sf)
{
    if (tex_params_defaults(tex_surface_rows, sf) < 0)
        fail_at(ps, &ps->lx.t, 0, "%s", tex_errmsg());
    sf->model = &tex_shading_phong;
}

static void parse_surface(struct parser *ps)
{
    struct tex_tok at = ps->lx.t;
    char *name = word(ps, "a surface name");
    for (int i = 0; i < ps->s->nsurfaces; i++)
        if (!strcmp(ps->s->surfaces[i]->name, name))
            fail_at(ps, &at, 0, "surface '%s' is defined twice", name);
    struct tex_surface *sf = palloc(ps, sizeof *sf);
    struct tex_surface **a =
        pgrow(ps, ps->s->surfaces, ps->s->nsurfaces, &ps->capsurfaces, sizeof *a);
    a[ps->s->nsurfaces++] = sf;
    ps->s->surfaces = a;
    sf->name = name;
    surface_defaults(ps, sf);
    sf->line = at.line;
    sf->col = at.col;
    struct block b = {.obj = sf, .tail = &sf->apply};
    unsigned long long seen = read_block(ps, tex_surface_rows, -1, &b, NULL, "a surface");
    if (sf->character)
        apply_character(ps, sf, seen, &at);
    /* a dielectric's own index wins over a character's */
    int ior_set = (seen & row_bit(tex_surface_rows, "ior")) != 0;
    struct tex_ct *ct = sf->ct;
    if (ct) {
        /* a dielectric from the database also gives the refraction index (at 550 nm) */
        if (ct->entry && ct->entry->kind == TEX_DIELECTRIC && !ior_set)
            sf->ior = tex_curve_at(&ct->entry->n, 550);
        if (tex_ct_init(ct, &ps->s->cs, ct->entry, ct->facets.dist, ct->facets.m, ct->facets.ns,
                        ct->s) < 0)
            fail_at(ps, &at, 0, "%s", tex_errmsg());
    }
    /* the targets that need a word of the surface */
    for (const struct tex_apply *ap = sf->apply; ap; ap = ap->next)
        for (const struct tex_appfn *fn = ap->fns; fn; fn = fn->next) {
            struct tex_tok ft = {TEX_TOK_NAME, "", 0, 0, ap->line, ap->col};
            if (fn->param == TEX_SP_BLEND && !sf->blend)
                fail_at(ps, &ft, 0, "blend = h needs 'blend SURFACE' in surface '%s'", name);
            int aniso = tex_shading_anisotropic(sf->model);
            if ((fn->param == TEX_SP_M && sf->model != &tex_shading_cook_torrance) ||
                (fn->param == TEX_SP_S && sf->model != &tex_shading_cook_torrance && !aniso))
                fail_at(ps, &ft, 0, "%s is Cook-Torrance's%s: surface '%s' needs model "
                                    "cook-torrance%s", tex_sparam_row(fn->param)->name,
                        fn->param == TEX_SP_S ? " and the anisotropic models'" : "", name,
                        fn->param == TEX_SP_S ? ", ward or ashikhmin-shirley" : "");
            if (fn->param >= TEX_SP_AU && fn->param <= TEX_SP_TANGENT && !aniso)
                fail_at(ps, &ft, 0, "%s is the anisotropic models': surface '%s' needs model "
                                    "ward or ashikhmin-shirley", tex_sparam_row(fn->param)->name,
                        name);
            if (fn->param == TEX_SP_M && ct && ct->facets.dist != TEX_FACET_BECKMANN)
                fail_at(ps, &ft, 0, "m is Beckmann's slope: surface '%s' has blinn facets",
                        name);
        }
}

int tex_scene_check_energy(struct tex_scene *s)
{
    int n = 0;
    for (int i = 0; i < s->nsurfaces; i++) {
        const struct tex_surface *sf = s->surfaces[i];
        double e;
        if (tex_surface_energy(sf, &e) && e > 1 + 1e-6) {
            tex_scene_warn(s, "%s:%d:%d: warning: surface '%s' breaks energy: %s reaches %.3g, "
                              "above 1 (thesis 4.4; a character gives consistent values)",
                           s->file, sf->line, sf->col, sf->name,
                           sf->model != &tex_shading_phong ? "(1 - s) Kd + max(s, Kr, Kt)"
                                                           : "Kd + max(Ks, Kr) + Kt",
                           e);
            n++;
        }
    }
    return n;
}

/* ---- objects -------------------------------------------------------------------- */

static const struct tex_surface *find_surface(struct parser *ps, const struct tex_tok *t)
{
    for (int i = 0; i < ps->s->nsurfaces; i++)
        if (strlen(ps->s->surfaces[i]->name) == t->len &&
            !memcmp(ps->s->surfaces[i]->name, t->text, t->len))
            return ps->s->surfaces[i];
    return NULL;
}

/* Transform t after those block b read before it */
static void place_xform(struct block *b, const tex_xform *t)
{
    tex_xform_mul(b->acc, t, b->acc);
    if (b->placed)
        *b->placed = 1;
}

void tex_scene_read_translate(void *reader, const struct tex_param *p, void *ctx)
{
    tex_xform t;
    (void)p;
    tex_xform_translate(&t, vec(reader));
    place_xform(ctx, &t);
}

void tex_scene_read_rotate(void *reader, const struct tex_param *p, void *ctx)
{
    tex_xform t;
    (void)p;
    tex_xform_identity(&t);
    tex_xform_rotate(&t, vec(reader));
    place_xform(ctx, &t);
}

void tex_scene_read_scale(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    tex_xform t;
    double sx = number(ps), sy = sx, sz = sx;
    if (ps->lx.t.kind == TEX_TOK_NUM) {
        sy = number(ps);
        sz = number(ps);
    }
    if (sx == 0 || sy == 0 || sz == 0)
        fail_at(ps, &ps->kt, 0, "%s by zero makes a degenerate object", p->name);
    tex_xform_scale(&t, tex_v3_make(sx, sy, sz));
    place_xform(ctx, &t);
}

/* `surface NAME` of an object block */
void tex_scene_read_surface(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_tok st = ps->lx.t;
    const struct tex_surface *sf;
    (void)p;
    if (st.kind != TEX_TOK_NAME || !(sf = find_surface(ps, &st)))
        FAIL(ps, "unknown surface '%.*s'", (int)st.len, st.text);
    ((struct block *)ctx)->ob->surface = sf;
    tex_lex_next(&ps->lx);
}

static int shape_kind(const struct tex_tok *t)
{
    for (int k = 0; k < TEX_SHAPE_NKINDS; k++)
        if (tex_tok_is_word(t, tex_shape_methods[k].name))
            return k;
    return -1;
}

static int csg_kind(const struct tex_tok *t)
{
    if (tex_tok_is_word(t, "union"))
        return TEX_CSG_UNION;
    if (tex_tok_is_word(t, "intersection"))
        return TEX_CSG_INTERSECTION;
    if (tex_tok_is_word(t, "difference"))
        return TEX_CSG_DIFFERENCE;
    return -1;
}

static int is_object(const struct tex_tok *t)
{
    return shape_kind(t) >= 0 || csg_kind(t) >= 0;
}

static struct tex_object *parse_object(struct parser *ps);

/* Check a shape's numbers and give the placement of its canonical shape; cones, cylinders
 * and tori keep their radii in ob, in world units. */
static void place_leaf(struct parser *ps, struct tex_object *ob, const struct tex_tok *at,
                       const struct tex_shape_params *l, tex_xform *place)
{
    int kind = ob->kind;

    switch (kind) {
    case TEX_SHAPE_SPHERE:
        if (!(l->radius > 0))
            fail_at(ps, at, 0, "sphere radius must be > 0");
        tex_xform_scale(place, tex_v3_make(l->radius, l->radius, l->radius));
        place->m[0][3] = l->centre.x, place->m[1][3] = l->centre.y, place->m[2][3] = l->centre.z;
        break;
    case TEX_SHAPE_BOX: {
        if (!(l->max.x > l->min.x && l->max.y > l->min.y && l->max.z > l->min.z))
            fail_at(ps, at, 0, "box needs min < max on every axis");
        tex_xform_scale(place, tex_v3_scale(tex_v3_sub(l->max, l->min), 0.5));
        tex_v3 c = tex_v3_scale(tex_v3_add(l->max, l->min), 0.5);
        place->m[0][3] = c.x, place->m[1][3] = c.y, place->m[2][3] = c.z;
        break;
    }
    case TEX_SHAPE_CYLINDER:
    case TEX_SHAPE_CONE:
    case TEX_SHAPE_INF_CONE: {
        double len = tex_v3_len(tex_v3_sub(l->top, l->base));
        double r0 = kind == TEX_SHAPE_CYLINDER ? l->radius : l->radius1;
        double r1 = kind == TEX_SHAPE_CYLINDER ? l->radius : l->radius2;
        if (!(len > 0))
            fail_at(ps, at, 0, "%s axis has zero length (base = top)",
                    tex_shape_methods[kind].name);
        if (!(r0 >= 0 && r1 >= 0 && r0 + r1 > 0))
            fail_at(ps, at, 0, "%s radii must be >= 0 and not both 0",
                    tex_shape_methods[kind].name);
        /* the canonical shape keeps unit radius scale; r0, r1 are in world units */
        tex_xform_frame(place, l->base, tex_v3_sub(l->top, l->base), len, 1);
        ob->r0 = r0;
        ob->r1 = r1;
        break;
    }
    case TEX_SHAPE_TORUS:
        /* r0, r1 are in world units like a cone's; the frame only turns and moves */
        if (!(l->major >= 0))
            fail_at(ps, at, 0, "torus major radius must be >= 0");
        if (!(l->minor > 0))
            fail_at(ps, at, 0, "torus minor radius must be > 0");
        if (!(tex_v3_len(l->axis) > 0))
            fail_at(ps, at, 0, "torus axis must not be zero");
        tex_xform_frame(place, l->centre, l->axis, 1, 1);
        ob->r0 = l->major;
        ob->r1 = l->minor;
        break;
    default:
        if (!(tex_v3_len(l->normal) > 0))
            fail_at(ps, at, 0, "plane normal must not be zero");
        tex_xform_frame(place, tex_v3_scale(tex_v3_norm(l->normal), l->distance), l->normal, 1, 1);
        break;
    }
}

/* A shape's block through tex_object_rows: its own words, surface and the transforms. */
static struct tex_object *parse_leaf(struct parser *ps, int kind, const struct tex_tok *at)
{
    struct tex_object *ob = palloc(ps, sizeof *ob);
    ob->op = TEX_CSG_LEAF;
    ob->kind = kind;
    ob->line = at->line;
    ob->col = at->col;
    struct tex_shape_params l;
    if (tex_params_defaults(tex_object_rows, &l) < 0)
        fail_at(ps, at, 0, "%s", tex_errmsg());
    tex_xform acc;
    tex_xform_identity(&acc);
    struct block b = {.obj = &l, .acc = &acc, .ob = ob};
    char what[32];
    snprintf(what, sizeof what, "a %s", tex_shape_methods[kind].name);
    ps->whole_vectors = 1;
    read_block(ps, tex_object_rows, kind, &b, NULL, what);
    ps->whole_vectors = 0;
    tex_xform place;
    place_leaf(ps, ob, at, &l, &place);
    tex_xform_mul(&ob->to_world, &acc, &place);
    return ob;
}

/* A plane whose anisotropic surface's fixed tangent lies along its normal has no
 * direction to stretch the highlight in: refused, naming the surface's line. */
static void fixed_tangent(struct parser *ps, const struct tex_object *ob)
{
    const struct tex_surface *sf = ob->surface;
    if (ob->op != TEX_CSG_LEAF || ob->kind != TEX_SHAPE_PLANE || !sf ||
        !tex_shading_anisotropic(sf->model) || sf->tangent_from != TEX_TANGENT_FIXED)
        return;
    tex_v3 n = tex_v3_norm(tex_xform_normal(
        &ob->to_obj, tex_shape_methods[TEX_SHAPE_PLANE].normal(ob, tex_v3_make(0, 0, 0))));
    tex_v3 c = tex_v3_cross(n, sf->tangent);
    if (tex_v3_dot(c, c) < 1e-8) {
        struct tex_tok t = {0};
        t.line = sf->line, t.col = sf->col;
        fail_at(ps, &t, 0, "surface '%s': tangent %g %g %g is along the normal of the plane on "
                           "line %d; give a direction in the plane, or tangent u",
                sf->name, sf->tangent.x, sf->tangent.y, sf->tangent.z, ob->line);
    }
}

static void set_world(struct parser *ps, struct tex_object *ob, const tex_xform *parent,
                      const struct tex_surface *sf, const struct tex_object *root)
{
    if (ob->op == TEX_CSG_LEAF) {
        tex_xform_mul(&ob->to_world, parent, &ob->to_world);
        if (tex_xform_invert(&ob->to_obj, &ob->to_world) < 0) {
            struct tex_tok t = {0};
            t.line = ob->line, t.col = ob->col;
            fail_at(ps, &t, 0, "degenerate %s (its transform is singular)",
                    tex_shape_methods[ob->kind].name);
        }
    } else {
        tex_xform w;
        tex_xform_mul(&w, parent, &ob->to_world);
        set_world(ps, ob->a, &w, ob->surface ? ob->surface : sf, root);
        set_world(ps, ob->b, &w, ob->surface ? ob->surface : sf, root);
    }
    if (!ob->surface)
        ob->surface = sf;
    ob->root = root;
    fixed_tangent(ps, ob);
}

static struct tex_object *parse_object(struct parser *ps)
{
    struct tex_tok at = ps->lx.t;
    if (++ps->nest > MAX_NEST)
        FAIL(ps, "objects nested too deeply");
    int k = shape_kind(&at);
    tex_lex_next(&ps->lx);
    struct tex_object *ob;
    if (k >= 0) {
        ob = parse_leaf(ps, k, &at);
    } else {
        int op = csg_kind(&at);
        ob = palloc(ps, sizeof *ob);
        ob->op = op;
        ob->line = at.line;
        ob->col = at.col;
        tex_xform_identity(&ob->to_world);
        struct tex_object **kids = NULL;
        int nk = 0, ck = 0;
        tex_lex_expect(&ps->lx, '{');
        while (!tex_tok_is_punct(&ps->lx.t, '}')) {
            struct tex_tok kt = ps->lx.t;
            const struct tex_param *p = row_of(tex_object_rows, &kt, -1);
            if (p && p->type == TEX_P_SPECIAL) { /* the words of every object: surface, placements */
                struct block b = {.acc = &ob->to_world, .ob = ob};
                tex_lex_next(&ps->lx);
                read_value(ps, p, &kt, &b);
            } else if (is_object(&kt)) {
                if (nk == ck) {
                    ck = ck ? 2 * ck : 4;
                    struct tex_object **nkids = palloc(ps, ck * sizeof *nkids);
                    if (nk)
                        memcpy(nkids, kids, nk * sizeof *nkids);
                    kids = nkids;
                }
                kids[nk++] = parse_object(ps);
            } else {
                char b[64];
                const char *block = op == TEX_CSG_UNION          ? "union"
                                    : op == TEX_CSG_INTERSECTION ? "intersection"
                                                                 : "difference";
                if (kt.kind == TEX_TOK_EOF)
                    FAIL(ps, "expected '}' to end a %s, found the end of the file", block);
                FAIL(ps, "unknown word %s in a %s", tex_tok_desc(&kt, b, sizeof b), block);
            }
        }
        tex_lex_next(&ps->lx);
        if (nk < 2)
            fail_at(ps, &at, 0, "a CSG operation needs at least two objects");
        /* more than two children make a balanced tree, so that every walk over it is
         * log2(N) deep (tex_csg_spatial orders it in space later): unions and intersections
         * pair their children, and a - b - c - ... is a - (b u c u ...) */
        if (op == TEX_CSG_DIFFERENCE) {
            ob->a = kids[0];
            ob->b = tex_csg_balanced(TEX_CSG_UNION, kids + 1, nk - 1, at.line, at.col, lex_alloc, ps);
        } else {
            ob->a = tex_csg_balanced(op, kids, nk / 2, at.line, at.col, lex_alloc, ps);
            ob->b = tex_csg_balanced(op, kids + nk / 2, nk - nk / 2, at.line, at.col, lex_alloc, ps);
        }
    }
    ps->nest--;
    return ob;
}

/* ---- hypertextures (hypertexture.h) ----------------------------------------------------- */

static int density_kind(const struct tex_tok *t)
{
    for (int k = 0; k < TEX_HD_NKINDS; k++)
        if (tex_tok_is_word(t, tex_hdensity_names[k]))
            return k;
    return -1;
}

static struct tex_hdensity *parse_density(struct parser *ps);

/* kids[0..n) combined by op, a balanced tree as CSG's: every walk log2(n) deep */
static struct tex_hdensity *density_tree(struct parser *ps, int op, struct tex_hdensity **kids,
                                         int n)
{
    if (n == 1)
        return kids[0];
    struct tex_hdensity *d = palloc(ps, sizeof *d);
    *d = (struct tex_hdensity){.kind = op, .line = kids[0]->line, .col = kids[0]->col};
    d->a = density_tree(ps, op, kids, n / 2);
    d->b = density_tree(ps, op, kids + n / 2, n - n / 2);
    return d;
}

/* A density: a shape's block through tex_hdensity_rows, or a boolean of densities */
static struct tex_hdensity *parse_density(struct parser *ps)
{
    char b[64], what[32];
    struct tex_tok at = ps->lx.t;
    int k = density_kind(&at);
    if (k < 0)
        FAIL(ps, "expected a density (sphere, box, cylinder, union, intersection, difference "
                 "or complement), found %s", tex_tok_desc(&at, b, sizeof b));
    if (++ps->nest > MAX_NEST)
        FAIL(ps, "densities nested too deeply");
    tex_lex_next(&ps->lx);
    struct tex_hdensity *d = palloc(ps, sizeof *d), **kids = NULL;
    snprintf(what, sizeof what, "a density %s", tex_hdensity_names[k]);
    if (k <= TEX_HD_CYLINDER) {
        if (tex_params_defaults(tex_hdensity_rows, d) < 0)
            fail_at(ps, &at, 0, "%s", tex_errmsg());
        ps->whole_vectors = 1;
        read_block(ps, tex_hdensity_rows, k, &(struct block){.obj = d}, NULL, what);
        ps->whole_vectors = 0;
    } else {
        size_t nk = 0, ck = 0;
        tex_lex_expect(&ps->lx, '{');
        while (!tex_tok_is_punct(&ps->lx.t, '}')) {
            if (ps->lx.t.kind == TEX_TOK_EOF)
                FAIL(ps, "expected '}' to end %s, found the end of the file", what);
            kids = pgrow(ps, kids, nk, &ck, sizeof *kids);
            kids[nk++] = parse_density(ps);
        }
        tex_lex_next(&ps->lx);
        if (k == TEX_HD_COMPLEMENT ? nk != 1 : nk < 2)
            fail_at(ps, &at, 0, "%s needs %s", what,
                    k == TEX_HD_COMPLEMENT ? "one density" : "at least two densities");
        if (k == TEX_HD_COMPLEMENT)
            d->a = kids[0];
        else if (k == TEX_HD_DIFFERENCE) /* a - b - c ... is a - (b u c u ...) */
            d->a = kids[0], d->b = density_tree(ps, TEX_HD_UNION, kids + 1, (int)nk - 1);
        else
            d->a = density_tree(ps, k, kids, (int)nk / 2),
            d->b = density_tree(ps, k, kids + nk / 2, (int)(nk - nk / 2));
    }
    d->kind = k;
    d->line = at.line, d->col = at.col;
    ps->nest--;
    return d;
}

/* An operand of a hypertexture's function: D (the object density, as a surface's p), H (the
 * modulated one, as f; not in density, which makes it), x y z and ox oy oz (the point), or
 * what an application function reads besides (textures, palettes) */
static struct tex_enode *hyper_operand(struct tex_expr_parser *xp)
{
    struct parser *ps = xp->ctx;
    struct tex_tok t = ps->lx.t;
    int D = tex_tok_is_word(&t, "D"), H = tex_tok_is_word(&t, "H"), q = -1;
    if (D || H) {
        if (H && ps->hyper_fn == 1 + TEX_HF_DENSITY)
            FAIL(ps, "density makes H: it reads D, the point and textures");
        struct tex_enode *e = tex_expr_node(&ps->lx, TEX_EK_LEAF, &t);
        e->op = D ? TEX_LEAF_P : TEX_LEAF_F;
        tex_lex_next(&ps->lx);
        return e;
    }
    for (int i = 0; i < TEX_Q_COUNT; i++)
        if (tex_tok_is_word(&t, tex_quantities[i].name))
            q = i;
    if (tex_tok_is_word(&t, "f") || tex_tok_is_word(&t, "p") ||
        (q >= 0 && !(q >= TEX_Q_X && q <= TEX_Q_OZ)))
        FAIL(ps, "'%.*s' is a surface's: a hypertexture's functions read D, H, x, y, z, "
                 "textures, palettes, numbers and functions", (int)t.len, t.text);
    return operand(xp);
}

static void parse_hypertexture(struct parser *ps, const struct tex_tok *at)
{
    struct tex_scene *s = ps->s;
    char b[64];
    struct tex_hyper *h = palloc(ps, sizeof *h);
    if (tex_params_defaults(tex_hyper_rows, h) < 0)
        fail_at(ps, at, 0, "%s", tex_errmsg());
    h->line = at->line, h->col = at->col;
    for (int i = 0; i < TEX_HF_COUNT; i++)
        h->lo[i] = tex_hyper_fn_rows[i].min, h->hi[i] = tex_hyper_fn_rows[i].max;
    tex_lex_expect(&ps->lx, '{');
    while (!tex_tok_is_punct(&ps->lx.t, '}')) {
        struct tex_tok kt = ps->lx.t;
        const struct tex_param *p = row_of(tex_hyper_rows, &kt, -1),
                               *f = row_of(tex_hyper_fn_rows, &kt, -1);
        if (tex_tok_is_word(&kt, "H")) /* the thesis's H = f_n(...f_0(D)) */
            f = &tex_hyper_fn_rows[TEX_HF_DENSITY];
        if (density_kind(&kt) >= 0) {
            if (h->d)
                FAIL(ps, "a hypertexture takes one density (union, intersection, difference "
                         "and complement combine them)");
            h->d = parse_density(ps);
        } else if (p) {
            tex_lex_next(&ps->lx);
            read_value(ps, p, &kt, &(struct block){.obj = h});
        } else if (f) {
            static const struct tex_expr_lang lang = {tex_expr_arith_binops, hyper_operand};
            struct tex_expr_parser xp = {&ps->lx, &lang, ps, 0, 0};
            tex_lex_next(&ps->lx);
            if (!tex_tok_is_punct(&ps->lx.t, '='))
                FAIL(ps, "expected '=' after %s, found %s", f->name,
                     tex_tok_desc(&ps->lx.t, b, sizeof b));
            tex_lex_next(&ps->lx);
            ps->hyper_fn = 1 + (int)(f - tex_hyper_fn_rows);
            h->fn[f - tex_hyper_fn_rows] = tex_expr_compile(&ps->lx, tex_expr_parse(&xp));
            ps->hyper_fn = 0;
        } else if (kt.kind == TEX_TOK_EOF) {
            FAIL(ps, "expected '}' to end a hypertexture, found the end of the file");
        } else {
            FAIL(ps, "unknown word %s in a hypertexture%s", tex_tok_desc(&kt, b, sizeof b),
                 nearest_row(tex_hyper_rows, -1, &kt));
        }
    }
    tex_lex_next(&ps->lx);
    struct tex_hdensity *bad;
    const char *msg;
    if (!h->d)
        fail_at(ps, at, 0, "a hypertexture needs a density: sphere, box, cylinder, union, "
                           "intersection, difference or complement");
    if (tex_hdensity_prepare(h->d, &bad, &msg) < 0)
        fail_at(ps, &(struct tex_tok){.line = bad->line, .col = bad->col}, 0, "%s", msg);
    if (!tex_hdensity_bounded(h->d))
        fail_at(ps, at, 0, "unbounded volume: a complement needs an intersection with, or a "
                           "difference from, a bounded density");
    if (s->nhypers == TEX_HYPER_MAX)
        fail_at(ps, at, 0, "more than %d hypertextures", TEX_HYPER_MAX);
    if (!h->shadow_step)
        h->shadow_step = 2 * h->step;
    if (!s->hypers)
        s->hypers = palloc(ps, TEX_HYPER_MAX * sizeof *s->hypers);
    s->hypers[s->nhypers++] = h;
}

/* ---- lights, camera, settings ------------------------------------------------------------ */

/* spectrum D65 | A | E | F2 ... (colord-data) | blackbody K | "blackbody:K" */
static void parse_spectrum(struct parser *ps, tex_curve *c)
{
    struct tex_tok t = ps->lx.t;
    char name[64];
    if (tex_tok_is_word(&t, "blackbody")) {
        tex_lex_next(&ps->lx);
        const struct tex_param *p = tex_param_find(tex_light_rows, "spectrum");
        snprintf(name, sizeof name, "blackbody:%.17g", ranged(ps, "blackbody K", p->min, p->max, 0));
    } else if ((t.kind == TEX_TOK_NAME || t.kind == TEX_TOK_STR) && t.len < sizeof name) {
        snprintf(name, sizeof name, "%.*s", (int)t.len, t.text);
        tex_lex_next(&ps->lx);
    } else {
        FAIL(ps, "spectrum takes D65, A, blackbody K or another CIE illuminant name");
    }
    if (tex_illuminant(c, name, NULL) < 0)
        fail_at(ps, &t, tex_errkind() == TEX_ERR_RUNTIME, "%s", tex_errmsg());
}

void tex_scene_read_spectrum(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_light *l = ((struct block *)ctx)->obj;
    (void)p;
    l->spectrum = palloc(ps, sizeof *l->spectrum);
    parse_spectrum(ps, l->spectrum);
}

/* falloff none | square | C1 C2 C3 */
void tex_scene_read_falloff(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_light *l = ((struct block *)ctx)->obj;
    struct tex_tok ft = ps->lx.t;
    if (tex_tok_is_word(&ft, "none") || tex_tok_is_word(&ft, "square")) {
        tex_lex_next(&ps->lx);
        l->falloff = tex_tok_is_word(&ft, "none") ? TEX_FALL_NONE : TEX_FALL_SQUARE;
        return;
    }
    char name[64];
    double *c[3] = {&l->c1, &l->c2, &l->c3};
    l->falloff = TEX_FALL_POLY;
    for (int i = 0; i < 3; i++) {
        snprintf(name, sizeof name, "%s C%d", p->name, i + 1);
        *c[i] = ranged(ps, name, p->min, p->max, 0);
    }
    if (l->c1 + l->c2 + l->c3 <= 0)
        fail_at(ps, &ft, 0, "%s c1 c2 c3 must not all be 0", p->name);
}

static void parse_light(struct parser *ps)
{
    struct tex_tok at = ps->lx.t;
    static const char *const kinds[] = {"distant", "point", "spot", "area", NULL};
    char *k = word(ps, "a light kind (distant|point|spot|area)");
    int kind = 0;
    while (kinds[kind] && strcmp(kinds[kind], k))
        kind++;
    if (!kinds[kind])
        fail_at(ps, &at, 0, "unknown light '%s' (distant|point|spot|area)", k);
    struct tex_scene *s = ps->s;
    struct tex_light *a = pgrow(ps, s->lights, s->nlights, &ps->caplights, sizeof *a);
    s->lights = a;
    struct tex_light *l = &a[s->nlights++];
    if (tex_params_defaults(tex_light_rows, l) < 0)
        fail_at(ps, &at, 0, "%s", tex_errmsg());
    l->kind = kind;
    char what[32];
    snprintf(what, sizeof what, "a %s light", k);
    struct block b = {.obj = l};
    unsigned long long seen = read_block(ps, tex_light_rows, kind, &b, NULL, what);
    const struct tex_param *dir = tex_param_find(tex_light_rows, "direction");
    if ((seen & row_bit(tex_light_rows, "direction")) && !(tex_v3_len(l->direction) > 0))
        fail_at(ps, &at, 0, "light %s must not be zero", dir->name);
    if (l->spectrum && (seen & row_bit(tex_light_rows, "colour")))
        fail_at(ps, &at, 0, "a light takes a colour or a spectrum, not both");
    for (int i = 0; i < 3; i++)
        l->rgb[i] = (float)(l->spectrum ? l->intensity : l->colour[i] * l->intensity);
    if (kind == TEX_LIGHT_DISTANT)
        l->dir = tex_v3_norm(l->direction);
    if (kind == TEX_LIGHT_SPOT) {
        if (!(seen & row_bit(tex_light_rows, "at")))
            fail_at(ps, &at, 0, "a spot light needs 'at X Y Z'");
        tex_v3 d = tex_v3_sub(l->at, l->pos);
        if (!(tex_v3_len(d) > 0))
            fail_at(ps, &at, 0, "spot light 'at' equals its position");
        l->dir = tex_v3_norm(d);
        l->cos_angle = cos(l->angle * M_PI / 180);
    }
    if (kind == TEX_LIGHT_AREA && !(tex_v3_len(tex_v3_cross(l->edge1, l->edge2)) > 0))
        fail_at(ps, &at, 0, "area light edges must span a parallelogram");
}

/* environment FILE [{ intensity I rotate X Y Z }] */
static void parse_environment(struct parser *ps, const struct tex_tok *kt)
{
    struct tex_environment *e = &ps->s->env;
    struct tex_tok ft = ps->lx.t;
    if (e->map)
        fail_at(ps, kt, 0, "only one environment");
    if (ft.kind != TEX_TOK_STR && ft.kind != TEX_TOK_NAME && !tex_tok_is_punct(&ft, '-'))
        FAIL(ps, "expected a map file or '-' after 'environment'");
    char *path = pstrdup(ps, ft.text, ft.len);
    tex_lex_next(&ps->lx);
    if (!strcmp(path, "-")) {
        if (ps->stdin_used)
            fail_at(ps, &ft, 0, "only one map can come from standard input");
        ps->stdin_used = 1;
    }
    if (tex_params_defaults(tex_environment_rows, e) < 0)
        fail_at(ps, &ft, 0, "%s", tex_errmsg());
    if (tex_tok_is_punct(&ps->lx.t, '{'))
        read_block(ps, tex_environment_rows, -1, &(struct block){.obj = e}, NULL, "the environment");
    tex_map *m = tex_map_read(path);
    if (!m)
        fail_at(ps, &ft, 1, "cannot read the environment map '%s': %s", path, tex_errmsg());
    struct tex_texture *tx = calloc(1, sizeof *tx);
    if (!tx) {
        tex_map_free(m);
        fail_at(ps, &ft, 1, "out of memory");
    }
    add_texture(ps, tx); /* freed with the scene's textures */
    tx->name = path;
    e->map = tx;
    texture_map(ps, tx, m, &ft);
    tex_xform r;
    tex_xform_identity(&r);
    tex_xform_rotate(&r, e->rotate);
    if (tex_xform_invert(&e->to_map, &r) < 0)
        fail_at(ps, &ft, 0, "the environment's rotation is singular");
}

static void parse_camera(struct parser *ps)
{
    read_block(ps, tex_camera_rows, -1, &(struct block){.obj = ps->s}, NULL, "the camera");
}

static void add_object(struct parser *ps, struct tex_object *ob)
{
    struct tex_scene *s = ps->s;
    if (s->nobjects == s->cobjects) { /* doubling: a scene may list 10^5 objects */
        int c = s->cobjects ? 2 * s->cobjects : 16;
        struct tex_object **a = realloc(s->objects, c * sizeof *a);
        if (!a)
            fail_at(ps, &ps->lx.t, 1, "out of memory");
        s->objects = a;
        s->cobjects = c;
    }
    s->objects[s->nobjects++] = ob;
}

void tex_scene_read_seed(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    (void)ctx;
    ps->s->settings.seed = (uint64_t)ranged(ps, p->name, p->min, p->max, 1);
}

void tex_scene_read_materials(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_tok ft = ps->lx.t;
    (void)ctx;
    if (ft.kind != TEX_TOK_STR && ft.kind != TEX_TOK_NAME)
        FAIL(ps, "expected a file name after '%s'", p->name);
    char *path = pstrdup(ps, ft.text, ft.len);
    tex_lex_next(&ps->lx);
    load_materials(ps, path, &ft);
}

/* colour rgb | spectral [N] */
void tex_scene_read_colour(void *reader, const struct tex_param *p, void *ctx)
{
    struct parser *ps = reader;
    struct tex_tok mt = ps->lx.t;
    int bands = 0;
    (void)ctx;
    if (tex_tok_is_word(&mt, "spectral")) {
        tex_lex_next(&ps->lx);
        bands = TEX_BANDS_DEFAULT;
        if (ps->lx.t.kind == TEX_TOK_NUM)
            bands = (int)ranged(ps, "spectral N", p->min, p->max, 1);
    } else if (tex_tok_is_word(&mt, "rgb")) {
        tex_lex_next(&ps->lx);
    } else {
        FAIL(ps, "%s model must be rgb or spectral [N]", p->name);
    }
    if (tex_scene_set_colour(ps->s, bands) < 0)
        fail_at(ps, &mt, tex_errkind() == TEX_ERR_RUNTIME, "%s", tex_errmsg());
}

/* A word of the settings (kt, already taken): 1 if it is one. */
static int settings_word(struct parser *ps, const struct tex_tok *kt)
{
    const struct tex_param *p = row_of(tex_settings_rows, kt, -1);
    struct block b = {.obj = ps->s};
    if (!p)
        return 0;
    read_value(ps, p, kt, &b);
    return 1;
}

static void parse_scene(struct parser *ps)
{
    struct tex_scene *s = ps->s;
    struct tex_tok camt = {0};
    camt.line = camt.col = 1;
    tex_lex_next(&ps->lx);
    while (ps->lx.t.kind != TEX_TOK_EOF) {
        struct tex_tok kt = ps->lx.t;
        if (is_object(&kt)) {
            struct tex_object *ob = parse_object(ps);
            tex_xform id;
            tex_xform_identity(&id);
            set_world(ps, ob, &id, NULL, ob);
            if (tex_csg_spatial(ob, lex_alloc, ps) < 0)
                fail_at(ps, &ps->lx.t, 1, "%s", tex_errmsg());
            add_object(ps, ob);
            continue;
        }
        tex_lex_next(&ps->lx);
        if (tex_tok_is_word(&kt, "camera")) {
            camt = kt;
            parse_camera(ps);
        } else if (tex_tok_is_word(&kt, "light")) {
            parse_light(ps);
        } else if (tex_tok_is_word(&kt, "texture")) {
            parse_texture(ps);
        } else if (tex_tok_is_word(&kt, "primitive") || tex_tok_is_word(&kt, "primitives")) {
            parse_primitive(ps, &kt);
        } else if (tex_tok_is_word(&kt, "surface")) {
            parse_surface(ps);
        } else if (tex_tok_is_word(&kt, "environment")) {
            parse_environment(ps, &kt);
        } else if (tex_tok_is_word(&kt, "hypertexture")) {
            parse_hypertexture(ps, &kt);
        } else if (!settings_word(ps, &kt)) {
            char b[64];
            fail_at(ps, &kt, 0, "unknown word %s at the top of the scene%s",
                    tex_tok_desc(&kt, b, sizeof b), nearest_row(tex_settings_rows, -1, &kt));
        }
    }
    tex_v3 f = tex_v3_sub(s->look, s->eye);
    if (!(tex_v3_len(f) > 0))
        fail_at(ps, &camt, 0, "camera eye and look are the same point");
    if (!(tex_v3_len(tex_v3_cross(f, s->up)) > 1e-12 * tex_v3_len(f) * tex_v3_len(s->up)))
        fail_at(ps, &camt, 0, "camera up is parallel to the viewing direction");
}

/* Everything that can fail lives here, under setjmp: the caller frees the scene. */
static int parse_all(struct parser *ps)
{
    if (setjmp(ps->jb))
        return -1;
    /* surfaces[0] is the default surface for objects that name none */
    struct tex_surface *def = palloc(ps, sizeof *def);
    def->name = "default";
    surface_defaults(ps, def);
    ps->s->surfaces = pgrow(ps, NULL, 0, &ps->capsurfaces, sizeof *ps->s->surfaces);
    ps->s->surfaces[0] = def;
    ps->s->nsurfaces = 1;
    parse_scene(ps);
    return 0;
}

struct tex_scene *tex_scene_parse(const char *text, size_t len, const char *name)
{
    static const struct tex_scene_opts defaults = TEX_SCENE_DEFAULTS;
    return tex_scene_parse_opts(text, len, name, &defaults);
}

struct tex_scene *tex_scene_parse_opts(const char *text, size_t len, const char *name,
                                       const struct tex_scene_opts *o)
{
    if (o->sample_size < 1 || o->sample_size > TEX_SCENE_MAX_SIDE) {
        tex_error("sample size %d: valid range 1..%d", o->sample_size, TEX_SCENE_MAX_SIDE);
        return NULL;
    }
    struct tex_scene *s = calloc(1, sizeof *s);
    if (!s || !(s->file = strdup(name))) {
        free(s);
        tex_error("out of memory");
        return NULL;
    }
    struct parser ps = {0};
    ps.name = name;
    ps.s = s;
    tex_lex_init(&ps.lx, text, len, name, &ps.jb, lex_alloc, &ps);
    ps.lx.semicolon_blank = 1;
    ps.sample_size = o->sample_size;
    if (tex_params_defaults(tex_camera_rows, s) < 0 ||
        tex_params_defaults(tex_settings_rows, s) < 0) {
        tex_scene_free(s);
        return NULL;
    }
    tex_colour_space_rgb(&s->cs);
    int rc = parse_all(&ps);
    if (ps.have_db)
        tex_matdb_free(&ps.db);
    if (rc < 0) {
        tex_scene_free(s);
        return NULL;
    }
    if (!s->nobjects && !s->nhypers)
        tex_scene_warn(s, "%s: warning: the scene has no objects", name);
    return s;
}

struct tex_scene *tex_scene_load(const char *path)
{
    size_t n;
    char *buf = tex_read_text(path, 1u << 28, &n, "a scene");
    if (!buf)
        return NULL;
    struct tex_scene *s = tex_scene_parse(buf, n, path);
    free(buf);
    return s;
}
