/* t_fractal - fBm, multifractals, midpoint displacement, Mandelbrot, Julia and Koch maps */
#include "textura.h"

int main(int argc, char **argv)
{
    return tex_generate_main(&tex_prim_fractal, argc, argv);
}
