/* fuzz_kdtree.c - libFuzzer target: t_bubble's nearest-point searches on point sets as
 * users give them, many coincident (10^4 copies of one point hung the kd-tree: issue 59).
 * The first bytes choose the dimension, the value (bubble, F1, F2, F2-F1, cell), radii
 * and tiling; the rest are points, coordinates of 0..15 sixteenths (so that points
 * coincide and align) and a radius each.  The kd-tree's map must be brute force's, bit
 * for bit, as t_bubble(1) says every search gives the same map. */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "textura.h"

static const char *const values[] = {"bubble", "f1", "f2", "f2-f1", "cell"};

/* The 8 x 6 map of the points file path by search, or NULL */
static tex_map *bubbles(const char *path, const uint8_t *opt, const char *search)
{
    struct tex_field *f = tex_field_new(&tex_prim_bubble);
    tex_map *m = NULL;
    if (f && tex_field_set(f, "points", path) == 0 &&
        tex_field_set(f, "dimension", opt[0] & 1 ? "3" : "2") == 0 &&
        tex_field_set(f, "value", values[opt[1] % 5]) == 0 &&
        tex_field_set(f, "search", search) == 0 &&
        (!(opt[0] & 2) || tex_field_set(f, "tile", "") == 0) && tex_field_init(f, 8, 6) == 0)
        m = tex_field_sample(f);
    tex_field_free(f);
    return m;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 3 || size > 1024)
        return 0;
    int dim = data[0] & 1 ? 3 : 2, radii = data[0] & 4;
    const uint8_t *opt = data, *p = data + 2, *end = data + size;
    FILE *fp;
    int fd = memfd_create("fuzz", 0);
    if (fd < 0 || !(fp = fdopen(dup(fd), "w")))
        abort();
    for (; p + dim <= end; p += dim + (radii != 0)) {
        for (int j = 0; j < dim; j++)
            fprintf(fp, "%s%g", j ? " " : "", (p[j] & 15) / 16.0);
        if (radii && p + dim < end)
            fprintf(fp, " %g", 0.25 + (p[dim] & 7) / 4.0);
        fputc('\n', fp);
    }
    fclose(fp);
    char path[64];
    snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    tex_map *k = bubbles(path, opt, "kdtree"), *b = bubbles(path, opt, "brute");
    if (!k != !b || (k && (k->w != b->w || k->h != b->h || k->nc != b->nc ||
                           memcmp(k->px, b->px, tex_map_samples(k) * sizeof *k->px))))
        abort();
    tex_map_free(k);
    tex_map_free(b);
    close(fd);
    return 0;
}
