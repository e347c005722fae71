/* proto.h - what t_proto's files share (t_proto.c keeps main)
 *
 *   catalog.c   the primitives and their rows, as JSON for the page
 *   pipeline.c  a request made into a pipeline of tools, every word checked
 *   spawn.c     the pipeline run, its stages spawned without a shell
 *   save.c      files saved into the folder it serves, and projects loaded
 *   http.c      libmicrohttpd: the token, the rate limit, the routes and replies
 */
#ifndef PROTO_H
#define PROTO_H

#include <limits.h>
#include <stddef.h>

#include <microhttpd.h>

#include "io/strbuf.h"

#define MAX_BODY 65536    /* bytes of a request body */
#define MAX_SIDE 4096     /* largest map the editor makes */
#define MAX_WORDS 48      /* argv words of one stage */
#define MAX_STEPS 8       /* pipeline steps after the primitive */
#define MAX_STAGES (1 + MAX_STEPS)
#define MAX_ARGS 64       /* query parameters of one request */
#define RUN_SECONDS 30    /* a request's time limit for its pipelines */
#define MAX_RUNS 8        /* pipelines running at once; more wait their turn */
#define HEAD_SECONDS 5    /* a request's time to arrive whole (and a kept connection's idle time) */
#define CONN_SLOTS 48     /* connections held at once: a new one drops the oldest still arriving */
#define BURST 60          /* requests allowed at once ... */
#define RATE 40           /* ... refilled per second */

/* What main sets up before serving. */
struct proto {
    const char *dir;         /* the working folder, whole: saves go there */
    const char *defs;        /* composed primitives (t_expr --defs), or NULL */
    int workfd;              /* the working folder, open */
    char token[33];          /* every request carries it */
    char bindir[PATH_MAX];   /* the tools: beside t_proto */
    char tmpdir[PATH_MAX];   /* the tools run there: in $TMPDIR, else /tmp */
    unsigned port;           /* the port it listens on: Host and Origin must name it */
    struct tex_procs *procs; /* built-in and composed primitives */
};
extern struct proto proto;

struct stage {
    const char *argv[MAX_WORDS + 1];
    int n;
};

struct pipeline {
    struct stage st[MAX_STAGES];
    int n;
    char words[MAX_STAGES * MAX_WORDS * 128]; /* the words, one after the other */
    size_t used;
    int nsteps;
    int overwrite, exists; /* a save may replace a file; it did not, the file exists */
    long end; /* the time (time(NULL)) every run of the request ends by, or 0 */
    char err[512];
};

/* catalog.c: {"primitives": [...], "palettes": "..."} */
void api_prims(struct tex_str *b);

/* pipeline.c: words and stages (-1 with pl->err set when full), the pipeline of a
 * request, its command line as a shell reads it, and the standard scene's stage */
const char *word(struct pipeline *pl, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int arg(struct pipeline *pl, const char *w);
int stage(struct pipeline *pl, const char *tool);
int fail(struct pipeline *pl, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int is_name(const char *s);
int build(struct MHD_Connection *c, struct pipeline *pl, int size);
void cmdline(const struct pipeline *pl, struct tex_str *b);
int scene_stage(struct pipeline *pl, const char *fn, const char *strength, const char *map);

/* spawn.c: the worst exit status (0 ok, 1 runtime, 2 usage), the output in out; and every
 * running pipeline killed (on a signal, before the temporary folder goes) */
int run(struct pipeline *pl, struct tex_str *out);
void kill_all(void);

/* save.c */
extern const char *const map_exts[];
int is_saved_palette(const char *name);
int save_name(struct pipeline *pl, const char *name, const char *const *exts);
int to_file(struct pipeline *pl, const char *name);
unsigned api_save(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out);
unsigned api_load(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out);

/* http.c: the size asked for (def if none; -1 with pl->err), and the server on
 * socket fd (listening on 127.0.0.1), NULL if it cannot start */
int get_size(struct MHD_Connection *c, struct pipeline *pl, int def);
struct MHD_Daemon *serve(int fd);

#endif
