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
#include <sys/socket.h>

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

/* A token bucket per client address, for requests that carry the token: bursts past BURST
 * get 429, and requests without it (403 anyway) never use up the page's. */
static int allowed(struct MHD_Connection *c)
{
    static struct bucket {
        unsigned long addr;
        double tokens;
        struct timespec last;
    } b[32];
    const union MHD_ConnectionInfo *ci =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_CLIENT_ADDRESS);
    unsigned long addr = ci && ci->client_addr && ci->client_addr->sa_family == AF_INET
                             ? ((const struct sockaddr_in *)ci->client_addr)->sin_addr.s_addr
                             : 0;
    struct timespec now;
    int ok, k = 0;
    clock_gettime(CLOCK_MONOTONIC, &now);
    pthread_mutex_lock(&lock);
    for (int i = 0; i < 32; i++) { /* the client's bucket, else the longest unused */
        if (b[i].last.tv_sec && b[i].addr == addr) {
            k = i;
            break;
        }
        if (b[i].last.tv_sec < b[k].last.tv_sec)
            k = i;
    }
    if (!b[k].last.tv_sec || b[k].addr != addr)
        b[k] = (struct bucket){addr, BURST, now};
    b[k].tokens += RATE * ((now.tv_sec - b[k].last.tv_sec) + (now.tv_nsec - b[k].last.tv_nsec) * 1e-9);
    if (b[k].tokens > BURST)
        b[k].tokens = BURST;
    b[k].last = now;
    ok = b[k].tokens >= 1;
    if (ok)
        b[k].tokens -= 1;
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

/* Host (and Origin, when sent) name this server: another name is a page of another site
 * that rebinds its name to 127.0.0.1 (DNS rebinding), or a cross-site request. */
static int ours(const char *v, const char *scheme)
{
    char a[64], b[64];
    snprintf(a, sizeof a, "%s127.0.0.1:%u", scheme, proto.port);
    snprintf(b, sizeof b, "%slocalhost:%u", scheme, proto.port);
    return v && (!strcmp(v, a) || !strcmp(v, b));
}

/* Every connection, by its socket: when it came or last finished a request, and what it
 * does now.  A watchdog drops one still arriving after HEAD_SECONDS (a trickle of bytes
 * resets MHD's idle timeout, not this), or sending after 2 * HEAD_SECONDS; a new one drops
 * the oldest arriving one when CONN_SLOTS are held, so slow clients never starve others. */
enum phase { ARRIVING, RUNNING, SENDING };
struct conn {
    int fd, dropped;
    enum phase phase;
    struct timespec since;
    size_t seen; /* body bytes dropped in this request */
    struct conn *next;
};
static struct conn *conns;
static pthread_mutex_t conns_lock = PTHREAD_MUTEX_INITIALIZER;

static double age(const struct conn *k, const struct timespec *now)
{
    return (double)(now->tv_sec - k->since.tv_sec) + (now->tv_nsec - k->since.tv_nsec) * 1e-9;
}

static void drop(struct conn *k)
{
    if (!k->dropped)
        shutdown(k->fd, SHUT_RDWR); /* MHD then sees the end and closes it */
    k->dropped = 1;
}

static void set_phase(struct MHD_Connection *c, enum phase ph)
{
    const union MHD_ConnectionInfo *ci =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    struct conn *k = ci ? ci->socket_context : NULL;
    if (!k)
        return;
    pthread_mutex_lock(&conns_lock);
    k->phase = ph;
    clock_gettime(CLOCK_MONOTONIC, &k->since);
    if (ph == ARRIVING)
        k->seen = 0;
    pthread_mutex_unlock(&conns_lock);
}

static void notify(void *cls, struct MHD_Connection *c, void **ctx,
                   enum MHD_ConnectionNotificationCode code)
{
    (void)cls;
    pthread_mutex_lock(&conns_lock);
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        const union MHD_ConnectionInfo *ci =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
        struct conn *k = calloc(1, sizeof *k), *old = NULL;
        int n = 0;
        for (struct conn *q = conns; q; q = q->next)
            if (!q->dropped) {
                n++;
                if (q->phase == ARRIVING && (!old || q->since.tv_sec < old->since.tv_sec ||
                                             (q->since.tv_sec == old->since.tv_sec &&
                                              q->since.tv_nsec < old->since.tv_nsec)))
                    old = q;
            }
        if (n >= CONN_SLOTS && old)
            drop(old);
        if (k && ci) {
            k->fd = ci->connect_fd;
            clock_gettime(CLOCK_MONOTONIC, &k->since);
            k->next = conns;
            conns = k;
        } else if (ci) {
            shutdown(ci->connect_fd, SHUT_RDWR);
            free(k);
            k = NULL;
        }
        *ctx = k;
    } else if (*ctx) {
        for (struct conn **q = &conns; *q; q = &(*q)->next)
            if (*q == *ctx) {
                *q = (*q)->next;
                break;
            }
        free(*ctx);
        *ctx = NULL;
    }
    pthread_mutex_unlock(&conns_lock);
}

static void completed(void *cls, struct MHD_Connection *c, void **state,
                      enum MHD_RequestTerminationCode toe)
{
    (void)cls, (void)state, (void)toe;
    set_phase(c, ARRIVING); /* a kept connection waits for its next request */
}

static void *watchdog(void *arg)
{
    (void)arg;
    for (;;) {
        struct timespec now, nap = {0, 200000000};
        nanosleep(&nap, NULL);
        clock_gettime(CLOCK_MONOTONIC, &now);
        pthread_mutex_lock(&conns_lock);
        for (struct conn *k = conns; k; k = k->next)
            if ((k->phase == ARRIVING && age(k, &now) > HEAD_SECONDS) ||
                (k->phase == SENDING && age(k, &now) > 2 * HEAD_SECONDS))
                drop(k);
        pthread_mutex_unlock(&conns_lock);
    }
    return NULL;
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
        char map[PATH_MAX + 64];
        snprintf(map, sizeof map, "%s/map.%lx.exr", proto.tmpdir,
                 (unsigned long)pthread_self());
        int r = !strcmp(what, "scene") ? arg(pl, word(pl, "-o%s", map))
                                        : arg(pl, "--format=png");
        r = r < 0 ? 2 : run(pl, out);
        if (!r && !strcmp(what, "scene")) {
            free(out->s);
            *out = (struct tex_str){0};
            const char *fn = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "apply");
            const char *k = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "strength");
            r = scene_stage(pl, fn, k, map) < 0 ? 2 : run(pl, out);
        }
        code = r == 0 ? 200 : r == 2 ? 400 : 500;
        *type = r == 0 ? "image/png" : *type;
    }
    return code;
}

/* The page and the API: the reply queued. */
static enum MHD_Result route(struct MHD_Connection *c, const char *url, struct tex_str *out)
{
    struct pipeline *pl;
    enum MHD_Result ret;
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
        api_prims(out);
        ret = reply(c, 200, "application/json", out->s, out->n);
        free(out->s);
        return ret;
    }
    if (!(pl = calloc(1, sizeof *pl)))
        return text(c, 500, "out of memory");
    pl->end = time(NULL) + RUN_SECONDS; /* the request's runs together */
    const char *what = url + (strncmp(url, "/api/", 5) ? 0 : 5);
    unsigned code;
    const char *type = "text/plain; charset=utf-8";
    if (!strcmp(what, "preview") || !strcmp(what, "cmdline") || !strcmp(what, "scene")) {
        code = api_render(c, pl, what, out, &type);
    } else if (!strcmp(what, "graph")) {
        code = api_graph(c, pl, out, &type);
    } else if (!strcmp(what, "save")) {
        code = api_save(c, pl, out);
    } else if (!strcmp(what, "load")) {
        code = api_load(c, pl, out);
    } else {
        code = 404;
        snprintf(pl->err, sizeof pl->err, "no such page");
    }
    if (code == 200)
        ret = reply(c, code, type, out->s ? out->s : "", out->n);
    else
        ret = text(c, code, pl->err[0] ? pl->err : "failed");
    free(out->s);
    free(pl);
    return ret;
}

/* The checks made once the headers are in, before any body is read: a 4xx, or 0. */
static enum MHD_Result refuse(struct MHD_Connection *c, const char *method, int *refused)
{
    const char *len = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Content-Length");
    const char *te = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Transfer-Encoding");
    const char *host = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host");
    const char *origin = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Origin");
    char msg[160];
    int nargs = MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, NULL, NULL);
    *refused = 1;
    if ((len && strtoull(len, NULL, 10) > MAX_BODY) || (te && strcmp(te, "identity")))
        return text(c, 413, "request body too large (the editor sends none)");
    if (!ours(host, "")) {
        snprintf(msg, sizeof msg, "the Host must be 127.0.0.1:%u or localhost:%u (got '%.40s')",
                 proto.port, proto.port, host ? host : "");
        return text(c, 403, msg);
    }
    if (origin && !ours(origin, "http://")) {
        snprintf(msg, sizeof msg, "requests from other sites are refused (Origin '%.60s')",
                 origin);
        return text(c, 403, msg);
    }
    if (nargs > MAX_ARGS) {
        snprintf(msg, sizeof msg, "too many query parameters (%d; at most %d)", nargs, MAX_ARGS);
        return text(c, 400, msg);
    }
    if (strcmp(method, "GET"))
        return text(c, 405, "only GET");
    *refused = 0;
    return MHD_YES;
}

static enum MHD_Result handle(void *cls, struct MHD_Connection *c, const char *url,
                              const char *method, const char *version, const char *data,
                              size_t *data_size, void **state)
{
    static int first_call;
    struct tex_str out = {0};
    enum MHD_Result ret;
    int refused;
    (void)cls, (void)version, (void)data;

    if (!*state) { /* the headers: refuse what is not ours before reading a body */
        *state = &first_call;
        ret = refuse(c, method, &refused);
        return refused ? (set_phase(c, SENDING), ret) : MHD_YES;
    }
    if (*data_size) { /* a body (the editor sends none): dropped, bounded */
        const union MHD_ConnectionInfo *ci =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
        struct conn *k = ci ? ci->socket_context : NULL;
        size_t n = *data_size;
        *data_size = 0;
        if (k && (k->seen += n) > MAX_BODY)
            return text(c, 413, "request body too large (the editor sends none)");
        return MHD_YES;
    }
    set_phase(c, SENDING); /* the reply is the last part bounded by the watchdog */
    if (!token_ok(c))
        return text(c, 403, "missing or wrong token: use the URL t_proto printed");
    if (!allowed(c))
        return text(c, 429, "too many requests: slow down");
    set_phase(c, RUNNING);
    ret = route(c, url, &out);
    set_phase(c, SENDING);
    return ret;
}

struct MHD_Daemon *serve(int fd)
{
    pthread_t t;
    if (pthread_create(&t, NULL, watchdog, NULL) != 0)
        return NULL;
    pthread_detach(t);
    /* a thread per connection: a slow pipeline holds its own request only */
    return MHD_start_daemon(MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_THREAD_PER_CONNECTION |
                                MHD_USE_POLL,
                            0, NULL, NULL, handle, NULL, MHD_OPTION_LISTEN_SOCKET, fd,
                            MHD_OPTION_NOTIFY_CONNECTION, notify, NULL,
                            MHD_OPTION_NOTIFY_COMPLETED, completed, NULL,
                            MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)HEAD_SECONDS * 3,
                            MHD_OPTION_CONNECTION_LIMIT, (unsigned)CONN_SLOTS * 2,
                            MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)262144, MHD_OPTION_END);
}
