/* t_weave - woven cloth, warp and weft in a plain, twill or satin weave, as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_weave, argc, argv);
}
