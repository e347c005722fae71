/* fp_strict.h - no contraction into fused multiply-adds in this file
 *
 * Maps must be bit-identical across SIMD levels, thread counts and
 * compilers, so kernels that have a scalar and a vector path include this
 * first: every level then does the same float operations in the same order,
 * whatever -march the library is built with.  The Makefile passes
 * -ffp-contract=off too; this keeps it for any other build (gcc ignores the
 * STDC pragma, clang the GCC one).  Not a guarded header: it only sets the
 * including file's floating-point mode.
 */
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#else
#pragma GCC optimize("fp-contract=off")
#endif
