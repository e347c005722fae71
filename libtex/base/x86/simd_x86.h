/* simd_x86.h - x86 intrinsics and the targets the kernels in x86/ folders compile for
 *
 * Included by the kernels of every layer's x86/ folder, never by the portable code.
 * A kernel is compiled for its instruction set function by function, so one build
 * runs on every x86-64 CPU and tex_simd_level (../simd.h) chooses at run time:
 *
 *   TEX_AVX2 void tex_noise_rows_avx2(...) { ... }
 *
 * TEX_AVX512 is AVX-512F; TEX_VBMI is AVX2 with AVX-512's byte permutes (VBMI, VL and
 * BW) on 256- and 512-bit registers, for the kernels that look tables up in registers
 * (tex_simd_vbmi).
 */
#ifndef TEX_SIMD_X86_H
#define TEX_SIMD_X86_H

#include "../simd.h"

#ifdef TEX_X86
#include <immintrin.h>
#define TEX_AVX2 __attribute__((target("avx2")))
#define TEX_AVX512 __attribute__((target("avx512f")))
#define TEX_VBMI __attribute__((target("avx2,avx512f,avx512vl,avx512bw,avx512vbmi")))
#endif

#endif
