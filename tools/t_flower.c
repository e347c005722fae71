/* t_flower - a flower, the rose curve, with its subregions, as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_flower, argc, argv);
}
