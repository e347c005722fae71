/* fuzz_points.c - libFuzzer target: points files (t_bubble --points,
 * textura-points(5)), read through a memory file in 2D and in 3D.
 * Any input must read or fail with a message; points read are finite and
 * their radii positive. */
#define _GNU_SOURCE
#include <math.h>
#include <stdlib.h>

#include "memfile.h"

static void read_path(const char *path)
{
    for (int dim = 2; dim <= 3; dim++) {
        tex_points ps;
        if (tex_points_read(&ps, path, dim) == 0) {
            if (ps.n < 1 || ps.dim != dim)
                abort();
            for (long i = 0; i < ps.n * dim; i++)
                if (!isfinite(ps.x[i]) || (ps.axes && !(ps.axes[i] > 0)))
                    abort();
        }
        tex_points_free(&ps);
    }
}
