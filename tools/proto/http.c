/* http.c - the editor's HTTP server (libmicrohttpd): the token, the rate limit, the
 * routes and their replies */
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <arpa/inet.h>

#include "textura.h"
#include "proto.h"

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

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
    if (!t || strlen(t) != strlen(proto.token))
        return 0;
    unsigned d = 0; /* in constant time */
    for (size_t i = 0; proto.token[i]; i++)
        d |= (unsigned)(t[i] ^ proto.token[i]);
    return d == 0;
}

int get_size(struct MHD_Connection *c, struct pipeline *pl, int def)
{
    const char *s = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "size");
    double x;
    if (!s)
        return def;
    if (tex_parse_real(s, &x) < 0 || x != (int)x || x < 1 || x > MAX_SIDE)
        return fail(pl, "size must be 1..%d (got '%.20s')", MAX_SIDE, s);
    return (int)x;
}

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
        snprintf(map, sizeof map, "%s/map.%lx.exr", proto.tmpdir,
                 (unsigned long)pthread_self());
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

struct MHD_Daemon *serve(int port)
{
    struct sockaddr_in sa = {0};

    signal(SIGPIPE, SIG_IGN);
    sa.sin_family = AF_INET;
    sa.sin_port = htons((unsigned short)port);
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK); /* never another interface */
    return MHD_start_daemon(MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_ERROR_LOG, 0, NULL, NULL,
                            handle, NULL, MHD_OPTION_SOCK_ADDR, (struct sockaddr *)&sa,
                            MHD_OPTION_THREAD_POOL_SIZE, 4, MHD_OPTION_CONNECTION_TIMEOUT, 15,
                            MHD_OPTION_CONNECTION_LIMIT, 64, MHD_OPTION_CONNECTION_MEMORY_LIMIT,
                            (size_t)65536, MHD_OPTION_END);
}
