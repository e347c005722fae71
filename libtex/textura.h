/* textura.h - libtex, the library behind the Textura tools
 *
 * Include this one header, link with `pkg-config --libs textura`.
 * libtex is layered; each folder is a layer and includes point only down
 * the list (tests/house/layers.sh checks it). Each module has its own header,
 * whose top is its manual.  These are the installed ones, every one of them
 * included here; libtex.so exports what they declare and nothing else
 * (base/api.h; tests/house/install.sh checks it).
 *
 * base/     the foundation
 *   api.h       what the headers export
 *   error.h     how failures are reported (libtex never prints or exits)
 *   map.h       the texture map: float32, 1-4 channels, metadata
 *   param.h     parameter rows: defaults, ranges, help, parsing
 *   paths.h     where an installed Textura finds its bridges and data
 *   progress.h  how long work tells how far it has gone
 *   rng.h       deterministic random numbers
 *   trig.h      sines of many points, the same bytes on any CPU or libm
 * io/       maps in and out
 *   stream.h    the OpenEXR stream between tools
 *   file.h      reading and writing maps: files, pipes, other formats
 *   limit.h     the one limit on what readers take in (TEXTURA_MAX_INPUT)
 *   netpbm.h    PNM, PAM and PFM, read and written natively
 *   prosim.h    ProSim's headerless NAME.r/.g/.b and NAME.pic, by their names
 *   assemble.h  windows of a map put together into the whole
 *   spool.h     a stream's rows in an unlinked temporary file, read back in any order
 *   terminal.h  a map drawn in a terminal (sixel, kitty)
 * prim/     the primitives
 *   prim.h      the primitive descriptor and registry, sampling on a grid
 *               (primitives.def lists the built-in ones)
 *   noise.h     gradient noise, its gradient, octave sums (turbulence, fBm)
 *   cellular.h  point sets and nearest-point queries (bubbles, Voronoi cells)
 *   geometry.h  the geometric primitives and their subregions
 *   spectral.h  the frequency domain: FFT, painted spectra, spectral synthesis
 * ops/      general tools and composition of maps
 *   palette.h   palettes: scalars and region ids to colours
 *   filter.h    neighbourhood filters (blur, edges, normal maps...)
 *   filter_ops.h the filters by name, with their parameters (t_filter, scripts)
 *   remap.h     bias, gain, gamma, levels, clamp, quantise
 *   transform.h filtered rotate, scale, shift, expand, clip
 *   compose.h   per-pixel operators, cascades, tiling, warps
 *   synth.h     texture synthesis from an example (t_synth)
 * lang/     the languages (their lexer and expression evaluator, lex.h and
 *           expr.h, are libtex's own)
 *   script.h    the pattern composition language
 *   proc.h      composed primitives: new primitives as expressions of others
 * render/   the renderer (t_apply)
 *   render.h        load a scene, set options, render, free (its insides,
 *                   scene.h and the headers it includes, are libtex's own)
 *   colour.h        the renderer's colour: n samples, RGB or spectral
 *   spectrum.h      spectral curves, CIE matching, illuminants
 *   colour_spectral.h  the spectral colour space
 *   fresnel.h       Fresnel reflectance of dielectrics and conductors
 *   microfacet.h    the Cook-Torrance specular term
 *   matdb.h         the materials database (optical constants n + ik)
 * cli/      the tools' shared command-line front end, the one module that
 *           prints and exits
 *   cli.h       the front end's manual, including the four below
 *   options.h   options from rows: getopt, operands, --help, the history
 *   message.h   errors, warnings and progress on standard error
 *   maps.h      a tool's maps read and written, whole or in bands of rows
 *   lockstep.h  per-pixel work over several maps read in bands, in step
 *   generate.h  the generators' main, from a primitive's descriptor
 */
#ifndef TEXTURA_H
#define TEXTURA_H

#include "base/api.h"
#include "base/error.h"
#include "base/progress.h"
#include "base/map.h"
#include "base/param.h"
#include "base/paths.h"
#include "base/rng.h"
#include "base/trig.h"
#include "io/stream.h"
#include "io/file.h"
#include "io/limit.h"
#include "io/netpbm.h"
#include "io/prosim.h"
#include "io/terminal.h"
#include "io/assemble.h"
#include "io/spool.h"
#include "prim/prim.h"
#include "prim/noise.h"
#include "prim/cellular.h"
#include "prim/geometry.h"
#include "prim/spectral.h"
#include "ops/palette.h"
#include "ops/filter.h"
#include "ops/filter_ops.h"
#include "ops/remap.h"
#include "ops/transform.h"
#include "ops/compose.h"
#include "ops/synth.h"
#include "lang/script.h"
#include "lang/proc.h"
#include "render/colour.h"
#include "render/spectrum.h"
#include "render/colour_spectral.h"
#include "render/fresnel.h"
#include "render/microfacet.h"
#include "render/matdb.h"
#include "render/render.h"
#include "cli/cli.h"

#endif
