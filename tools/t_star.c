/* t_star - a star, with its subregions, as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_star, argc, argv);
}
