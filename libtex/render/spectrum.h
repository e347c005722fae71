/* spectrum.h - the spectral colour model (Ferreira 1991, section 4, after Hall)
 *
 * Curves and bands.  A tex_curve holds a spectral curve at 1 nm from 380 to
 * 780 nm (401 values), built from a table (linear interpolation, constant
 * beyond its ends), from Planck's law, or read from Debian's colord-data.
 * A tex_bands splits 380-780 nm into n equal bands (1 <= n <= TEX_BANDS_MAX,
 * default 16, i.e. 25 nm each).  Following Hall (1987), a curve is sampled by
 * taking in each band the mean of the curve over the band, computed exactly
 * from its 1 nm values (the piecewise-linear curve through them); all
 * illumination is then done per band.
 *
 *   tex_colorimetry cm;                      // CIE 1931 2-degree + D65
 *   if (tex_colorimetry_load(&cm, NULL) < 0) ...  // NULL: /usr/share/colord
 *   struct tex_bands b;
 *   tex_bands_init(&b, 16, &cm);             // usage error outside 1..64
 *   float s[TEX_BANDS_MAX];
 *   tex_bands_sample(&b, &curve, s);         // Hall band means
 *   double xyz[3], rgb[3];
 *   tex_bands_xyz(&b, s, xyz);               // reflected spectrum -> XYZ
 *   tex_xyz_to_linear_srgb(xyz, rgb);        // primaries' matrix
 *   tex_gamut_map(rgb, TEX_GAMUT_DESATURATE);
 *   // then the display non-linearity when a file is written (colour.h's
 *   // tex_srgb_encode, the renderer's: the chain stays linear until then)
 *
 * Spectrum to XYZ.  The band samples are reconstructed as a step function
 * (constant over each band) and multiplied by the CIE matching functions,
 * so X = sum_i s_i Wx_i with Wx_i the integral of xbar over band i; the
 * weights are divided by the integral of ybar over 380-780 nm, so that a
 * flat spectrum of 1 has Y = 1 and an equal-energy spectrum has x = y = 1/3.
 *
 * Lights.  tex_bands_light() samples a light's curve and scales it to
 * luminance Y = 1; a light's intensity multiplies that.  A white (rho = 1)
 * diffuse surface under D65 then gives XYZ of D65 with Y = 1, which is
 * linear sRGB (1,1,1): D65 is sRGB's white.  Under illuminant A the same
 * surface is orange, as it should be (no chromatic adaptation is applied).
 *
 * XYZ -> linear sRGB: tex_xyz_to_linear_srgb() is the IEC 61966-2-1 matrix
 *     R =  3.2404542 X - 1.5371385 Y - 0.4985314 Z
 *     G = -0.9692660 X + 1.8760108 Y + 0.0415560 Z
 *     B =  0.0556434 X - 0.2040259 Y + 1.0572252 Z
 * built from the primaries' chromaticities r (0.64, 0.33), g (0.30, 0.60),
 * b (0.15, 0.06) and the white (0.3127, 0.3290).  The band chain
 * (tex_bands_to_rgb) builds the same matrix from the same primaries, but
 * with the white measured from colord's D65 through these very bands
 * (SMPTE RP 177): colord's 5 nm D65 cut to 380-780 nm sits at (0.3131,
 * 0.3294), and with the textbook matrix a white surface would come out
 * 0.6 % off neutral.  This way it is neutral to rounding for any band count.
 *
 * Gamut mapping (tex_gamut_map), in linear RGB:
 *   TEX_GAMUT_CLIP        clamp each channel to [0,1] (shifts hue).
 *   TEX_GAMUT_DESATURATE  move the colour in a straight line toward the grey
 *       of the same luminance Y = 0.2126 R + 0.7152 G + 0.0722 B until it is
 *       inside [0,1]^3: first until no channel is negative, then until none
 *       exceeds 1.  Luminance and hue (dominant wavelength) are kept and only
 *       saturation is lost; a colour brighter than white (Y >= 1) becomes
 *       white, a colour with Y <= 0 black.  This is the default.
 *   TEX_GAMUT_CHROMA      only the first step: no negative channel, luminance
 *       kept, values above 1 left for the writer (the renderer's per-sample
 *       conversion, so that EXR output keeps its range).
 *   TEX_GAMUT_NONE        leave linear values as they are.
 *
 * RGB -> spectrum (tex_bands_from_rgb), for colours given in RGB (textured
 * albedo, scene colours) in spectral mode: a smooth basis.  Three smooth
 * curves that sum to 1 at every wavelength,
 *     b_blue  = 1 - sig((l - 490)/12),  b_red = sig((l - 590)/12),
 *     b_green = 1 - b_blue - b_red,      sig(t) = 1/(1 + e^-t),
 * are weighted, rho = sum c_j b_j, with c = M^-1 rgb, where M_ij is the
 * linear sRGB component i of basis curve j seen under D65.  The round trip
 * rgb -> spectrum -> rgb under D65 is then exact, and rgb (1,1,1) gives the
 * flat spectrum 1 (so white stays white and grey stays grey).  Very saturated
 * colours can need negative weights; the curve is then clipped to [0,1] for a
 * reflectance (to [0,inf) otherwise), which desaturates them slightly.  This
 * is simpler than Smits (1999) and, unlike it, exact for all non-saturated
 * colours.
 *
 * Files from colord-data (IT8/CGATS text): SPECTRAL_START_NM, SPECTRAL_END_NM,
 * SPECTRAL_BANDS and NUMBER_OF_SETS in the header, then BEGIN_DATA, one line
 * per set with SPECTRAL_BANDS values evenly spaced from start to end, and
 * END_DATA.  The CMF file has three sets (xbar, ybar, zbar), the illuminant
 * files one.  A missing file is a runtime error naming the path and the
 * Debian package (colord-data).  The directory is /usr/share/colord, or the
 * environment variable TEXTURA_COLORD if set, or the `dir` argument.
 */
#ifndef TEX_SPECTRUM_H
#define TEX_SPECTRUM_H

#include "../base/api.h"

TEX_API_BEGIN

#define TEX_LAMBDA_MIN 380
#define TEX_LAMBDA_MAX 780
#define TEX_CURVE_N (TEX_LAMBDA_MAX - TEX_LAMBDA_MIN + 1)
#define TEX_BANDS_MAX 64
#define TEX_BANDS_DEFAULT 16

typedef struct tex_curve {
    float v[TEX_CURVE_N]; /* v[i] at 380 + i nm */
} tex_curve;

typedef struct tex_colorimetry {
    tex_curve x, y, z; /* CIE 1931 2-degree matching functions */
    tex_curve d65;     /* CIE D65 relative power */
} tex_colorimetry;

struct tex_bands {
    int n;
    double width;                  /* nm */
    float centre[TEX_BANDS_MAX];   /* nm */
    float wxyz[TEX_BANDS_MAX][4];  /* CIE weights by band: XYZ = sum s_i wxyz[i][.]; [3] 0 */
    float basis[3][TEX_BANDS_MAX]; /* RGB basis curves (blue, green, red) per band */
    double rgb2c[3][3];            /* M^-1: rgb -> basis weights (r, g, b order) */
    double xyz2rgb[3][3];          /* sRGB primaries, white = these bands' D65 */
};

enum tex_gamut { TEX_GAMUT_DESATURATE, TEX_GAMUT_CLIP, TEX_GAMUT_CHROMA, TEX_GAMUT_NONE };

/* Curves. */
void tex_curve_constant(tex_curve *c, double v);
/* wl must be strictly increasing and >= 0; n >= 1.  Usage error otherwise. */
int tex_curve_from_table(tex_curve *c, const double *wl, const double *val, int n);
/* Planck's law at kelvin (> 0), scaled to 1 at 560 nm. */
int tex_curve_blackbody(tex_curve *c, double kelvin);
/* Value at a wavelength (linear between the 1 nm samples, constant outside). */
double tex_curve_at(const tex_curve *c, double nm);
/* Mean of the curve over [a, b] nm (a < b), exact for the piecewise-linear curve. */
double tex_curve_mean(const tex_curve *c, double a, double b);

/* colord-data files: set `set` (0-based) of an IT8 spectral file. */
int tex_curve_read_colord(tex_curve *c, const char *path, int set);
int tex_colorimetry_load(tex_colorimetry *cm, const char *dir);
/* A named illuminant: "D65", "A", "E" (equal energy), any CIE-<name>.sp of
 * colord ("D50", "F2", ...), or "blackbody:K" (e.g. "blackbody:3200"). */
int tex_illuminant(tex_curve *c, const char *name, const char *dir);

/* Bands. */
int tex_bands_init(struct tex_bands *b, int n, const tex_colorimetry *cm);
void tex_bands_sample(const struct tex_bands *b, const tex_curve *c, float *out);
/* Sample a light and scale it to Y = 1.  Returns -1 for a light with Y <= 0. */
int tex_bands_light(const struct tex_bands *b, const tex_curve *c, float *out);
void tex_bands_xyz(const struct tex_bands *b, const float *s, double xyz[3]);
void tex_bands_from_rgb(const struct tex_bands *b, const double rgb[3], int reflectance,
                        float *out);
/* Whole chain: spectrum -> XYZ -> linear sRGB (b->xyz2rgb) -> gamut mapping (linear). */
void tex_bands_to_rgb(const struct tex_bands *b, const float *s, enum tex_gamut g,
                      double rgb[3]);

/* Colour spaces. */
void tex_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);
void tex_linear_srgb_to_xyz(const double rgb[3], double xyz[3]);
void tex_gamut_map(double rgb[3], enum tex_gamut g);

TEX_API_END
#endif
