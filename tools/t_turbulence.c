/* t_turbulence - Perlin turbulence as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_turbulence, argc, argv);
}
