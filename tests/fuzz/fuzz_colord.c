/* fuzz_colord.c - libFuzzer target: the CIE curve files of colord-data (IT8
 * text, render/spectrum.c), read through a memory file for each of 3 sets.
 * Any input must read or fail with a message; a curve read is finite. */
#define _GNU_SOURCE
#include <math.h>
#include <stdlib.h>

#include "memfile.h"

static void read_path(const char *path)
{
    for (int set = 0; set < 3; set++) {
        tex_curve c;
        if (tex_curve_read_colord(&c, path, set) == 0)
            for (int i = 0; i < TEX_CURVE_N; i++)
                if (!isfinite(c.v[i]))
                    abort();
    }
}
