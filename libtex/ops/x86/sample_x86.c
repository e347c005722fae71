/* sample_x86.c - the sampler's lookup compiled for AVX2 (sample_template.c) */
#include <math.h>
#include <string.h>

#include "base/x86/simd_x86.h"

#ifdef TEX_X86
#include "ops/transform.h"
#include "ops/x86/sample_x86.h"

#define SAMPLE_FN tex_sample_avx2
#define SAMPLE_TARGET TEX_AVX2
#include "ops/sample_template.c"
#endif
