/* t_noise - the thesis's gradient noise as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_noise, argc, argv);
}
