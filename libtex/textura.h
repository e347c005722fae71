/* textura.h - libtex, the library behind the Textura tools
 *
 * Include this one header, link with `pkg-config --libs textura`.
 * Each module has its own header, whose top is its manual.
 *
 * Foundation
 *   error.h     how failures are reported (libtex never prints or exits)
 *   map.h       the texture map: float32, 1-4 channels, metadata
 *   stream.h    the OpenEXR stream between tools
 *   file.h      reading and writing maps: files, pipes, other formats
 *   param.h     parameter tables: defaults, ranges, help, parsing
 *   prim.h      the primitive descriptor and registry, sampling on a grid
 *   cli.h       the tools' shared command-line front end
 *   rng.h       deterministic random numbers
 * Primitives
 *   noise.h     gradient noise, its gradient, octave sums (turbulence, fBm)
 *   cellular.h  point sets and nearest-point queries (bubbles, Voronoi cells)
 *   geometry.h  the geometric primitives and their subregions
 *   spectral.h  the frequency domain: FFT, painted spectra, spectral synthesis
 * General tools and composition
 *   palette.h   palettes: scalars and region ids to colours
 *   filter.h    neighbourhood filters (blur, edges, normal maps...)
 *   remap.h     bias, gain, gamma, levels, clamp, quantise
 *   transform.h filtered rotate, scale, shift, expand, clip
 *   compose.h   per-pixel operators, cascades, tiling, warps
 *   script.h    the pattern composition language
 * The renderer (t_apply)
 *   render.h        scenes, CSG objects, mapping, texture application
 *   render_shade.h  shading models: the interface every model fills
 *   render_ct.h     the Cook-Torrance model
 *   colour.h        the renderer's colour: n samples, RGB or spectral
 *   colour_spectral.h, spectrum.h, fresnel.h, microfacet.h, matdb.h
 *                   the spectral colour model and its optics
 */
#ifndef TEXTURA_H
#define TEXTURA_H

#include "cellular.h"
#include "cli.h"
#include "colour.h"
#include "colour_spectral.h"
#include "compose.h"
#include "error.h"
#include "file.h"
#include "filter.h"
#include "fresnel.h"
#include "geometry.h"
#include "map.h"
#include "matdb.h"
#include "microfacet.h"
#include "noise.h"
#include "palette.h"
#include "param.h"
#include "prim.h"
#include "remap.h"
#include "render.h"
#include "render_ct.h"
#include "render_shade.h"
#include "rng.h"
#include "script.h"
#include "spectral.h"
#include "spectrum.h"
#include "stream.h"
#include "transform.h"

#endif
