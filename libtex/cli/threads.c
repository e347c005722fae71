/* threads.c - OpenMP's threads for a tool: -j, and idle threads that sleep */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "cli/internal.h"

/* OpenMP's idle threads spin after every parallel region (libgomp polls 300000 times,
 * libomp for 200 ms) unless OMP_WAIT_POLICY is passive, and in a pipeline of tools on
 * busy cores that spinning takes the CPU the other stages need: a five-stage pipeline
 * spends about twice the CPU (tests/bench/omp_wait).  With libgomp, every tool's own getenv
 * answers the policy (omp_env.c).  LLVM's libomp reads the environment itself, as it loads,
 * before any code of a tool runs (a constructor, even one in .preinit_array, comes too late
 * or sees its setenv undone): built with clang, a tool whose environment names no policy
 * runs itself again, once, with OMP_WAIT_POLICY=passive; one set (to anything, e.g.
 * active) is kept.  Only at the start of a tool's main: nothing is open or printed yet.
 * A tool asked for one thread (its last -j or --threads is 1) starts none that could spin
 * and is not run again: a second start costs a whole start-up (doc/performance.md). */
#if defined(_OPENMP) && defined(__clang__)
static int one_thread(char **argv)
{
    const char *last = NULL;
    for (int i = 1; argv[i] && strcmp(argv[i], "--") != 0; i++) {
        const char *a = argv[i];
        if (strncmp(a, "--threads=", 10) == 0)
            last = a + 10;
        else if (strncmp(a, "-j", 2) == 0 && a[2])
            last = a + 2;
        else if ((strcmp(a, "-j") == 0 || strcmp(a, "--threads") == 0) && argv[i + 1])
            last = argv[++i];
    }
    return last && strcmp(last, "1") == 0;
}
#endif

void tex_cli_passive_threads(char **argv)
{
#if defined(_OPENMP) && defined(__clang__)
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT") || getenv("KMP_BLOCKTIME") ||
        one_thread(argv) || setenv("OMP_WAIT_POLICY", "passive", 1) < 0)
        return;
    execv("/proc/self/exe", argv); /* returns only on failure (no /proc): spin, then */
#else
    (void)argv;
#endif
}

void tex_cli_threads(int n)
{
#ifdef _OPENMP
    if (n > 0)
        omp_set_num_threads(n);
#else
    (void)n;
#endif
}
