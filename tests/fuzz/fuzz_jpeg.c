/* fuzz_jpeg.c - libFuzzer target: the JPEG bridge (jpeg_bridge.c) and libjpeg-turbo under
 * it, baseline and progressive; what decodes is encoded again and must decode to the same
 * size (codec.h). */
#define BRIDGE tex_jpeg_bridge
#define EXACT 0
#include "codec.h"
