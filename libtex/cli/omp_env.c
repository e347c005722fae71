/* omp_env.c - a tool's OpenMP threads sleep when idle
 *
 * OpenMP's idle threads spin after every parallel region (libgomp polls 300000 times)
 * unless OMP_WAIT_POLICY is passive, and in a pipeline of tools on busy cores that
 * spinning takes the CPU the other stages need (tests/bench/omp_wait).  libgomp reads
 * the policy through getenv once, as it loads, before any code of a tool runs.  Every
 * tool links this getenv, which the shared libraries (libgomp among them) then call in
 * place of the C library's: it answers from the environment as that one does, and where
 * the environment names no policy (OMP_WAIT_POLICY, GOMP_SPINCOUNT or KMP_BLOCKTIME) it
 * answers OMP_WAIT_POLICY with "passive".  One set, to anything, is kept.
 *
 * Not in libtex: a library must not replace getenv in the programs that use it.  LLVM's
 * libomp reads the environment itself: a tool built with clang runs itself again with
 * the variable set (threads.c).
 */
#include <stdlib.h>
#include <string.h>

#ifndef __clang__ /* gcc's OpenMP is libgomp */
extern char **environ;

static char *lookup(const char *name)
{
    size_t n = strlen(name);
    for (char **e = environ; e && *e; e++)
        if (strncmp(*e, name, n) == 0 && (*e)[n] == '=')
            return *e + n + 1;
    return NULL;
}

/* default visibility: libtex's objects are built hidden, and an interposer must be seen */
__attribute__((visibility("default"))) char *getenv(const char *name)
{
    char *v = lookup(name);
    if (!v && strcmp(name, "OMP_WAIT_POLICY") == 0 && !lookup("GOMP_SPINCOUNT") &&
        !lookup("KMP_BLOCKTIME"))
        v = (char *)"passive";
    return v;
}
#else
typedef int tex_omp_env_unused; /* clang: threads.c's second start instead */
#endif
