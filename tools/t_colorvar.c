/* t_colorvar - Gardner colour variation */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_colorvar, argc, argv);
}
