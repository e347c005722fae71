/* t_bubble - bubbles and Voronoi cells around random points (thesis 5.2.2.5) */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_bubble, argc, argv);
}
