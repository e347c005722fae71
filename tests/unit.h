/* unit.h - the smallest test harness: TAP-like lines for tests/run
 *
 *   CHECK(x == 1, "x is one");
 *   CHECKF(fabs(a - b) < 1e-6, "a matches b (a=%g b=%g)", a, b);
 *   unit_top_path("patterns/materials.txt", path, sizeof path);   // a file of the tree
 *   return unit_done();
 */
#ifndef UNIT_H
#define UNIT_H

#include <stdio.h>
#include <stdlib.h>

static int unit_failures;

#define CHECKF(cond, ...)                                                                         \
    do {                                                                                           \
        if (cond) {                                                                                \
            printf("ok - ");                                                                       \
        } else {                                                                                   \
            printf("not ok - %s:%d: ", __FILE__, __LINE__);                                        \
            unit_failures++;                                                                       \
        }                                                                                          \
        printf(__VA_ARGS__);                                                                       \
        putchar('\n');                                                                             \
    } while (0)
#define CHECK(cond, name) CHECKF(cond, "%s", name)

/* TEXTURA_TOP/rel, a file of the source tree (TEXTURA_TOP unset: the current folder) */
static inline const char *unit_top_path(const char *rel, char *path, size_t n)
{
    const char *top = getenv("TEXTURA_TOP");
    snprintf(path, n, "%s/%s", top ? top : ".", rel);
    return path;
}

static inline int unit_done(void)
{
    fflush(stdout);
    return unit_failures ? 1 : 0;
}

#endif
