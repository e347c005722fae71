/* t_brick - a brick wall, with its subregions, as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_brick, argc, argv);
}
