/* proto.h - what t_proto's files share (t_proto.c keeps main)
 *
 *   catalog.c   the node kinds (primitives, operator tools) and their rows, as JSON
 *   pipeline.c  a request made into a pipeline of tools, every word checked
 *   graph.c     a node graph: checked, run as pipelines over temporary files, exported
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
#define MAX_NODES 32      /* nodes of a graph */
#define MAX_SLOTS 9       /* input slots of a node */
#define MAX_GRAPH 32768   /* bytes of a graph's or a project's JSON */
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

/* catalog.c: the operator kinds (the table), found by name; a kind's row of that name as its
 * tool printed it (NULL if none or not offered); the rows read from each tool at start
 * (-1 with a message); {"primitives": [...], "kinds": [...], "palettes": [...]} */
struct tex_json;
struct kind {
    const char *name, *tool;
    const char *operand, *choices, *operand_help; /* the operand word's row, or NULL;
                                                   * choices NULL: a palette's name */
    const char *slots[MAX_SLOTS];                 /* input slots, in operand order */
    int needs;                                    /* the first slots that must be fed */
    const char *skip;                             /* the tool's rows not offered */
    int sized;                                    /* takes -s SIZE */
    struct tex_json *help;                        /* the tool's --help-json */
};
extern struct kind kinds[];
const struct kind *kind_find(const char *name);
const struct tex_json *kind_row(const struct kind *k, const char *name);
int kinds_load(void);
void api_prims(struct tex_str *b);

/* pipeline.c: words and stages (-1 with pl->err set when full), the pipeline of a
 * request, its command line as a shell reads it, and the standard scene's stage */
const char *word(struct pipeline *pl, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int arg(struct pipeline *pl, const char *w);
int stage(struct pipeline *pl, const char *tool);
int fail(struct pipeline *pl, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
int is_name(const char *s);
int plain_value(struct pipeline *pl, const char *name, const char *v);
const char *inside(struct pipeline *pl, const char *opt, const char *v);
struct tex_param;
int param_arg(struct pipeline *pl, const struct tex_param *row, const char *value);
int build(struct MHD_Connection *c, struct pipeline *pl, int size);
void cmdline(const struct pipeline *pl, struct tex_str *b);
int scene_text(struct pipeline *pl, struct tex_str *s, const char *fn, const char *strength,
               const char *map);
int scene_stage(struct pipeline *pl, const char *fn, const char *strength, const char *map);

/* graph.c: /api/graph (what=preview, scene, sh, compose or apply; the HTTP status, the
 * reply into out, its type into *type), and a graph's export as text for /api/save
 * (form sh, compose or apply) */
unsigned api_graph(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out,
                   const char **type);
int graph_export(struct MHD_Connection *c, struct pipeline *pl, const char *form,
                 const char *map, struct tex_str *out);
/* a project's text checked: JSON, its graph (if any) one that loads: nodes of known kinds,
 * edges into their slots, an output, no cycle (inputs may still be missing) */
int project_check(struct pipeline *pl, const char *text);

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
