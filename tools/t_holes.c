/* t_holes - the thesis hole model */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_holes, argc, argv);
}
