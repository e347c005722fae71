/* t_d_noise - the gradient of noise, or a normal map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_d_noise, argc, argv);
}
