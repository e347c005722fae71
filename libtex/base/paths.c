/* paths.c - the install folders, resolved relative to libtex's own file */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/paths.h"

#ifndef TEX_PREFIX
#define TEX_PREFIX "/usr/local"
#endif
#ifndef TEX_LIBDIR
#define TEX_LIBDIR TEX_PREFIX "/lib"
#endif
#ifndef TEX_DATADIR
#define TEX_DATADIR TEX_PREFIX "/share/textura"
#endif

static char dirs[2][PATH_MAX + 64];
static pthread_once_t once = PTHREAD_ONCE_INIT;

/* The part of a build-time folder below the prefix ("/lib"), or NULL. */
static const char *below_prefix(const char *dir)
{
    size_t n = strlen(TEX_PREFIX);
    if (strncmp(dir, TEX_PREFIX, n) == 0 && dir[n] == '/')
        return dir + n;
    return NULL;
}

/* dir without its suffix tail ("/x/lib" less "/lib" is "/x"); 0 if it doesn't end so. */
static int strip_tail(char *dir, const char *tail)
{
    size_t n = strlen(dir), t = strlen(tail);
    if (t > n || strcmp(dir + n - t, tail) != 0)
        return 0;
    dir[n - t] = '\0';
    return 1;
}

static void resolve(void)
{
    const char *built[2] = {TEX_LIBDIR, TEX_DATADIR};
    char obj[PATH_MAX], prefix[PATH_MAX];
    const char *base, *lib_tail = below_prefix(TEX_LIBDIR);
    Dl_info di;
    int found = 0;

    for (int d = 0; d < 2; d++)
        snprintf(dirs[d], PATH_MAX, "%s", built[d]);
    if (!dladdr((void *)resolve, &di) || !di.dli_fname)
        return;
    base = strrchr(di.dli_fname, '/');
    base = base ? base + 1 : di.dli_fname;
    if (strncmp(base, "libtex.so", 9) == 0) {
        if (realpath(di.dli_fname, obj) && lib_tail) {
            *strrchr(obj, '/') = '\0';
            found = strip_tail(obj, lib_tail);
        }
    } else if (realpath("/proc/self/exe", obj)) {
        *strrchr(obj, '/') = '\0';
        found = strip_tail(obj, "/bin");
    }
    if (!found)
        return;
    snprintf(prefix, sizeof prefix, "%s", obj);
    for (int d = 0; d < 2; d++) {
        const char *tail = below_prefix(built[d]);
        char cand[PATH_MAX + 64];
        struct stat st;
        if (!tail || (size_t)snprintf(cand, sizeof cand, "%s%s", prefix, tail) >= PATH_MAX)
            continue;
        if (stat(cand, &st) == 0 && S_ISDIR(st.st_mode))
            memcpy(dirs[d], cand, sizeof dirs[d]);
    }
}

const char *tex_install_dir(enum tex_dir d)
{
    pthread_once(&once, resolve);
    return dirs[d == TEX_DIR_DATA];
}
