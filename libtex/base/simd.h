/* simd.h - the instruction sets the vector kernels may use
 *
 * Kernels with a vector path live in their layer's x86/ folder, compiled for
 * AVX2 or AVX-512 function by function (x86/simd_x86.h), and are chosen at run
 * time, so one build runs on every x86-64 CPU:
 *
 *   #ifdef TEX_X86
 *   if (tex_simd_level() >= TEX_SIMD_AVX2) { rows_avx2(...); return; }
 *   #endif
 *   rows(...);
 *
 * Every level performs the same float operations in the same order, so the
 * bytes never depend on it; TEXTURA_SIMD=scalar forces the portable path and
 * TEXTURA_SIMD=avx2 caps the level at AVX2, as the tests do to check that, and
 * a test that compares the paths in one process lowers the level with
 * tex_simd_limit.  AVX-512F has two users, the noise rows of wide cells
 * (noise.h) and the renderer's map lookups over a packet of hits
 * (tex_texture_points), and VBMI one, the point kernel's sixteen lanes with
 * their hashes from a byte table in registers where the CPU has VBMI
 * (tex_simd_vbmi); elsewhere AVX2 stays the best level's kernel.
 */
#ifndef TEX_SIMD_H
#define TEX_SIMD_H

/* TEX_X86: this build has the x86 kernels to choose from */
#if defined(__x86_64__) || defined(__i386__)
#define TEX_X86 1
#endif

#ifdef __cplusplus
extern "C" {
#endif

enum { TEX_SIMD_SCALAR = 0, TEX_SIMD_AVX2 = 1, TEX_SIMD_AVX512 = 2 };
/* The level in use: the best the CPU has, or TEXTURA_SIMD's if lower. */
int tex_simd_level(void);
/* Use at most level from now on (TEX_SIMD_AVX512: the CPU's best again). */
void tex_simd_limit(int level);
/* 1 where the level in use is AVX-512 and the CPU has its byte permutes (VBMI, with VL and
 * BW), for the kernels that look tables up in registers. */
int tex_simd_vbmi(void);
const char *tex_simd_name(int level);

#ifdef __cplusplus
}
#endif

#endif
