/* palette_srgb.h - OKLab to sRGB for palette.c and its x86 kernel
 *
 * Internal to libtex (not installed).  The sRGB encoding c^(1/2.4) comes from
 * a table of Taylor polynomials (palette.c's enc_pow), filled once; the vector
 * kernel (x86/palette_x86.c) reads the same table and performs the same double
 * operations, so both give the same floats.
 */
#ifndef TEX_PALETTE_SRGB_H
#define TEX_PALETTE_SRGB_H

enum { ENC_PIECES = 32, ENC_DEGREE = 6 };

/* The encoding's table: coefficient k of piece i at coef[k][i] (a coefficient's pieces
 * together, for permutes); scale[-e] = 2^(5e/12) */
struct tex_srgb_enc {
    double coef[ENC_DEGREE + 1][ENC_PIECES], scale[16];
};

/* OKLab to linear sRGB: L, M and S's cube roots from (L, a, b), then RGB from their cubes
 * (a subtraction is the addition of the negated product, to the bit) */
static const double ok_lms[3][2] = {{0.3963377774, 0.2158037573},
                                    {-0.1055613458, -0.0638541728},
                                    {-0.0894841775, -1.2914855480}};
static const double ok_rgb[3][3] = {{4.0767416621, -3.3077115913, 0.2309699292},
                                    {-1.2684380046, 2.6097574011, -0.3413193965},
                                    {-0.0041960863, -0.7034186147, 1.7076147010}};

/* The sRGB encoding of linear c as a float (palette.c's scalar definition) */
float tex_palette_srgb_encode(double c);

#endif
