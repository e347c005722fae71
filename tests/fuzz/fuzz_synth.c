/* fuzz_synth.c - libFuzzer target: t_synth's input, a sample of any values.  The first
 * bytes choose the sample's size (2..11 a side), channels (1..4) and the synthesis's
 * options (neighbourhood 3 or 5, 1 or 2 levels, k 1..4, tile, quilting or a search of every
 * position); the rest are the samples' float bits, repeated to fill it, so that huge
 * values (1e20, 3e38, whose distances overflow to inf and NaN: issue 59), denormals, NaN
 * and infinities come.  The synthesis must make the map or refuse it with a message; every
 * value it makes is one of the sample's (it copies positions). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

static int cmpf(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 8)
        return 0;
    int w = 2 + data[0] % 10, h = 2 + data[1] % 10, nc = 1 + data[2] % 4;
    struct tex_synth_opts o = TEX_SYNTH_DEFAULTS;
    o.neighbourhood = data[3] & 1 ? 5 : 3;
    o.levels = 1 + data[3] / 2 % 2;
    o.k = 1 + data[4] % 4;
    o.passes = 1;
    o.tile = data[4] >> 7;
    o.search = data[5] & 1 ? TEX_SYNTH_EXHAUSTIVE : TEX_SYNTH_COHERENT;
    o.seed = data[6];
    data += 8, size -= 8;
    tex_map *s = tex_map_new(w, h, nc);
    if (!s)
        abort();
    size_t n = tex_map_samples(s);
    for (size_t i = 0; size >= 4 && i < n; i++)
        memcpy(&s->px[i], data + i * 4 % (size / 4 * 4), 4);
    tex_map *m = tex_synth(s, 8, 8, &o, NULL, NULL);
    if (m) {
        float *v = malloc(sizeof *v * n);
        if (!v || m->nc != nc || m->w != 8 || m->h != 8)
            abort();
        memcpy(v, s->px, sizeof *v * n);
        qsort(v, n, sizeof *v, cmpf);
        for (size_t i = 0; i < tex_map_samples(m); i++) /* finite: a sample with NaN is refused */
            if (!bsearch(&m->px[i], v, n, sizeof *v, cmpf))
                abort();
        free(v);
        tex_map_free(m);
    }
    tex_map_free(s);
    return 0;
}
