/* textura.h - libtex, the library behind the Textura tools
 *
 * Include this one header, link with `pkg-config --libs textura`.
 * Each module has its own header, whose top is its manual:
 *
 *   error.h   how failures are reported (libtex never prints or exits)
 *   map.h     the texture map: float32, 1-4 channels, metadata
 *   stream.h  the OpenEXR stream between tools
 *   file.h    reading and writing maps: files, pipes, other formats
 *   param.h   parameter tables: defaults, ranges, help, parsing
 *   prim.h    the primitive descriptor and registry, sampling on a grid
 *   cli.h     the tools' shared command-line front end
 *   rng.h     deterministic random numbers
 *   noise.h   the thesis's gradient noise
 *   geometry.h the geometric primitives and their subregions
 */
#ifndef TEXTURA_H
#define TEXTURA_H

#include "cli.h"
#include "error.h"
#include "file.h"
#include "geometry.h"
#include "map.h"
#include "noise.h"
#include "param.h"
#include "prim.h"
#include "rng.h"
#include "stream.h"

#endif
