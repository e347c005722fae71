/* t_proto - the prototyping module: an interactive texture editor served on localhost
 *
 * The page (share/textura/proto/index.html) picks a primitive, sets its parameters from
 * the descriptor rows, adds pipeline steps, and shows the map and a standard scene.  Every
 * map is made by the tools themselves, run as a pipeline of processes without a shell
 * (argv arrays of checked words): the command line the page shows is what ran, so it
 * gives the same bytes when run in a shell.  Safe by default: 127.0.0.1 only, a random
 * token on every request (403 without it), saves confined to the working folder (plain
 * names, no symlinks), bounded sizes, bodies and times, 429 on bursts. */
#define _GNU_SOURCE /* pipe2, posix_spawn_file_actions_addchdir_np */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <arpa/inet.h>
#include <microhttpd.h>

#include "io/json.h"
#include "textura.h"

extern char **environ;

#define MAX_BODY 65536    /* bytes of a request body */
#define MAX_SIDE 4096     /* largest map the editor makes */
#define MAX_WORDS 48      /* argv words of one stage */
#define MAX_STAGES 10     /* primitive + steps + the writer */
#define RUN_SECONDS 30    /* a pipeline's time limit */
#define BURST 60          /* requests allowed at once ... */
#define RATE 40           /* ... refilled per second */

static struct opts {
    int port;
    const char *dir, *defs, *bind;
} o = {0, ".", NULL, "127.0.0.1"};

static const struct tex_param rows[] = {
    TEX_INT(struct opts, port, 'p', 0, 0, 65535, "N", "port to listen on (0: any free port)"),
    TEX_STRING(struct opts, dir, 'C', ".", "DIR", "working folder: saves go there and only there"),
    TEX_STRING(struct opts, defs, 0, NULL, "FILE",
               "composed primitives (textura(5)) offered beside the built-in ones"),
    {0}};

static char token[33], bindir[PATH_MAX], tmpdir[64];
static int workfd = -1;
static struct tex_procs *procs;
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

/* ---- the descriptors, as JSON for the page ---- */

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

static void api_prims(struct tex_str *b)
{
    char names[4096];
    tex_str_add(b, "{\"primitives\":[");
    for (int i = 0; tex_primitives[i]; i++)
        json_prim(b, tex_primitives[i], 0, i == 0);
    for (int i = 0; tex_procs_get(procs, i); i++)
        json_prim(b, tex_procs_get(procs, i), 1, 0);
    tex_str_add(b, "],\"palettes\":");
    tex_json_string(b, tex_palette_names(names, sizeof names) >= 0 ? names : "");
    tex_str_add(b, "}");
}

/* ---- requests into pipelines ---- */

struct stage {
    const char *argv[MAX_WORDS + 1];
    int n;
};

struct pipeline {
    struct stage st[MAX_STAGES];
    int n;
    char words[MAX_STAGES * MAX_WORDS][128];
    int nwords;
    char err[512];
};

static const char *word(struct pipeline *pl, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static const char *word(struct pipeline *pl, const char *fmt, ...)
{
    va_list ap;
    if (pl->nwords == MAX_STAGES * MAX_WORDS)
        return NULL;
    char *w = pl->words[pl->nwords++];
    va_start(ap, fmt);
    vsnprintf(w, sizeof pl->words[0], fmt, ap);
    va_end(ap);
    return w;
}

static int arg(struct pipeline *pl, const char *w)
{
    struct stage *s = &pl->st[pl->n - 1];
    if (!w || s->n == MAX_WORDS) {
        snprintf(pl->err, sizeof pl->err, "too many words in one step");
        return -1;
    }
    s->argv[s->n++] = w;
    return 0;
}

static int stage(struct pipeline *pl, const char *tool)
{
    if (pl->n == MAX_STAGES) {
        snprintf(pl->err, sizeof pl->err, "too many steps (at most %d)", MAX_STAGES - 2);
        return -1;
    }
    pl->st[pl->n++].n = 0;
    return arg(pl, word(pl, "%s", tool));
}

static int fail(struct pipeline *pl, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(struct pipeline *pl, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pl->err, sizeof pl->err, fmt, ap);
    va_end(ap);
    return -1;
}

/* A value for a row: checked by the row itself, as the tool will. */
static int check_value(struct pipeline *pl, const struct tex_param *p, const char *v)
{
    void *scratch = calloc(1, p->off + 4096); /* room for the row's value */
    int rc = 0;
    if (strlen(v) > 100)
        rc = fail(pl, "value too long (%.20s...)", v);
    else if (!scratch || tex_param_parse(p, scratch, v, TEX_PARAM_OPTION) < 0)
        rc = fail(pl, "%s", tex_errmsg());
    free(scratch);
    return rc;
}

static int is_name(const char *s)
{
    if (!*s || strlen(s) > 64)
        return 0;
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_' || *s == '-'))
            return 0;
    return 1;
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
    prim = tex_procs_find(procs, MHD_lookup_connection_value(r->c, MHD_GET_ARGUMENT_KIND, "prim"));
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
    for (char *c = name; *c; c++) /* the option's spelling */
        if (*c == '_')
            *c = '-';
    if (row->type == TEX_P_FLAG) {
        if (strcmp(colon + 1, "0") && strcmp(colon + 1, "1"))
            r->failed = fail(r->pl, "--%s is 0 or 1 (got '%.20s')", name, colon + 1);
        else if (!strcmp(colon + 1, "1") && arg(r->pl, word(r->pl, "--%s", name)) < 0)
            r->failed = -1;
    } else if (check_value(r->pl, row, colon + 1) < 0 ||
               arg(r->pl, word(r->pl, "--%s=%s", name, colon + 1)) < 0) {
        r->failed = -1;
    }
    return r->failed ? MHD_NO : MHD_YES;
}

/* NAME.pal, a plain file in the working folder (the palette editor saves there). */
static int is_saved_palette(const char *name)
{
    struct stat st;
    size_t n = strlen(name);
    if (n < 5 || n > 100 || strcmp(name + n - 4, ".pal") || name[0] == '.' || strchr(name, '/'))
        return 0;
    for (const char *s = name; *s; s++)
        if (!(*s == '.' || *s == '_' || *s == '-' || (*s >= '0' && *s <= '9') ||
              (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z')))
            return 0;
    return fstatat(workfd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
}

/* step=KIND:ARG:ARG...: one pipeline step, each word checked. */
static int step(struct pipeline *pl, const char *spec, int size)
{
    char buf[256], *w[8];
    int n = 0;
    double x;
    if (strlen(spec) >= sizeof buf)
        return fail(pl, "step too long");
    strcpy(buf, spec);
    for (char *s = strtok(buf, ":"); s && n < 8; s = strtok(NULL, ":"))
        w[n++] = s;
    if (!n)
        return fail(pl, "empty step");
    for (int i = 1; i < n; i++)
        if (tex_parse_real(w[i], &x) < 0 && !is_name(w[i]) && !is_saved_palette(w[i]))
            return fail(pl, "malformed step argument '%.40s'", w[i]);
    if (!strcmp(w[0], "palette") && n == 2 && is_saved_palette(w[1])) /* one the editor saved */
        return stage(pl, "t_palette") | arg(pl, word(pl, "%s/%s", o.dir, w[1])) | arg(pl, "-");
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
    if (step(r->pl, value, r->size) < 0) {
        r->failed = -1;
        return MHD_NO;
    }
    return MHD_YES;
}

/* The pipeline of a request: the primitive's tool, its parameters, the steps. */
static int build(struct MHD_Connection *c, struct pipeline *pl, int size)
{
    const char *name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "prim");
    const char *seed = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "seed");
    const char *tile = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "tile");
    const struct tex_primitive *p;
    struct req r = {c, pl, size, 0};
    double s;

    if (!name || !is_name(name) || !(p = tex_procs_find(procs, name)))
        return fail(pl, "unknown primitive '%.40s'", name ? name : "");
    if (tex_primitive_find(name)) {
        if (stage(pl, word(pl, "t_%s", name)) < 0)
            return -1;
    } else if (stage(pl, "t_expr") | arg(pl, "--defs") | arg(pl, o.defs) | arg(pl, name)) {
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

static void cmdline(const struct pipeline *pl, struct tex_str *b)
{
    for (int i = 0; i < pl->n; i++) {
        if (i)
            tex_str_add(b, " | ");
        for (int k = 0; k < pl->st[i].n; k++) {
            const char *w = pl->st[i].argv[k];
            int plain = strspn(w, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                  "0123456789_-=.,/:") == strlen(w);
            tex_str_add(b, plain ? "%s%s" : "%s'%s'", k ? " " : "", w);
        }
    }
}

/* The pipeline's stages started, each reading the one before (the first /dev/null), the
 * last writing to out, all to errfd; pid[i] 0 where one could not start */
static void spawn_stages(struct pipeline *pl, pid_t *pid, int out, int errfd)
{
    int in = -1;
    char path[PATH_MAX + 64];

    for (int i = 0; i < pl->n; i++) {
        int p[2] = {-1, out};
        posix_spawn_file_actions_t fa;
        if (i < pl->n - 1 && pipe2(p, O_CLOEXEC) < 0)
            break;
        posix_spawn_file_actions_init(&fa);
        if (in >= 0)
            posix_spawn_file_actions_adddup2(&fa, in, 0);
        else
            posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_adddup2(&fa, i < pl->n - 1 ? p[1] : out, 1);
        posix_spawn_file_actions_adddup2(&fa, errfd, 2);
        posix_spawn_file_actions_addchdir_np(&fa, tmpdir);
        snprintf(path, sizeof path, "%s/%s", bindir, pl->st[i].argv[0]);
        pl->st[i].argv[pl->st[i].n] = NULL;
        if (posix_spawn(&pid[i], path, &fa, NULL, (char **)pl->st[i].argv, environ) != 0)
            pid[i] = 0;
        posix_spawn_file_actions_destroy(&fa);
        if (in >= 0)
            close(in);
        if (i < pl->n - 1) {
            close(p[1]);
            in = p[0];
        }
    }
}

/* Run the pipeline; the last stage's standard output into out.  Returns the
 * worst exit status (0 ok, 1 runtime, 2 usage) with stderr's first line in err. */
static int run(struct pipeline *pl, struct tex_str *out)
{
    pid_t pid[MAX_STAGES] = {0};
    int errp[2], outp[2], status = 0;
    struct tex_str err = {0};
    time_t end = time(NULL) + RUN_SECONDS;

    if (pipe2(errp, O_CLOEXEC) < 0 || pipe2(outp, O_CLOEXEC) < 0)
        return fail(pl, "cannot make a pipe"), 1;
    spawn_stages(pl, pid, outp[1], errp[1]);
    close(outp[1]);
    close(errp[1]);
    struct pollfd fds[2] = {{outp[0], POLLIN, 0}, {errp[0], POLLIN, 0}};
    while (fds[0].fd >= 0 || fds[1].fd >= 0) {
        int left = (int)(end - time(NULL));
        if (left <= 0 || poll(fds, 2, left * 1000) <= 0) {
            for (int i = 0; i < pl->n; i++)
                if (pid[i] > 0)
                    kill(pid[i], SIGKILL);
            snprintf(pl->err, sizeof pl->err, "the pipeline took longer than %d s", RUN_SECONDS);
            status = 1;
            break;
        }
        for (int k = 0; k < 2; k++) {
            char buf[65536];
            ssize_t got;
            if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            if ((got = read(fds[k].fd, buf, sizeof buf)) <= 0) {
                close(fds[k].fd);
                fds[k].fd = -1;
                continue;
            }
            struct tex_str *b = k ? &err : out;
            if (b->n + got > (size_t)64 << 20) /* more than any map of MAX_SIDE */
                continue;
            tex_str_bytes(b, buf, (size_t)got);
        }
    }
    for (int k = 0; k < 2; k++)
        if (fds[k].fd >= 0)
            close(fds[k].fd);
    for (int i = 0; i < pl->n; i++) {
        int ws;
        if (pid[i] <= 0) {
            status = 1;
            snprintf(pl->err, sizeof pl->err, "cannot run %s", pl->st[i].argv[0]);
            continue;
        }
        waitpid(pid[i], &ws, 0);
        int code = WIFEXITED(ws) ? WEXITSTATUS(ws) : 1;
        if (code > status)
            status = code;
    }
    if (status && err.s) {
        char *nl = strchr(err.s, '\n');
        if (nl)
            *nl = 0;
        snprintf(pl->err, sizeof pl->err, "%s", err.s);
    }
    free(err.s);
    return status;
}

/* ---- saving into the working folder ---- */

/* A plain name in the working folder: no folder part, no "..", no leading dot, not a
 * symlink; ext one of the allowed extensions for the kind. */
static int save_name(struct pipeline *pl, const char *name, const char *const *exts)
{
    struct stat st;
    const char *dot;
    if (!name || !*name || strlen(name) > 100 || strchr(name, '/') || name[0] == '.' ||
        strstr(name, ".."))
        return fail(pl, "save names are plain file names in the working folder (got '%.40s')",
                    name ? name : "");
    for (const char *s = name; *s; s++)
        if (!(*s == '.' || *s == '_' || *s == '-' || (*s >= '0' && *s <= '9') ||
              (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z')))
            return fail(pl, "save names use letters, digits, '.', '_' and '-' (got '%.40s')",
                        name);
    if (fstatat(workfd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
        return fail(pl, "'%s' exists and is not a plain file (a symlink or a folder)", name);
    if (!(dot = strrchr(name, '.')))
        return fail(pl, "'%s' needs an extension", name);
    for (int i = 0; exts[i]; i++)
        if (!strcmp(dot + 1, exts[i]))
            return 0;
    return fail(pl, "'%s': the extension must be one of the kind's (%s...)", name, exts[0]);
}

/* The last stage writes name's format on standard output (the shell redirects it). */
static int to_file(struct pipeline *pl, const char *name)
{
    return arg(pl, word(pl, "--format=%s", strrchr(name, '.') + 1));
}

/* Write text to name in the working folder, atomically, never through a symlink. */
static int save_text(struct pipeline *pl, const char *name, const char *text, size_t n)
{
    char tmp[160];
    snprintf(tmp, sizeof tmp, ".%s.%d.tmp", name, (int)getpid());
    int fd = openat(workfd, tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        return fail(pl, "cannot write '%s': %s", name, strerror(errno));
    int ok = write(fd, text, n) == (ssize_t)n;
    ok &= close(fd) == 0;
    if (!ok || renameat(workfd, tmp, workfd, name) < 0) {
        unlinkat(workfd, tmp, 0);
        return fail(pl, "cannot write '%s'", name);
    }
    return 0;
}

/* ---- HTTP ---- */

static enum MHD_Result reply(struct MHD_Connection *c, unsigned code, const char *type,
                             const void *data, size_t n)
{
    struct MHD_Response *r = MHD_create_response_from_buffer(n, (void *)data,
                                                             MHD_RESPMEM_MUST_COPY);
    if (!r)
        return MHD_NO;
    MHD_add_response_header(r, "Content-Type", type);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    enum MHD_Result ret = MHD_queue_response(c, code, r);
    MHD_destroy_response(r);
    return ret;
}

static enum MHD_Result text(struct MHD_Connection *c, unsigned code, const char *msg)
{
    return reply(c, code, "text/plain; charset=utf-8", msg, strlen(msg));
}

/* A token bucket over every request: bursts past BURST get 429. */
static int allowed(void)
{
    static double tokens = BURST;
    static struct timespec last;
    struct timespec now;
    int ok;
    clock_gettime(CLOCK_MONOTONIC, &now);
    pthread_mutex_lock(&lock);
    if (last.tv_sec)
        tokens += RATE * ((now.tv_sec - last.tv_sec) + (now.tv_nsec - last.tv_nsec) * 1e-9);
    if (tokens > BURST)
        tokens = BURST;
    last = now;
    ok = tokens >= 1;
    if (ok)
        tokens -= 1;
    pthread_mutex_unlock(&lock);
    return ok;
}

static int token_ok(struct MHD_Connection *c)
{
    const char *t = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "token");
    if (!t)
        t = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "X-Token");
    if (!t || strlen(t) != strlen(token))
        return 0;
    unsigned d = 0; /* in constant time */
    for (size_t i = 0; token[i]; i++)
        d |= (unsigned)(t[i] ^ token[i]);
    return d == 0;
}

static int get_size(struct MHD_Connection *c, struct pipeline *pl, int def)
{
    const char *s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "size");
    double x;
    if (!s)
        return def;
    if (tex_parse_real(s, &x) < 0 || x != (int)x || x < 1 || x > MAX_SIDE)
        return fail(pl, "size must be 1..%d (got '%.20s')", MAX_SIDE, s);
    return (int)x;
}

/* The standard scene (thesis 4.3.7): the map on a sphere over a plane, through the
 * application function chosen (Kd, Ks, bump). */
static int scene_stage(struct pipeline *pl, const char *fn, const char *map)
{
    char scene[PATH_MAX];
    struct tex_str s = {0};
    const char *apply = !fn || !strcmp(fn, "Kd") ? "Kd = f"
                        : !strcmp(fn, "Ks")      ? "Ks = f"
                        : !strcmp(fn, "bump")    ? "bump = 2"
                                                 : NULL;
    if (!apply)
        return fail(pl, "the application function must be Kd, Ks or bump (got '%.20s')", fn);
    tex_str_add(&s, "image 192 144\nsamples 1\nambient 0.25 0.25 0.25\nbackground 0.15 0.15 0.17\n"
             "camera { eye 0 1.3 -3.6 look 0 0.7 0 fov 42 }\n"
             "light point { position -3 5 -4 intensity 1 }\n"
             "texture m file \"%s\"\n"
             "surface ball { Kd 0.8 Ks 0.3 n 40 apply m { mapping sphere %s } }\n"
             "surface floor { Kd 0.7 Ks 0.1 n 10 apply m { scale 0.5 %s } }\n"
             "sphere { centre 0 0.8 0 radius 0.8 surface ball }\n"
             "plane { surface floor }\n",
         map, apply, apply);
    snprintf(scene, sizeof scene, "%s/scene.%lx.scene", tmpdir, (unsigned long)pthread_self());
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

/* The map and project files the editor may write */
static const char *const map_exts[] = {"png", "exr", "tif", "pfm", NULL};
static const char *const proj_exts[] = {"tproj", "txt", NULL};

/* /api/preview, /api/cmdline and /api/scene (what): the pipeline's PNG, command line, or
 * scene render into out, of *type; the HTTP status */
static unsigned api_render(struct MHD_Connection *c, struct pipeline *pl, const char *what,
                           struct tex_str *out, const char **type)
{
    unsigned code = 200;
    int size = get_size(c, pl, 256);
    if (size < 0 || build(c, pl, size) < 0) {
        code = 400;
    } else if (!strcmp(what, "cmdline")) {
        const char *map = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "map");
        if (map && (save_name(pl, map, map_exts) < 0 || to_file(pl, map) < 0)) {
            code = 400;
        } else {
            cmdline(pl, out);
            if (map)
                tex_str_add(out, " > %s", map);
        }
    } else {
        char map[PATH_MAX];
        snprintf(map, sizeof map, "%s/map.%lx.exr", tmpdir, (unsigned long)pthread_self());
        int r = !strcmp(what, "scene") ? arg(pl, word(pl, "-o%s", map))
                                        : arg(pl, "--format=png");
        r = r < 0 ? 2 : run(pl, out);
        if (!r && !strcmp(what, "scene")) {
            free(out->s);
            *out = (struct tex_str){0};
            const char *fn = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "apply");
            r = scene_stage(pl, fn, map) < 0 ? 2 : run(pl, out);
        }
        code = r == 0 ? 200 : r == 2 ? 400 : 500;
        *type = r == 0 ? "image/png" : *type;
    }
    return code;
}

/* /api/save: a map, palette, command line, scene or project into the work directory */
static unsigned api_save(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out)
{
    struct tex_str b = {0};
    static const char *const pal_exts[] = {"pal", NULL};
    static const char *const sh_exts[] = {"sh", "txt", NULL};
    static const char *const scene_exts[] = {"scene", "txt", NULL};
    const char *kind = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "kind");
    const char *name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "name");
    const char *body = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "text");
    int size = get_size(c, pl, 512), rc = -1;
    kind = kind ? kind : "";
    if (!strcmp(kind, "palette") || !strcmp(kind, "project")) {
        /* text the page made: a palette file, or a project (the query) */
        if (save_name(pl, name, kind[1] == 'a' ? pal_exts : proj_exts) == 0) {
            if (!body || strlen(body) > 16384)
                fail(pl, "the %s's text is missing or longer than 16384 bytes", kind);
            else if (kind[1] == 'a') {
                tex_palette *p = tex_palette_parse(body, strlen(body), name);
                rc = p ? save_text(pl, name, body, strlen(body)) : fail(pl, "%s", tex_errmsg());
                tex_palette_free(p);
            } else {
                rc = save_text(pl, name, body, strlen(body));
            }
        }
    } else if (size < 0 || build(c, pl, size) < 0) {
        ;
    } else if (!strcmp(kind, "map")) {
        /* the map as the command line makes it: standard output, into the file */
        if (save_name(pl, name, map_exts) == 0 && to_file(pl, name) == 0 && !run(pl, out))
            rc = save_text(pl, name, out->s, out->n);
        free(out->s);
        *out = (struct tex_str){0};
    } else if (!strcmp(kind, "cmdline") || !strcmp(kind, "scene")) {
        if (save_name(pl, name, kind[0] == 'c' ? sh_exts : scene_exts) == 0) {
            const char *map = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "map");
            if (kind[0] == 's') { /* the scene's texture statement, its map from standard input */
                tex_str_add(&b, "# ");
                cmdline(pl, &b);
                tex_str_add(&b, " | t_apply THIS.scene\ntexture map file -\n");
            } else if (save_name(pl, map, map_exts) == 0 && to_file(pl, map) == 0) {
                tex_str_add(&b, "#!/bin/sh\n");
                cmdline(pl, &b);
                tex_str_add(&b, " > %s\n", map);
            }
            rc = b.n ? save_text(pl, name, b.s, b.n) : -1;
        }
    } else {
        fail(pl, "kind must be map, palette, cmdline, scene or project (got '%.20s')", kind);
    }
    if (rc == 0)
        tex_str_add(out, "saved %s", name);
    free(b.s);
    return rc == 0 ? 200 : 400;
}

/* /api/load: a project's text into out */
static unsigned api_load(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out)
{
    unsigned code = 400;
    const char *name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "name");
    if (save_name(pl, name, proj_exts) == 0) {
        int fd = openat(workfd, name, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
        tex_buf tb = {0};
        if (fd < 0 || tex_read_fd(fd, &tb, name) < 0 || tb.len > 16384)
            fail(pl, "cannot read project '%s'", name);
        else {
            tex_str_bytes(out, (const char *)tb.data, tb.len);
            code = 200;
        }
        if (fd >= 0)
            close(fd);
        tex_buf_free(&tb);
    }
    return code;
}

static enum MHD_Result handle(void *cls, struct MHD_Connection *c, const char *url,
                              const char *method, const char *version, const char *data,
                              size_t *data_size, void **state)
{
    static int first_call;
    struct pipeline *pl;
    struct tex_str out = {0};
    enum MHD_Result ret;
    (void)cls, (void)version, (void)data;

    if (!*state) { /* the headers: refuse big bodies before reading them */
        const char *len = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Content-Length");
        *state = &first_call;
        if (len && strtoull(len, NULL, 10) > MAX_BODY)
            return text(c, 413, "request body too large");
        return MHD_YES;
    }
    if (*data_size) { /* the editor sends no bodies: drop them, bounded */
        static _Thread_local size_t seen;
        seen += *data_size;
        *data_size = 0;
        if (seen > MAX_BODY) {
            seen = 0;
            return text(c, 413, "request body too large");
        }
        return MHD_YES;
    }
    if (!allowed())
        return text(c, 429, "too many requests: slow down");
    if (strcmp(method, "GET"))
        return text(c, 405, "only GET");
    if (!token_ok(c))
        return text(c, 403, "missing or wrong token: use the URL t_proto printed");
    if (!strcmp(url, "/") || !strcmp(url, "/index.html")) {
        char path[PATH_MAX];
        size_t n;
        snprintf(path, sizeof path, "%s/proto/index.html", tex_install_dir(TEX_DIR_DATA));
        char *page = tex_read_text(path, 1 << 20, &n, "the page");
        if (!page)
            return text(c, 500, tex_errmsg());
        ret = reply(c, 200, "text/html; charset=utf-8", page, n);
        free(page);
        return ret;
    }
    if (!strcmp(url, "/api/primitives")) {
        api_prims(&out);
        ret = reply(c, 200, "application/json", out.s, out.n);
        free(out.s);
        return ret;
    }
    if (!(pl = calloc(1, sizeof *pl)))
        return text(c, 500, "out of memory");
    const char *what = url + (strncmp(url, "/api/", 5) ? 0 : 5);
    unsigned code;
    const char *type = "text/plain; charset=utf-8";
    if (!strcmp(what, "preview") || !strcmp(what, "cmdline") || !strcmp(what, "scene")) {
        code = api_render(c, pl, what, &out, &type);
    } else if (!strcmp(what, "save")) {
        code = api_save(c, pl, &out);
    } else if (!strcmp(what, "load")) {
        code = api_load(c, pl, &out);
    } else {
        code = 404;
        snprintf(pl->err, sizeof pl->err, "no such page");
    }
    if (code == 200)
        ret = reply(c, code, type, out.s ? out.s : "", out.n);
    else
        ret = text(c, code, pl->err[0] ? pl->err : "failed");
    free(out.s);
    free(pl);
    return ret;
}

static void self_dir(void)
{
    ssize_t n = readlink("/proc/self/exe", bindir, sizeof bindir - 1);
    bindir[n > 0 ? n : 0] = 0;
    char *slash = strrchr(bindir, '/');
    if (slash)
        *slash = 0;
}

int main(int argc, char **argv)
{
    static const struct tex_tool tool = {"t_proto", "", "an interactive texture editor in the "
                                         "browser, served on 127.0.0.1", 0, rows, 0, 0};
    struct tex_common c;
    struct sockaddr_in sa = {0};
    unsigned char rnd[16];
    struct MHD_Daemon *d;

    static char dir[PATH_MAX];
    tex_cli_parse(&tool, argc, argv, &c, &o);
    self_dir();
    if (!realpath(o.dir, dir) || (workfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC)) < 0)
        tex_usage_die("cannot open the working folder '%s'", o.dir);
    o.dir = dir; /* the tools run elsewhere: the map's path must be whole */
    static char defs[PATH_MAX];
    if (o.defs && realpath(o.defs, defs))
        o.defs = defs; /* the same for t_expr --defs */
    if (!(procs = tex_procs_new()) || (o.defs && tex_procs_read(procs, o.defs) < 0))
        tex_die();
    FILE *ur = fopen("/dev/urandom", "rb");
    if (!ur || fread(rnd, 1, sizeof rnd, ur) != sizeof rnd)
        tex_usage_die("cannot read /dev/urandom for the token");
    fclose(ur);
    for (int i = 0; i < 16; i++)
        sprintf(token + 2 * i, "%02x", rnd[i]);
    snprintf(tmpdir, sizeof tmpdir, "/tmp/t_proto.XXXXXX");
    if (!mkdtemp(tmpdir))
        tex_usage_die("cannot make a temporary folder");
    signal(SIGPIPE, SIG_IGN);
    sa.sin_family = AF_INET;
    sa.sin_port = htons((unsigned short)o.port);
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK); /* never another interface */
    d = MHD_start_daemon(MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_ERROR_LOG, 0, NULL, NULL,
                         handle, NULL, MHD_OPTION_SOCK_ADDR, (struct sockaddr *)&sa,
                         MHD_OPTION_THREAD_POOL_SIZE, 4, MHD_OPTION_CONNECTION_TIMEOUT, 15,
                         MHD_OPTION_CONNECTION_LIMIT, 64, MHD_OPTION_CONNECTION_MEMORY_LIMIT,
                         (size_t)65536, MHD_OPTION_END);
    if (!d)
        tex_usage_die("cannot listen on 127.0.0.1:%d", o.port);
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(d, MHD_DAEMON_INFO_BIND_PORT);
    printf("t_proto: serving %s on http://127.0.0.1:%u/?token=%s\n", o.dir,
           info ? info->port : (unsigned)o.port, token);
    fflush(stdout);
    for (;;)
        pause(); /* until a signal ends the process */
}
