/* palette_x86.h - palette.c's kernels for x86: OKLab to sRGB eight colours at a time
 * (AVX-512) or four (AVX2), the floats of tex_oklab_to_srgb; and a run of a map's values
 * coloured sixteen at a time (AVX-512), the floats of colour_run
 */
#ifndef TEX_PALETTE_X86_H
#define TEX_PALETTE_X86_H

struct tex_srgb_enc;

/* The first n - n % 8 colours of lab (channels apart) as sRGB into rgb, the encoding's
 * table e filled; returns how many. */
int tex_oklab_srgb_avx512(const struct tex_srgb_enc *e, const float *const lab[3],
                          float *const rgb[3], int n);

/* The same, the first n - n % 4 colours, four at a time with AVX2 */
int tex_oklab_srgb_avx2(const struct tex_srgb_enc *e, const float *const lab[3],
                        float *const rgb[3], int n);

/* A palette of 1..16 stops in order, each quantity's stops side by side for permutes */
struct tex_palette_lanes {
    int n, oklab; /* stops; mixed in OKLab */
    float pos[16], rgba[4][16], lab[3][16];
};

/* colour_run of the first n - n % 16 values of v: t from lo, hi and outside (enum
 * tex_outside) as palette_t and stop_t, the stop by count, the mix as mix_stops (OKLab to
 * sRGB through e), nc (3 or 4) floats a pixel into out; returns how many. */
int tex_palette_colour_avx512(const struct tex_palette_lanes *l, const struct tex_srgb_enc *e,
                              const float *v, int n, double lo, double hi, int outside,
                              float *out, int nc);
/* The same eight at a time with AVX2: the first n - n % 8 values */
int tex_palette_colour_avx2(const struct tex_palette_lanes *l, const struct tex_srgb_enc *e,
                            const float *v, int n, double lo, double hi, int outside,
                            float *out, int nc);

#endif
