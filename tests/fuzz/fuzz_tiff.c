/* fuzz_tiff.c - libFuzzer target: the TIFF bridge (tiff_bridge.c) and libtiff under it:
 * strips and tiles, 8 and 16-bit integers, floats, and libtiff's RGBA reader for the
 * rest; what decodes round-trips through the writer exactly (codec.h). */
#define BRIDGE tex_tiff_bridge
#define EXACT 1
#include "codec.h"
