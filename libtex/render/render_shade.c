/* render_shade.c - Whitted-Phong and the table of shading models */
#include <string.h>

#include "render/render.h"
#include "render/render_shade.h"
#include "render/render_ct.h"
#include "render/anisotropic.h"

static void phong_direct(const struct tex_material *m, const double N[3], const double V[3],
                         const double L[3], const tex_colour *E, int n, tex_colour *out)
{
    tex_phong_direct(m, N, V, L, E, n, out);
}

static void phong_weights(const struct tex_material *m, double cosi, int n, tex_colour *kr,
                          tex_colour *kt)
{
    (void)cosi;
    tex_colour_set(kr, n, (float)m->kr);
    tex_colour_set(kt, n, (float)m->kt);
}

const struct tex_shading_model tex_shading_phong = {"phong", phong_direct, phong_weights};

static const struct tex_shading_model *const models[] = {&tex_shading_phong,
                                                         &tex_shading_cook_torrance,
                                                         &tex_shading_ward,
                                                         &tex_shading_ashikhmin_shirley, NULL};

const struct tex_shading_model *tex_shading_find(const char *name)
{
    for (int i = 0; models[i]; i++)
        if (!strcmp(models[i]->name, name))
            return models[i];
    return NULL;
}
