/* t_proto - the prototyping module: an interactive texture editor served on localhost
 *
 * The page (share/textura/proto/index.html) picks a primitive, sets its parameters from
 * the descriptor rows, adds pipeline steps, and shows the map and a standard scene.  Every
 * map is made by the tools themselves, run as a pipeline of processes without a shell
 * (argv arrays of checked words): the command line the page shows is what ran, so it
 * gives the same bytes when run in a shell.  Safe by default: 127.0.0.1 only, a random
 * token on every request (403 without it), saves confined to the working folder (plain
 * names, no symlinks), bounded sizes, bodies and times, 429 on bursts.
 *
 * main is here; the rest is in proto/ (proto.h lists the files). */
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "textura.h"
#include "proto/proto.h"

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

struct proto proto = {.workfd = -1};

static void self_dir(void)
{
    ssize_t n = readlink("/proc/self/exe", proto.bindir, sizeof proto.bindir - 1);
    proto.bindir[n > 0 ? n : 0] = 0;
    char *slash = strrchr(proto.bindir, '/');
    if (slash)
        *slash = 0;
}

int main(int argc, char **argv)
{
    static const struct tex_tool tool = {"t_proto", "", "an interactive texture editor in the "
                                         "browser, served on 127.0.0.1", 0, rows, 0, 0};
    struct tex_common c;
    unsigned char rnd[16];
    struct MHD_Daemon *d;

    static char dir[PATH_MAX];
    tex_cli_parse(&tool, argc, argv, &c, &o);
    self_dir();
    if (!realpath(o.dir, dir) ||
        (proto.workfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC)) < 0)
        tex_usage_die("cannot open the working folder '%s'", o.dir);
    proto.dir = dir; /* the tools run elsewhere: the map's path must be whole */
    static char defs[PATH_MAX];
    proto.defs = o.defs && realpath(o.defs, defs) ? defs : o.defs; /* the same for --defs */
    if (!(proto.procs = tex_procs_new()) ||
        (proto.defs && tex_procs_read(proto.procs, proto.defs) < 0))
        tex_die();
    FILE *ur = fopen("/dev/urandom", "rb");
    if (!ur || fread(rnd, 1, sizeof rnd, ur) != sizeof rnd)
        tex_usage_die("cannot read /dev/urandom for the token");
    fclose(ur);
    for (int i = 0; i < 16; i++)
        sprintf(proto.token + 2 * i, "%02x", rnd[i]);
    snprintf(proto.tmpdir, sizeof proto.tmpdir, "/tmp/t_proto.XXXXXX");
    if (!mkdtemp(proto.tmpdir))
        tex_usage_die("cannot make a temporary folder");
    if (!(d = serve(o.port)))
        tex_usage_die("cannot listen on 127.0.0.1:%d", o.port);
    const union MHD_DaemonInfo *info = MHD_get_daemon_info(d, MHD_DAEMON_INFO_BIND_PORT);
    printf("t_proto: serving %s on http://127.0.0.1:%u/?token=%s\n", proto.dir,
           info ? info->port : (unsigned)o.port, proto.token);
    fflush(stdout);
    for (;;)
        pause(); /* until a signal ends the process */
}
