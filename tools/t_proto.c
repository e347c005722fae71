/* t_proto - the prototyping module: an interactive texture editor served on localhost
 *
 * The page (share/textura/proto/index.html) picks a primitive, sets its parameters from
 * the descriptor rows, adds pipeline steps, and shows the map and a standard scene.  Every
 * map is made by the tools themselves, run as a pipeline of processes without a shell
 * (argv arrays of checked words): the command line the page shows is what ran, so it
 * gives the same bytes when run in a shell, every word quoted.  Safe by default:
 * 127.0.0.1 only, Host and Origin its own, a random token on every request (403 without
 * it), saves confined to the working folder (plain names, no symlinks, no overwriting
 * unless asked), files read only from inside it, bounded sizes, bodies, query parameters
 * and times (a request's whole time, not its idle time), 429 on one client's bursts.
 *
 * main is here; the rest is in proto/ (proto.h lists the files). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

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

/* The listening socket on 127.0.0.1:port, never another interface; its port in proto. */
static int listen_on(int port)
{
    struct sockaddr_in sa = {.sin_family = AF_INET, .sin_port = htons((unsigned short)port),
                             .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t n = sizeof sa;
    int one = 1, fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) < 0 ||
        bind(fd, (struct sockaddr *)&sa, sizeof sa) < 0 || listen(fd, 64) < 0 ||
        getsockname(fd, (struct sockaddr *)&sa, &n) < 0) {
        tex_error("cannot listen on 127.0.0.1:%d: %s (-p takes 0..65535, 0 for any free port)",
                  port, strerror(errno));
        tex_die();
    }
    proto.port = ntohs(sa.sin_port);
    return fd;
}

/* The temporary folder's files and the folder itself. */
static void remove_tmpdir(void)
{
    DIR *d = opendir(proto.tmpdir);
    struct dirent *e;
    for (int pass = 0; d && pass < 2; pass++, rewinddir(d)) /* a run may just have ended */
        while ((e = readdir(d)))
            if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
                unlinkat(dirfd(d), e->d_name, 0);
    if (d)
        closedir(d);
    rmdir(proto.tmpdir);
}

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
    free(c.cmdline); /* no map of its own records it */
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
    int fd = listen_on(o.port);
    /* the signals that end it are taken here, in main, by sigwait: every thread (MHD's
     * too) starts with them blocked; the tools get them unblocked (spawn.c) */
    sigset_t ends;
    int sig;
    sigemptyset(&ends);
    sigaddset(&ends, SIGTERM);
    sigaddset(&ends, SIGINT);
    sigaddset(&ends, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &ends, NULL);
    signal(SIGPIPE, SIG_IGN);
    const char *tmp = getenv("TMPDIR") && *getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    snprintf(proto.tmpdir, sizeof proto.tmpdir, "%s/t_proto.XXXXXX", tmp);
    if (strlen(tmp) > sizeof proto.tmpdir - 64 || !mkdtemp(proto.tmpdir)) {
        tex_error("cannot make a temporary folder in %s: %s", tmp, strerror(errno));
        tex_die();
    }
    if (kinds_load() < 0) { /* the operator tools' rows, from the tools beside it */
        remove_tmpdir();
        tex_die();
    }
    if (!(d = serve(fd))) {
        remove_tmpdir();
        tex_error("cannot start the server on 127.0.0.1:%u", proto.port);
        tex_die();
    }
    printf("t_proto: serving %s on http://127.0.0.1:%u/?token=%s\n", proto.dir, proto.port,
           proto.token);
    fflush(stdout);
    while (sigwait(&ends, &sig) != 0)
        ;
    kill_all(); /* no tool writes into the folder after this */
    remove_tmpdir();
    return 0;
}
