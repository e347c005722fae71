/* simd.c - the SIMD level, found once */

#include <stdlib.h>
#include <string.h>

#include "base/simd.h"

const char *tex_simd_name(int level)
{
    return level == TEX_SIMD_AVX512 ? "avx512" : level == TEX_SIMD_AVX2 ? "avx2" : "scalar";
}

/* The CPU's best level, capped by TEXTURA_SIMD (scalar or avx2).  At this level with VBMI
 * (tex_simd_vbmi) the point kernel takes sixteen points at a time and its hashes from byte
 * permutes, faster than the eight-lane AVX2 kernel. */
enum { VBMI = 4 }; /* beside the level in simd_detect's answer */

static int simd_detect(void)
{
    int best = TEX_SIMD_SCALAR, vbmi = 0;
    const char *e = getenv("TEXTURA_SIMD");
#ifdef TEX_X86
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2"))
        best = TEX_SIMD_AVX2;
    if (best == TEX_SIMD_AVX2 && __builtin_cpu_supports("avx512f"))
        best = TEX_SIMD_AVX512;
    vbmi = __builtin_cpu_supports("avx512vbmi") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512bw");
#endif
    if (e && strcmp(e, "scalar") == 0)
        best = TEX_SIMD_SCALAR;
    else if (e && strcmp(e, "avx2") == 0 && best > TEX_SIMD_AVX2)
        best = TEX_SIMD_AVX2;
    return best | (vbmi ? VBMI : 0);
}

/* simd_detect's answer, found once */
static int detected(void)
{
    static int d = -1;
    int v = __atomic_load_n(&d, __ATOMIC_RELAXED);
    if (v < 0) {
        v = simd_detect();
        __atomic_store_n(&d, v, __ATOMIC_RELAXED);
    }
    return v;
}

static int limit = TEX_SIMD_AVX512;

int tex_simd_level(void)
{
    int l = detected() & ~VBMI, m = __atomic_load_n(&limit, __ATOMIC_RELAXED);
    return l < m ? l : m;
}

void tex_simd_limit(int level)
{
    __atomic_store_n(&limit, level, __ATOMIC_RELAXED);
}

int tex_simd_vbmi(void)
{
    return (detected() & VBMI) && tex_simd_level() >= TEX_SIMD_AVX512;
}
