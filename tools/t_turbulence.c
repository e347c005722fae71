/* t_turbulence - turbulence */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_turbulence, argc, argv);
}
