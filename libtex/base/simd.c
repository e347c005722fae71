/* simd.c - the SIMD level, found once */

#include <stdlib.h>
#include <string.h>

#include "base/simd.h"

const char *tex_simd_name(int level)
{
    return level == TEX_SIMD_AVX512 ? "avx512" : level == TEX_SIMD_AVX2 ? "avx2" : "scalar";
}

/* The CPU's best level, capped by TEXTURA_SIMD (scalar or avx2).  The point kernel has no
 * sixteen-lane form: with its gradients gathered or transposed in 512-bit registers it ran
 * at 0.6-0.9 times the AVX2 one's speed on a Xeon with AVX-512 (2026-11).  At this level it
 * keeps eight lanes and takes its hashes from VBMI's byte permutes (tex_simd_vbmi): 1.3 times
 * the gathers' speed on an EPYC (Zen 4). */
static int simd_detect(void)
{
    int best = TEX_SIMD_SCALAR;
    const char *e = getenv("TEXTURA_SIMD");
#ifdef TEX_X86
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2"))
        best = TEX_SIMD_AVX2;
    if (best == TEX_SIMD_AVX2 && __builtin_cpu_supports("avx512f"))
        best = TEX_SIMD_AVX512;
#endif
    if (e && strcmp(e, "scalar") == 0)
        best = TEX_SIMD_SCALAR;
    else if (e && strcmp(e, "avx2") == 0 && best > TEX_SIMD_AVX2)
        best = TEX_SIMD_AVX2;
    return best;
}

static int limit = TEX_SIMD_AVX512;

int tex_simd_level(void)
{
    static int level = -1;
    int l = __atomic_load_n(&level, __ATOMIC_RELAXED), m;
    if (l < 0) {
        l = simd_detect();
        __atomic_store_n(&level, l, __ATOMIC_RELAXED);
    }
    m = __atomic_load_n(&limit, __ATOMIC_RELAXED);
    return l < m ? l : m;
}

void tex_simd_limit(int level)
{
    __atomic_store_n(&limit, level, __ATOMIC_RELAXED);
}

int tex_simd_vbmi(void)
{
    static int has = -1;
    int h = __atomic_load_n(&has, __ATOMIC_RELAXED);
    if (h < 0) {
        h = 0;
#ifdef TEX_X86
        __builtin_cpu_init();
        h = __builtin_cpu_supports("avx512vbmi") && __builtin_cpu_supports("avx512vl") &&
            __builtin_cpu_supports("avx512bw");
#endif
        __atomic_store_n(&has, h, __ATOMIC_RELAXED);
    }
    return h && tex_simd_level() >= TEX_SIMD_AVX512;
}
