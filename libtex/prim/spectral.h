/* spectral.h - the frequency domain: FFT, inverse FFT of painted spectra,
 * spectral synthesis of fBm and Lewis's sparse convolution
 *
 * Thesis 2.4 and 5.2.3 (Lewis 1984): some textures are easier to describe
 * by their spectrum.  Transforms go through FFTW in single precision with
 * its threads (as many as OpenMP's max, i.e. -j) and the ESTIMATE planner,
 * so the same input gives the same bits on every run and for any thread
 * count (FFTW's threads only split independent rows and columns; checked
 * by the tests).  FFTW chooses its SIMD codelets from the CPU, so two
 * machines with different vector units may differ in the last bits.  Any
 * size works, not only powers of two.
 *
 * The centred layout.  A w x h spectrum map holds the frequency (kx, ky),
 * in cycles across the map, at pixel
 *     x = (kx + w/2) mod w,  y = (ky + h/2) mod h      (integer division)
 * so the DC term sits at (w/2, h/2), the middle, as a person paints it;
 * ky grows downwards like y.  A map's value at pixel (x,y) is
 *     f(x,y) = sum_k F(k) exp(+2 pi i (kx x / w + ky y / h))
 * and the forward transform is normalised by 1/(w h), so F(0) is the
 * map's mean and a cosine of amplitude A shows as A/2 at k and at -k.
 * Phases are stored as turns in [0,1): phi = 2 pi p.
 *
 * Scalars of a map: channel 0 of 1- and 2-channel maps, the Rec. 709 luma
 * 0.2126 R + 0.7152 G + 0.0722 B of RGB(A) maps (alpha ignored).
 *
 *   tex_map *s = tex_fft(m, TEX_FFT_COMPLEX, 0);      // re, im; centred
 *   struct tex_ifft_opts o = TEX_IFFT_DEFAULTS;
 *   tex_map *back = tex_ifft(s, &o);                  // == m within float rounding
 *
 *   tex_fft(m, out, hann)
 *       TEX_FFT_LOGMAG  log(1 + w h |F|) / log(1 + w h max|F|), in [0,1]
 *       TEX_FFT_MAG     |F| (raw: DC = mean)
 *       TEX_FFT_PHASE   arg F in turns [0,1)
 *       TEX_FFT_COMPLEX 2 channels, Re F and Im F: lossless
 *     hann != 0 multiplies the map by the Hann window
 *     (0.5 - 0.5 cos(2 pi (x + 0.5) / w)) (same in y), divided by its mean
 *     so that amplitudes keep their scale, against edge leakage.
 *
 *   tex_ifft(spectrum, opts)
 *     A 2-channel spectrum is complex (Re, Im) as tex_fft writes it; any
 *     other is a magnitude M (its scalar), combined with a phase: random
 *     (uniform, from opts->seed; a pure function of the seed and the
 *     frequency), zero, or opts->phase_map (turns, same size).
 *     symmetric: complete the spectrum by Hermitian symmetry, F(-k) =
 *     conj F(k), so that the result is real (and the c2r transform runs,
 *     twice as fast).  For each pair k, -k the member with the larger
 *     magnitude (on a tie, the one first in the map) gives magnitude and
 *     phase, so painting two quadrants (one half plane) is enough;
 *     self-conjugate terms (DC, Nyquist) become M cos(phi).  A complex
 *     spectrum is projected instead: (F(k) + conj F(-k)) / 2.
 *     Outputs: TEX_IFFT_REAL Re f, _MAG |f|, _LOGMAG log(1 + |f|),
 *     _PHASE arg f in turns, _COMPLEX Re f and Im f as 2 channels.
 *     Scale: TEX_SCALE_UNIT rescales REAL to [0,1] by its min and max and
 *     MAG, LOGMAG by their max (a constant map becomes its value clamped
 *     to [0,1]); TEX_SCALE_NONE keeps raw values; TEX_SCALE_AUTO is NONE
 *     for a complex spectrum (exact inversion) and UNIT otherwise.
 *     Refused (runtime error): NaN or infinite pixels, an all-zero
 *     spectrum, a phase map of another size.
 *
 *   tex_spectral_fbm(m, p)
 *     Fill the 1-channel map m with fBm by spectral synthesis (Voss,
 *     Saupe): amplitude f^-(H+1) at every frequency k != 0, uniform random
 *     phase, Hermitian, inverse c2r, rescaled to [0,1].  f = |k| in cycles
 *     across the longer side, so features are round in pixels.  Anisotropy
 *     (angle a in degrees counter-clockwise from +u on the screen, ratio
 *     r > 0): structures are stretched r times along a, i.e. the amplitude
 *     uses f' = sqrt((r k_par)^2 + k_perp^2) with k_par the component of
 *     k along a.  Only lo <= f <= hi carries energy (the band).  Integer
 *     frequencies only, so the map tiles by construction.
 *
 *   tex_sparse_convolve(sample, w, h, p)
 *     Lewis's sparse convolution.  The sample (any channels, at most w x h)
 *     minus its mean is windowed by the radial exp(-k rho), rho the
 *     distance from its centre in units of its half size (rho = 1 at the
 *     middle of each edge; the thesis's exp(-sqrt(x^2+y^2)) with x, y
 *     scaled to the sample), and summed at N = density w h / (sw sh)
 *     uniform random pixel positions with uniform random weights in
 *     [-1,1] (the white noise), circularly, through the FFT.  The field
 *     has the windowed sample's spectrum; it tiles.  Each channel is then
 *     mapped linearly onto the sample's range (min to min, max to max).
 */
#ifndef TEX_SPECTRAL_H
#define TEX_SPECTRAL_H

#include <stdint.h>

#include "../base/api.h"
#include "../base/map.h"

TEX_API_BEGIN

enum tex_fft_output { TEX_FFT_LOGMAG, TEX_FFT_MAG, TEX_FFT_PHASE, TEX_FFT_COMPLEX };
enum tex_ifft_phase { TEX_PHASE_RANDOM, TEX_PHASE_ZERO, TEX_PHASE_MAP };
enum tex_ifft_output { TEX_IFFT_REAL, TEX_IFFT_MAG, TEX_IFFT_LOGMAG, TEX_IFFT_PHASE,
                       TEX_IFFT_COMPLEX };
enum tex_ifft_scale { TEX_SCALE_AUTO, TEX_SCALE_UNIT, TEX_SCALE_NONE };

struct tex_ifft_opts {
    enum tex_ifft_phase phase;
    const tex_map *phase_map; /* TEX_PHASE_MAP: turns, the spectrum's size */
    uint64_t seed;            /* TEX_PHASE_RANDOM */
    int symmetric;
    enum tex_ifft_output output;
    enum tex_ifft_scale scale;
};
#define TEX_IFFT_DEFAULTS {TEX_PHASE_RANDOM, NULL, 1, 0, TEX_IFFT_REAL, TEX_SCALE_AUTO}

struct tex_fbm_spec {
    double h;            /* Hurst exponent: amplitude f^-(h+1) */
    double angle, ratio; /* anisotropy: degrees, stretch (1: isotropic) */
    double lo, hi;       /* band, cycles across the longer side */
    uint64_t seed;
};

struct tex_sparse_spec {
    double density; /* impulses per sample area */
    double falloff; /* k of the window exp(-k rho) */
    uint64_t seed;
};

tex_map *tex_fft(const tex_map *m, enum tex_fft_output out, int hann);
tex_map *tex_ifft(const tex_map *spectrum, const struct tex_ifft_opts *o);
int tex_spectral_fbm(tex_map *m, const struct tex_fbm_spec *p);
tex_map *tex_sparse_convolve(const tex_map *sample, int w, int h, const struct tex_sparse_spec *p);

/* 0 if every sample of m is finite, else -1 naming the first bad pixel
 * (after "what: " unless what is NULL). */
int tex_check_finite(const tex_map *m, const char *what);

TEX_API_END
#endif
