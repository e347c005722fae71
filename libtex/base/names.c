/* names.c - a table from names to pointers (open addressing on FNV-1a) */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/names.h"

/* The slot of name: where it is, or the empty one where it would go (cap a power of 2). */
static long slot_of(char *const *key, long cap, const char *name)
{
    uint32_t h = 2166136261u;
    for (const char *c = name; *c; c++)
        h = (h ^ (unsigned char)*c) * 16777619u;
    long i = (long)(h & (uint32_t)(cap - 1));
    while (key[i] && strcmp(key[i], name))
        i = (i + 1) & (cap - 1);
    return i;
}

static int grow(struct tex_names *t)
{
    long cap = t->cap ? 2 * t->cap : 64;
    char **key = calloc((size_t)cap, sizeof *key);
    void **val = calloc((size_t)cap, sizeof *val);
    if (!key || !val) {
        free(key), free(val);
        return tex_error("out of memory");
    }
    for (long i = 0; i < t->cap; i++)
        if (t->key[i]) {
            long j = slot_of(key, cap, t->key[i]);
            key[j] = t->key[i];
            val[j] = t->val[i];
        }
    free(t->key), free(t->val);
    t->key = key, t->val = val, t->cap = cap;
    return 0;
}

int tex_names_put(struct tex_names *t, const char *name, void *val)
{
    if (2 * (t->n + 1) > t->cap && grow(t) < 0)
        return -1;
    long i = slot_of(t->key, t->cap, name);
    if (t->key[i])
        return 0;
    if (!(t->key[i] = strdup(name)))
        return tex_error("out of memory");
    t->val[i] = val;
    t->n++;
    return 0;
}

void *tex_names_get(const struct tex_names *t, const char *name)
{
    return t->cap ? t->val[slot_of(t->key, t->cap, name)] : NULL;
}

void tex_names_free(struct tex_names *t)
{
    for (long i = 0; i < t->cap; i++)
        free(t->key[i]);
    free(t->key), free(t->val);
    memset(t, 0, sizeof *t);
}
