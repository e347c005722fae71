/* t_wood - wood rings as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_wood, argc, argv);
}
