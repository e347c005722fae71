/* limit.c - the one limit on what a reader takes in ($TEXTURA_MAX_INPUT) */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>

#include "base/error.h"
#include "io/limit.h"

/* $TEXTURA_MAX_INPUT into *max: 1 when it is set, 0 when not (*max the default), -1 when it
 * is not a size. */
static int env_max(size_t *max)
{
    const char *s = getenv("TEXTURA_MAX_INPUT");
    char *end;
    unsigned long long v, unit = 1;

    *max = TEX_INPUT_MAX_DEFAULT;
    if (!s || !*s)
        return 0;
    errno = 0;
    v = strtoull(s, &end, 10);
    switch (*end) {
    case 'k': case 'K': unit = 1ULL << 10, end++; break;
    case 'm': case 'M': unit = 1ULL << 20, end++; break;
    case 'g': case 'G': unit = 1ULL << 30, end++; break;
    }
    if (*s < '0' || *s > '9' || *end || errno || v > SIZE_MAX / unit || v * unit < 1024)
        return tex_usage_error("TEXTURA_MAX_INPUT must be a size from 1K, in bytes or with K, "
                               "M or G (got \"%s\")", s);
    *max = (size_t)(v * unit);
    return 1;
}

int tex_input_max(size_t *max)
{
    return env_max(max) < 0 ? -1 : 0;
}

/* The header's bytes, a map's floats and an eighth more (a chunk that compression made
 * larger), its offset table and chunks' leaders (16 bytes a row at most) and 1 MiB: more than
 * a valid stream of it holds. */
static size_t stream_bound(long long w, long long h, long long nc, size_t head)
{
    unsigned long long f = (unsigned long long)w * h * nc * 4;
    return (size_t)(head + f + f / 8 + 16ULL * (unsigned long long)h + (1ULL << 20));
}

int tex_input_max_rows(long long w, long long h, long long nc, size_t head, size_t *max)
{
    int set = env_max(max);
    if (set == 0)
        *max = stream_bound(w, h, nc, head);
    return set < 0 ? -1 : 0;
}

int tex_input_check_rows(long long w, long long h, long long nc)
{
    size_t max;
    int set = env_max(&max);
    return set < 0 ? -1 : set ? tex_input_check_decoded(w, h, nc) : 0;
}

int tex_input_check_decoded(long long w, long long h, long long nc)
{
    size_t max;
    if (tex_input_max(&max) < 0)
        return -1;
    /* sides and channels are checked first (tex_map_check_size): the product fits */
    if (w > 0 && h > 0 && nc > 0 && (unsigned long long)w * h * nc * 4 > max)
        return tex_error("%lldx%lld with %lld channel%s is %llu bytes as float, over the input "
                         "limit of %zu (TEXTURA_MAX_INPUT)",
                         w, h, nc, nc > 1 ? "s" : "", (unsigned long long)w * h * nc * 4, max);
    return 0;
}
