/* planes.c - a scanline's channel runs and a map's pixels, moved from one to the other */
#include <string.h>

#include "base/simd.h"
#include "io/planes.h"
#include "io/x86/planes_x86.h"

void tex_planes_join(float *px, const float *const *plane, int nc, size_t w)
{
    size_t x = 0;
    if (nc == 1) {
        memcpy(px, plane[0], w * sizeof *px);
        return;
    }
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2 && nc >= 3)
        x = tex_planes_join_avx2(px, plane, nc, w);
#endif
    for (; x < w; x++)
        for (int k = 0; k < nc; k++)
            px[x * nc + k] = plane[k][x];
}

void tex_planes_split(float *const *plane, const float *px, int nc, size_t w)
{
    size_t x = 0;
    if (nc == 1) {
        memcpy(plane[0], px, w * sizeof *px);
        return;
    }
#ifdef TEX_X86
    if (tex_simd_level() >= TEX_SIMD_AVX2 && nc >= 3)
        x = tex_planes_split_avx2(plane, px, nc, w);
#endif
    for (; x < w; x++)
        for (int k = 0; k < nc; k++)
            plane[k][x] = px[x * nc + k];
}
