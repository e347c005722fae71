/* t_cycloid - two nested cycloid arches, with its subregions, as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_cycloid, argc, argv);
}
