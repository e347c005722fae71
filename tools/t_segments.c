/* t_segments - randomly placed, nearly parallel line segments as a texture map */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_segments, argc, argv);
}
