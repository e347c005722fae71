/* t_spectral - fBm by spectral synthesis: the classic forgery of clouds */
#include "prim/spectral.h"
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_spectral, argc, argv);
}
