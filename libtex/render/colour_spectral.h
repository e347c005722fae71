/* colour_spectral.h - the spectral colour space for the renderer (colour.h)
 *
 * Fills a struct tex_colour_space whose colours are n Hall bands over
 * 380-780 nm (spectrum.h), so t_apply can shade per band:
 *
 *   struct tex_colour_space cs;
 *   if (tex_colour_space_spectral(&cs, 16, NULL) < 0) die(tex_errmsg());
 *   cs.from_rgb(&cs, rgb, TEX_SPECTRUM_REFLECTANCE, &c);   // albedo, texture
 *   cs.to_rgb(&cs, &c, rgb);                               // once per sample
 *   tex_colour_space_spectral_light(&cs, &curve, &c);      // D65, A, blackbody
 *   tex_colour_space_spectral_free(&cs);
 *
 * from_rgb: a reflectance goes through the smooth RGB basis of
 * tex_bands_from_rgb (clipped to [0,1]); an illuminant given as RGB is that
 * basis curve times D65 with Y = 1, so the RGB light (1,1,1) is D65, the
 * white of sRGB, and a white surface under it renders as (1,1,1).
 * to_rgb: CIE 1931 -> XYZ -> linear sRGB (white = D65 through these bands)
 * and the chromatic gamut mapping TEX_GAMUT_CHROMA (negative channels
 * desaturated toward the grey of equal luminance); the range above 1 is left
 * to the writer.  n outside 1..TEX_COLOUR_MAX is a usage error; missing CIE
 * tables a runtime error naming colord-data.  `colord` is the colord-data
 * directory, NULL for the default (spectrum.h).
 */
#ifndef TEX_COLOUR_SPECTRAL_H
#define TEX_COLOUR_SPECTRAL_H

#include "../base/api.h"
#include "colour.h"
#include "spectrum.h"

TEX_API_BEGIN

int tex_colour_space_spectral(struct tex_colour_space *cs, int n, const char *colord);
void tex_colour_space_spectral_free(struct tex_colour_space *cs);
/* A light's spectrum, scaled to luminance Y = 1 (then times the light's intensity).
 * In an RGB space: its linear sRGB colour with Y = 1 (computed through 16 bands). */
int tex_colour_space_spectral_light(const struct tex_colour_space *cs, const tex_curve *c,
                                    tex_colour *out);
/* The bands behind a spectral space (NULL for an RGB space). */
const struct tex_bands *tex_colour_space_bands(const struct tex_colour_space *cs);
/* Sample any curve (n or k of a material) into the space's n samples; in RGB mode
 * the curve is read at 610, 550 and 465 nm (representative R, G, B wavelengths). */
void tex_colour_space_curve(const struct tex_colour_space *cs, const tex_curve *c,
                            tex_colour *out);

TEX_API_END
#endif
