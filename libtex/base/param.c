/* param.c - defaults, parsing and range checks from parameter tables */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/map.h"
#include "base/nearest.h"
#include "base/param.h"

#define AT(obj, p, T) ((T *)((char *)(obj) + (p)->off))

int tex_parse_size(const char *s, int *w, int *h)
{
    char *end;
    long long a, b;

    a = strtoll(s, &end, 10);
    if (end == s)
        return -1;
    if (*end == 'x' || *end == 'X') {
        const char *t = end + 1;
        b = strtoll(t, &end, 10);
        if (end == t)
            return -1;
    } else
        b = a;
    if (*end || tex_map_check_sides(a, b, 1) < 0)
        return -1;
    *w = (int)a;
    *h = (int)b;
    return 0;
}

int tex_parse_real(const char *text, double *out)
{
    char *end;
    double v;

    while (*text == ' ')
        text++;
    errno = 0;
    v = strtod(text, &end);
    if (end == text || *end != '\0' || !isfinite(v) || errno == ERANGE)
        return -1;
    *out = v;
    return 0;
}

static int hexval(int c)
{
    return c >= '0' && c <= '9' ? c - '0'
         : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                : -1;
}

int tex_parse_color(const char *text, float rgba[4])
{
    rgba[3] = 1.0f;
    if (text[0] == '#') {
        size_t n = strlen(text + 1);
        int d[8];
        if (n != 3 && n != 6 && n != 8)
            return -1;
        for (size_t i = 0; i < n; i++)
            if ((d[i] = hexval(text[1 + i])) < 0)
                return -1;
        for (int c = 0; c < (n == 8 ? 4 : 3); c++)
            rgba[c] = n == 3 ? d[c] * 17 / 255.0f : (d[2 * c] * 16 + d[2 * c + 1]) / 255.0f;
        return 0;
    } else {
        char buf[128], *tok, *save;
        int k = 0;
        double v;
        if (strlen(text) >= sizeof buf)
            return -1;
        strcpy(buf, text);
        for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            if (k == 4 || tex_parse_real(tok, &v) < 0 || v < 0 || v > 1)
                return -1;
            rgba[k++] = (float)v;
        }
        if (k == 1) /* a grey level */
            rgba[1] = rgba[2] = rgba[0];
        return k == 1 || k == 3 || k == 4 ? 0 : -1;
    }
}

const char *tex_param_option(const struct tex_param *p, char *buf, size_t n)
{
    return tex_param_name(p, buf, n, TEX_PARAM_OPTION);
}

const char *tex_param_name(const struct tex_param *p, char *buf, size_t n,
                           enum tex_param_style style)
{
    snprintf(buf, n, "%s%s", style == TEX_PARAM_OPTION ? "--" : "", p->name);
    for (char *c = buf; *c; c++)
        if (*c == '_')
            *c = '-';
    return buf;
}

int tex_param_count(const struct tex_param *p)
{
    return p->n > 1 ? p->n : 1;
}

static void fmt_real(double v, char *buf, size_t n)
{
    if (v >= 1e15 || (v <= -1e15))
        snprintf(buf, n, "%g", v);
    else
        snprintf(buf, n, "%.10g", v);
}

const char *tex_param_range(const struct tex_param *p, char *buf, size_t n)
{
    char a[40], b[40];

    switch (p->type) {
    case TEX_P_INT:
        snprintf(buf, n, "%lld..%lld", (long long)p->min, (long long)p->max);
        break;
    case TEX_P_REAL:
    case TEX_P_FLOAT:
    case TEX_P_REALS:
        if (isinf(p->min) && isinf(p->max)) { /* a point or direction: any numbers */
            buf[0] = '\0';
            break;
        }
        fmt_real(p->min, a, sizeof a);
        fmt_real(p->max, b, sizeof b);
        if (p->type == TEX_P_REALS && p->nmax > 1)
            snprintf(buf, n, "1..%d values in %s..%s", p->nmax, a, b);
        else
            snprintf(buf, n, "%s..%s", a, b);
        break;
    case TEX_P_ENUM:
        snprintf(buf, n, "%s", p->choices);
        break;
    case TEX_P_COLOR:
        snprintf(buf, n, "#rrggbb, r,g,b or a grey level in 0..1");
        break;
    case TEX_P_FLAG:
        snprintf(buf, n, "0 or 1");
        break;
    default:
        buf[0] = '\0';
    }
    return buf;
}

const char *tex_param_default(const struct tex_param *p, char *buf, size_t n)
{
    switch (p->type) {
    case TEX_P_INT:
        if (p->defstr)
            snprintf(buf, n, "%s", p->defstr);
        else
            snprintf(buf, n, "%lld", (long long)p->def);
        break;
    case TEX_P_REAL:
    case TEX_P_FLOAT:
        if (p->defstr)
            snprintf(buf, n, "%s", p->defstr);
        else
            fmt_real(p->def, buf, n);
        break;
    case TEX_P_FLAG:
        snprintf(buf, n, "off");
        break;
    default:
        snprintf(buf, n, "%s", p->defstr ? p->defstr : "none");
    }
    return buf;
}

/* The US spellings the names also take: the rows spell the UK way. */
static const char *const spellings[][2] = {
    {"color", "colour"},     {"center", "centre"},     {"gray", "grey"},
    {"quantize", "quantise"}, {"neighbor", "neighbour"}, {"normalize", "normalise"},
};

/* name with '-' for '_' and each spelling of one column written as the
 * other's (to = 1: UK, 0: US), into buf. */
static const char *respell(const char *name, int to, char *buf, size_t n)
{
    const size_t ns = sizeof spellings / sizeof *spellings;
    size_t k = 0;

    while (*name && k + 1 < n) {
        size_t i, len = 0;
        for (i = 0; i < ns; i++)
            if (!strncmp(name, spellings[i][!to], len = strlen(spellings[i][!to])))
                break;
        if (i < ns && k + strlen(spellings[i][to]) + 1 < n) {
            strcpy(buf + k, spellings[i][to]);
            k += strlen(spellings[i][to]);
            name += len;
        } else {
            buf[k++] = *name == '_' ? '-' : *name;
            name++;
        }
    }
    buf[k] = '\0';
    return buf;
}

const char *tex_param_us_spelling(const char *name, char *buf, size_t n)
{
    return respell(name, 0, buf, n);
}

int tex_param_same_name(const char *a, const char *b)
{
    char ca[128], cb[128];
    /* respell keeps the first letter ('_' becomes '-'): most rows differ there */
    if (*a != *b && !((*a == '_' || *a == '-') && (*b == '_' || *b == '-')))
        return 0;
    return !strcmp(respell(a, 1, ca, sizeof ca), respell(b, 1, cb, sizeof cb));
}

/* Does the space-separated list have the long name? */
const char *tex_param_list_next(const char **list, char *word, size_t n)
{
    while (*list && **list) {
        size_t k = strcspn(*list, " ");
        const char *at = *list;
        *list += k;
        *list += strspn(*list, " ");
        if (k < n) {
            memcpy(word, at, k);
            word[k] = '\0';
            return word;
        }
    }
    return NULL;
}

static int listed(const char *list, const char *name)
{
    char word[128];

    while (tex_param_list_next(&list, word, sizeof word))
        if (word[0] != '-' && tex_param_same_name(word, name))
            return 1;
    return 0;
}

const struct tex_param *tex_param_find(const struct tex_param *t, const char *name)
{
    const struct tex_param *r;

    for (r = t; r && r->name; r++)
        if (tex_param_same_name(r->name, name) || listed(r->alias, name))
            return r;
    for (r = t; r && r->name; r++)
        if (listed(r->old, name)) {
            char buf[64];
            tex_param_name(r, buf, sizeof buf, TEX_PARAM_WORD);
            if (tex_param_deprecated_is_error())
                return NULL; /* the caller's "unknown parameter" */
            tex_warning("'%s' is deprecated and will be removed: write '%s'", name, buf);
            return r;
        }
    return NULL;
}

int tex_param_deprecated_is_error(void)
{
    const char *e = getenv("TEXTURA_DEPRECATED");
    return e && !strcmp(e, "error");
}

/* "NAME must be RANGE (got V)": V is the text given, or else the number v. */
const char *tex_param_nearest(const struct tex_param *t, int kind, const char *word, char *buf,
                              size_t n)
{
    struct tex_nearest nr;
    tex_nearest_init(&nr, word);
    for (const struct tex_param *p = t; p && p->name; p++)
        if (kind < 0 || !p->kinds || (p->kinds >> kind & 1))
            tex_nearest_try(&nr, p->name, strlen(p->name));
    if (!tex_nearest_name(&nr))
        return NULL;
    snprintf(buf, n, "%s", tex_nearest_name(&nr));
    for (char *c = buf; *c; c++) /* rows' names are written with '-' in scenes and options */
        *c = *c == '_' ? '-' : *c;
    return buf;
}

const char *tex_choice_nearest(const char *choices, const char *word, char *buf, size_t n)
{
    struct tex_nearest nr;
    tex_nearest_init(&nr, word);
    tex_nearest_try_list(&nr, choices);
    if (!tex_nearest_name(&nr))
        return NULL;
    snprintf(buf, n, "%s", tex_nearest_name(&nr));
    return buf;
}

static int bad(const struct tex_param *p, enum tex_param_style style, const char *text, double v)
{
    char o[64], r[96], got[64], near[96] = "";

    if (text)
        snprintf(got, sizeof got, style == TEX_PARAM_OPTION ? "'%.50s'" : "%.50s", text);
    else
        snprintf(got, sizeof got, "%g", v);
    if (p->type == TEX_P_ENUM && text && tex_choice_nearest(p->choices, text, o, sizeof o))
        snprintf(near, sizeof near, "; did you mean %s?", o); /* a mistyped choice */
    return tex_usage_error("%s must be %s (got %s)%s", tex_param_name(p, o, sizeof o, style),
                           tex_param_range(p, r, sizeof r), got, near);
}

/* "Kd takes 1 or 3 numbers (got 2)" */
static int bad_count(const struct tex_param *p, enum tex_param_style style, int k)
{
    unsigned counts = p->counts ? p->counts : 1u << tex_param_count(p);
    char o[64], list[96] = "";
    size_t len = 0;
    int last = 0;

    for (int i = 1; i < 32; i++)
        if (counts >> i & 1)
            last = i;
    for (int i = 1; i < 32; i++)
        if (counts >> i & 1)
            len += (size_t)snprintf(list + len, sizeof list - len, "%s%d",
                                    len ? (i == last ? " or " : ", ") : "", i);
    return tex_usage_error("%s takes %s number%s (got %d)", tex_param_name(p, o, sizeof o, style),
                           list, last > 1 ? "s" : "", k);
}

/* Check k numbers against row p and store them (text: what they came from, for messages). */
static int store(const struct tex_param *p, void *obj, const double *v, int k,
                 enum tex_param_style style, const char *text)
{
    int n = tex_param_count(p);
    unsigned counts = p->counts ? p->counts : 1u << n;

    if (p->type == TEX_P_FLAG) {
        if (k != 1 || (v[0] != 0 && v[0] != 1))
            return bad(p, style, text, v[0]);
        *AT(obj, p, int) = (int)v[0];
        return 0;
    }
    if (n == 1 && !p->counts && k != 1) /* "3,4" for a number */
        return bad(p, style, text, v[0]);
    if (k < 1 || k > 31 || !(counts >> k & 1) || (k != 1 && k != n))
        return bad_count(p, style, k);
    for (int i = 0; i < k; i++)
        if (!isfinite(v[i]) || v[i] < p->min || v[i] > p->max ||
            (p->type == TEX_P_INT && v[i] != floor(v[i])))
            return bad(p, style, text, v[i]);
    for (int i = 0; i < n; i++) {
        double x = v[k == 1 ? 0 : i];
        if (p->type == TEX_P_INT)
            AT(obj, p, int)[i] = (int)x;
        else if (p->type == TEX_P_FLOAT)
            AT(obj, p, float)[i] = (float)x;
        else
            AT(obj, p, double)[i] = x;
    }
    return 0;
}

int tex_param_store(const struct tex_param *p, void *obj, const double *v, int k,
                    enum tex_param_style style)
{
    if (p->type != TEX_P_INT && p->type != TEX_P_REAL && p->type != TEX_P_FLOAT &&
        p->type != TEX_P_FLAG)
        return tex_usage_error("internal: %s does not take numbers", p->name);
    return store(p, obj, v, k, style, NULL);
}

/* Comma-separated numbers of an INT, REAL or FLOAT row; a FLAG given no text is on. */
static int parse_numbers(const struct tex_param *p, void *obj, const char *text,
                         enum tex_param_style style)
{
    double v[32];
    int k = 0;
    char buf[512], *tok, *save;

    if (p->type == TEX_P_FLAG && (!text || text[0] == '\0'))
        v[k++] = 1;
    else {
        if (strlen(text) >= sizeof buf)
            return bad(p, style, text, 0);
        strcpy(buf, text);
        for (tok = buf; tok; tok = save) {
            if ((save = strchr(tok, ',')))
                *save++ = '\0';
            if (k == 32 || tex_parse_real(tok, &v[k++]) < 0)
                return bad(p, style, text, 0);
        }
    }
    return store(p, obj, v, k, style, text);
}

int tex_param_set(const struct tex_param *p, void *obj, const char *text)
{
    return tex_param_parse(p, obj, text, TEX_PARAM_OPTION);
}

int tex_param_parse(const struct tex_param *p, void *obj, const char *text,
                    enum tex_param_style style)
{
    double v;

    switch (p->type) {
    case TEX_P_INT:
    case TEX_P_REAL:
    case TEX_P_FLOAT:
    case TEX_P_FLAG:
        return parse_numbers(p, obj, text, style);
    case TEX_P_ENUM: {
        const char *c = p->choices;
        size_t n = strlen(text);
        for (int i = 0; c && *c; i++) {
            const char *bar = strchr(c, '|');
            size_t len = bar ? (size_t)(bar - c) : strlen(c);
            if (len == n && strncmp(c, text, n) == 0) {
                *AT(obj, p, int) = i;
                return 0;
            }
            c = bar ? bar + 1 : c + len;
        }
        return bad(p, style, text, 0);
    }
    case TEX_P_REALS: {
        struct tex_reals *r = AT(obj, p, struct tex_reals);
        char buf[1024], *tok, *save;
        if (strlen(text) >= sizeof buf)
            return bad(p, style, text, 0);
        strcpy(buf, text);
        r->n = 0;
        /* strtok would skip empty fields: ",," must be an error, not a shorter list. */
        for (tok = buf; tok; tok = save) {
            if ((save = strchr(tok, ',')))
                *save++ = '\0';
            if (r->n == p->nmax || tex_parse_real(tok, &v) < 0 || v < p->min || v > p->max)
                return bad(p, style, text, 0);
            r->v[r->n++] = v;
        }
        return 0;
    }
    case TEX_P_COLOR:
        if (tex_parse_color(text, AT(obj, p, float)) < 0)
            return bad(p, style, text, 0);
        return 0;
    case TEX_P_STRING:
        *AT(obj, p, const char *) = text;
        return 0;
    case TEX_P_SPECIAL:
        break;
    }
    return tex_usage_error("internal: %s has no value to parse", p->name);
}

int tex_params_defaults(const struct tex_param *t, void *obj)
{
    for (; t && t->name; t++) {
        switch (t->type) {
        case TEX_P_SPECIAL:
            break;
        case TEX_P_INT:
        case TEX_P_REAL:
        case TEX_P_FLOAT:
        case TEX_P_FLAG:
            /* the number itself, checked as a parsed one would be: no text to parse */
            if (t->type == TEX_P_FLAG)
                *AT(obj, t, int) = 0;
            else if (t->defstr ? tex_param_set(t, obj, t->defstr) < 0
                               : store(t, obj, &t->def, 1, TEX_PARAM_OPTION, NULL) < 0)
                return -1;
            break;
        case TEX_P_STRING:
            *AT(obj, t, const char *) = t->defstr;
            break;
        default:
            if (!t->defstr) {
                if (t->type == TEX_P_ENUM)
                    *AT(obj, t, int) = 0;
                else if (t->type == TEX_P_REALS)
                    AT(obj, t, struct tex_reals)->n = 0;
                else
                    memset(AT(obj, t, float), 0, 4 * sizeof(float));
            } else if (tex_param_set(t, obj, t->defstr) < 0)
                return -1;
        }
    }
    return 0;
}

void tex_error_in_words(void)
{
    const char *m = tex_errmsg();
    char buf[1024];
    size_t n = 0;
    for (const char *c = m; *c && n + 1 < sizeof buf; c++) {
        int starts = c == m || !(isalnum((unsigned char)c[-1]) || c[-1] == '-');
        if (starts && c[0] == '-' && c[1] == '-' && islower((unsigned char)c[2]))
            c++; /* skip both dashes */
        else
            buf[n++] = *c;
    }
    buf[n] = '\0';
    if (tex_errkind() == TEX_ERR_USAGE)
        tex_usage_error("%s", buf);
    else
        tex_error("%s", buf);
}
