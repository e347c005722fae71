/* test_cli_options.c - options parsed from parameter rows, as users type them: defaults,
 * values, operands before and after options, range and usage messages, deprecated names,
 * and --help and --help-mdoc made from the rows */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/json.h"
#include "textura.h"
#include "unit.h"

static const struct tex_primitive *prim;
static struct tex_tool tool;
static char **args;
static struct tex_common common;
static void *opts;

/* Parse as t_NAME parses: the tool a generator's main makes of its primitive (generate.c). */
static void use(const struct tex_primitive *p, const char *name)
{
    prim = p;
    tool = (struct tex_tool){name, "", p->summary,
                             TEX_OPT_OUTPUT | TEX_OPT_SIZE | TEX_OPT_SEED | TEX_OPT_WINDOW,
                             p->params, 0, 0};
}

static int parse(char **argv)
{
    int argc = 0;
    while (argv[argc])
        argc++;
    free(opts);
    free(common.cmdline); /* tex_cli_parse clears common */
    opts = calloc(1, prim->params_size + 64);
    return tex_cli_parse(&tool, argc, argv, &common, opts);
}

static double value(const char *name)
{
    const struct tex_param *r = tex_param_find(tool.params, name);
    const char *at = (const char *)opts + (r ? r->off : 0);
    return !r ? -1e300 : r->type == TEX_P_INT ? *(const int *)at : *(const double *)at;
}

/* What the child of run wrote on standard output and standard error. */
static char out[65536], err[4096];

/* The first line of what the child wrote on standard error, for the test's line. */
static const char *msg(void)
{
    static char line[256];
    snprintf(line, sizeof line, "%.*s", (int)strcspn(err, "\n"), err);
    return line;
}

/* Parse argv in a child process, as a tool would: its exit status. */
static int run(char **argv)
{
    char fo[] = "/tmp/test_cli_out.XXXXXX", fe[] = "/tmp/test_cli_err.XXXXXX";
    int o = mkstemp(fo), e = mkstemp(fe), status = -1;
    pid_t pid;

    fflush(stdout);
    if (o < 0 || e < 0 || (pid = fork()) < 0)
        return -1;
    if (pid == 0) {
        dup2(o, 1);
        dup2(e, 2);
        parse(argv);
        exit(0);
    }
    waitpid(pid, &status, 0);
    memset(out, 0, sizeof out);
    memset(err, 0, sizeof err);
    if (pread(o, out, sizeof out - 1, 0) < 0 || pread(e, err, sizeof err - 1, 0) < 0)
        status = -1;
    close(o);
    close(e);
    unlink(fo);
    unlink(fe);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

#define ARGS(...) (args = (char *[]){__VA_ARGS__, NULL})

/* argv ends the process with status, its standard error the message. */
static void expect(char **argv, int status, const char *message, const char *what)
{
    CHECKF(run(argv) == status && !strcmp(err, message), "%s (%s)", what, msg());
}

static void test_values(void)
{
    const struct tex_param *oct;
    int i;

    use(&tex_prim_turbulence, "t_turbulence");
    oct = tex_param_find(tool.params, "octaves");
    i = parse(ARGS("t_turbulence"));
    CHECKF(i == 1 && common.w == 256 && common.h == 256 && common.seed == 1 &&
               !common.output && oct && value("octaves") == oct->def,
           "no options: -s 256, seed 1, standard output, --octaves its row's default (%g)",
           oct ? oct->def : -1);
    i = parse(ARGS("t_turbulence", "-s", "64x32", "--octaves", "7", "-j", "1", "--seed=9",
                   "-q", "-o", "a b.exr"));
    CHECK(i == 11 && common.w == 64 && common.h == 32 && value("octaves") == 7 &&
              common.seed == 9 && common.threads == 1 && common.quiet &&
              !strcmp(common.output, "a b.exr"),
          "options set their fields, joined (--seed=9) or not");
    CHECKF(!strcmp(common.cmdline, "t_turbulence -s 64x32 --octaves 7 --seed=9 -o 'a b.exr'"),
           "the history's command line leaves out -j and -q and quotes for a shell (%s)",
           common.cmdline);
    CHECK(tex_cli_given("octaves") && tex_cli_given("seed") && !tex_cli_given("frequency"),
          "tex_cli_given tells which options were named");
}

static void test_operands(void)
{
    static const struct tex_param rows[] = {
        TEX_REAL(struct { double a; }, a, 'a', 0.1, -100, 100, "A", "amount"), {0}};
    prim = &tex_prim_turbulence; /* its params_size is room enough */
    tool = (struct tex_tool){"t_two", "MAP BY", "two maps", TEX_OPT_OUTPUT, rows, 2, 2};
    for (int posix = 0; posix <= 1; posix++) {
        int i;
        if (posix)
            setenv("POSIXLY_CORRECT", "1", 1);
        i = parse(ARGS("t_two", "m.exr", "by.exr", "-a", "0.5", "-o", "x.exr"));
        CHECKF(i == 5 && !strcmp(args[5], "m.exr") && !strcmp(args[6], "by.exr") &&
                   value("a") == 0.5 && !strcmp(common.output, "x.exr"),
               "options after the operands are taken, the operands last in order%s",
               posix ? ", under POSIXLY_CORRECT too" : "");
        CHECKF(!strcmp(common.cmdline, "t_two m.exr by.exr -a 0.5 -o x.exr"),
               "the history keeps the order typed (%s)", common.cmdline);
        unsetenv("POSIXLY_CORRECT");
    }
    /* static: the parser keeps its copy of "-0.5" in argv for the life of the program */
    static char *neg[] = {"t_two", "-0.5", "-a", "-2", "--", "-x.exr", NULL};
    int i = parse(args = neg);
    CHECK(i == 4 && !strcmp(args[4], "-0.5") && !strcmp(args[5], "-x.exr") && value("a") == -2,
          "a negative number is an operand unless an option takes it; \"--\" ends the options");
    expect(ARGS("t_two", "a", "b", "c"), 2,
           "t_two: error: unexpected operand 'c' (usage: t_two [options] MAP BY)\n",
           "a third operand is refused by name");
    expect(ARGS("t_two", "a", "-a", "1"), 2,
           "t_two: error: missing operand (usage: t_two [options] MAP BY)\n",
           "a missing operand is a usage error");
}

static void test_messages(void)
{
    use(&tex_prim_turbulence, "t_turbulence");
    expect(ARGS("t_turbulence", "--octaves", "40"), 2,
           "t_turbulence: error: --octaves must be 1..30 (got '40')\n",
           "a value out of range: the row's name and range, exit 2");
    CHECKF(run(ARGS("t_turbulence", "-n", "0")) == 2 && strstr(err, "--octaves must be 1..30"),
           "the short letter's message names the long option (%s)", msg());
    expect(ARGS("t_turbulence", "--oct", "7"), 2,
           "t_turbulence: error: unknown option --oct: options are written "
           "whole (--octaves?)\n",
           "an abbreviation is refused with the whole name");
    CHECKF(run(ARGS("t_turbulence", "-s", "0x5")) == 2 && strstr(err, "-s must be N or WxH"),
           "a bad size is a usage error (%s)", msg());
    CHECKF(run(ARGS("t_turbulence", "-o", "x.exr", "--format", "png")) == 2 &&
               strstr(err, "--format png contradicts the extension of x.exr"),
           "--format against -o's extension is refused (%s)", msg());
    expect(ARGS("t_turbulence", "--seed"), 2,
           "t_turbulence: error: missing value for --seed (see t_turbulence --help)\n",
           "a missing value");
    use(&tex_prim_fractal, "t_fractal");
    expect(ARGS("t_fractal", "--mode", "fbm", "--c", "0.3"), 2,
           "t_fractal: error: --c applies to --mode julia only\n",
           "an option of another mode is refused");
}

static void test_deprecated(void)
{
    use(&tex_prim_ring, "t_ring");
    expect(ARGS("t_ring", "--width", "0.2"), 0,
           "t_ring: warning: --width is deprecated and will be removed: "
           "write --ring-width\n",
           "an old name is taken with a warning naming the new one");
    CHECKF(run(ARGS("t_ring", "-q", "-d", "0.2")) == 0 && !err[0], "-q silences it (%s)", msg());
    setenv("TEXTURA_DEPRECATED", "error", 1);
    expect(ARGS("t_ring", "--width", "0.2"), 2,
           "t_ring: error: --width is deprecated: write --ring-width "
           "(TEXTURA_DEPRECATED=error)\n",
           "TEXTURA_DEPRECATED=error refuses it");
    unsetenv("TEXTURA_DEPRECATED");
    parse(ARGS("t_ring", "-q", "--width", "0.2"));
    CHECK(value("ring_width") == 0.2, "the old name sets the row's value");
}

/* The line of --help that documents row p, or NULL. */
static const char *help_line(const struct tex_param *p)
{
    char opt[64], want[80];
    tex_param_option(p, opt, sizeof opt);
    snprintf(want, sizeof want, "%s%s", opt, p->alias ? "," : " ");
    for (const char *l = out; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL)
        if (!strncmp(l + 6, want, strlen(want)) && (!p->key || l[3] == p->key))
            return l;
    return NULL;
}

static void test_help(void)
{
    char rng[128], def[64], line[512];
    int rows = 0, found = 0, ranged = 0;

    use(&tex_prim_turbulence, "t_turbulence");
    CHECK(run(ARGS("t_turbulence", "--help")) == 0 && !strncmp(out, "usage: t_turbulence "
          "[options]\n", 29) && strstr(out, prim->summary), "--help: the usage line and summary");
    for (const struct tex_param *p = prim->params; p->name; p++, rows++) {
        const char *l = help_line(p);
        found += l != NULL;
        if (l && (p->type == TEX_P_INT || p->type == TEX_P_REAL)) {
            snprintf(line, sizeof line, "[%s] (default %s)\n", tex_param_range(p, rng, sizeof rng),
                     tex_param_default(p, def, sizeof def));
            ranged += strstr(l, line) == strchr(l, '\n') - strlen(line) + 1;
        }
    }
    CHECKF(rows > 3 && found == rows, "every row has its line (%d of %d)", found, rows);
    CHECKF(ranged > 2, "numbers end in their row's range and default (%d rows)", ranged);
    CHECK(strstr(out, "  -o, --output FILE ") && strstr(out, "  -S, --seed N ") &&
              strstr(out, "  -h, --help                   show this help\n"),
          "the common options follow the tool's");
    CHECK(run(ARGS("t_turbulence", "--help-mdoc")) == 0 && !strncmp(out, ".Bl -tag -width Ds\n",
          19) && !strcmp(out + strlen(out) - 4, ".El\n"), "--help-mdoc is one tag list");
    const struct tex_param *oct = tex_param_find(prim->params, "octaves");
    snprintf(line, sizeof line, ".It Fl %c , Fl -octaves Ar %s\n%c%s, %s; default %s.\n",
             oct->key, oct->meta, oct->help[0] - 32, oct->help + 1,
             tex_param_range(oct, rng, sizeof rng), tex_param_default(oct, def, sizeof def));
    CHECKF(strstr(out, line) != NULL, "--octaves in mdoc: %.*s", (int)strcspn(line, "\n"),
           line);
    {   /* --help-json: the tool's own rows, as editors read them */
        char err[128];
        struct tex_json *j = run(ARGS("t_turbulence", "--help-json")) == 0
                                 ? tex_json_parse(out, strlen(out), err, sizeof err) : NULL;
        const struct tex_json *ps = tex_json_get(j, "params"), *o = NULL;
        int n = 0;
        for (const struct tex_param *p = prim->params; p->name; p++)
            n++;
        for (int i = 0; ps && i < ps->n; i++)
            if (!strcmp(tex_json_get(&ps->item[i], "name")->str, "octaves"))
                o = &ps->item[i];
        CHECK(j && !strcmp(tex_json_get(j, "tool")->str, "t_turbulence") && ps && ps->n == n &&
                  o && !strcmp(tex_json_get(o, "default")->str, def) &&
                  !strcmp(tex_json_get(o, "help")->str, oct->help),
              "--help-json is JSON: the tool and its own rows, each with its default and help");
        tex_json_free(j);
    }
    CHECK(run(ARGS("t_turbulence", "-V")) == 0 && !strncmp(out, "t_turbulence (Textura) ", 23),
          "-V names the tool and Textura");
}

int main(void)
{
    test_values();
    test_operands();
    test_messages();
    test_deprecated();
    test_help();
    free(opts);
    free(common.cmdline);
    return unit_done();
}
