/* t_perturb - perturbed regular pattern (marble veins) */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_perturb, argc, argv);
}
