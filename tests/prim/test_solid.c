/* test_solid - the solid forms of holes and colour variation (thesis 5.2.2.6-7) and wood:
 * they vary along w, and their 2D maps are slices of them */
#include <math.h>
#include <string.h>

#include "textura.h"
#include "unit.h"

static struct tex_field *field(const char *name, const char *key, const char *val)
{
    struct tex_field *f = tex_field_new(tex_primitive_find(name));
    if (!f || (key && tex_field_set(f, key, val) < 0) || tex_field_init(f, 0, 0) < 0) {
        printf("# %s: %s\n", name, tex_errmsg());
        tex_field_free(f);
        return NULL;
    }
    return f;
}

/* The largest change of f's solid field along w over a grid of (u, v), and the largest
 * difference between the slice w = ws (v = ws for colour variation's height) and the map. */
static void along_w(const struct tex_field *f, int slice_is_v, double ws, double *vary,
                    double *slice)
{
    *vary = *slice = 0;
    for (int i = 0; i < 32; i++)
        for (int j = 0; j < 32; j++) {
            double u = (i + 0.5) / 32, v = (j + 0.5) / 32, w[2] = {0.1, 0.6}, uu[2] = {u, u},
                   vv[2] = {v, v};
            float a[6], m[3], s[3];
            f->prim->eval3(f, 2, uu, vv, w, a);
            *vary = fmax(*vary, fabs(a[0] - a[f->nc]));
            /* the map's (u, v) is the field's (u, w) for colour variation, (u, v) otherwise */
            double su = u, sv = slice_is_v ? ws : v, sw = slice_is_v ? v : ws;
            f->prim->eval2(f, 1, &u, &v, m);
            f->prim->eval3(f, 1, &su, &sv, &sw, s);
            *slice = fmax(*slice, fabs(m[0] - s[0]));
        }
}

int main(void)
{
    double vary, slice;
    struct tex_field *f = field("holes", "grid_cells", "6");
    CHECK(f && (f->prim->flags & TEX_PRIM_3D), "holes has a solid form");
    if (f) {
        along_w(f, 0, 0.5, &vary, &slice);
        CHECKF(vary > 0.3, "solid holes vary along w (by %.3f)", vary);
        tex_field_free(f);
    }
    f = field("colorvar", "noise", "0.5");
    CHECK(f && (f->prim->flags & TEX_PRIM_3D), "colour variation has a solid form");
    if (f) {
        along_w(f, 1, 0, &vary, &slice);
        CHECKF(vary > 0.1, "solid colour variation varies along w (by %.3f)", vary);
        CHECKF(slice < 1e-6, "colour variation's slice y = 0 is its map at (x, z) (off by %g)",
               slice);
        tex_field_free(f);
    }
    f = field("wood", "tilt", "30");
    if (f) {
        along_w(f, 0, 0.5, &vary, &slice);
        CHECKF(vary > 0.1, "tilted wood varies along w (by %.3f)", vary);
        CHECKF(slice == 0, "wood's map is its slice w = 1/2 (off by %g)", slice);
        tex_field_free(f);
    }
    /* a point's value does not depend on how many points come with it */
    f = field("holes", NULL, NULL);
    if (f) {
        double u[5] = {0.1, 0.2, 0.3, 0.4, 0.5}, v[5] = {0.5, 0.4, 0.3, 0.2, 0.1},
               w[5] = {0.9, 0.7, 0.5, 0.3, 0.1};
        float all[5], one;
        f->prim->eval3(f, 5, u, v, w, all);
        f->prim->eval3(f, 1, u + 3, v + 3, w + 3, &one);
        CHECK(memcmp(&one, all + 3, sizeof one) == 0, "solid holes: the same value alone or in a row");
        tex_field_free(f);
    }
    return unit_done();
}
