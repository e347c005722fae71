/* fuzz_png.c - libFuzzer target: the PNG bridge (png_bridge.c) and libpng under it (built
 * with the fuzzer's coverage from Debian's sources by make fuzz-libs, else the system's);
 * what decodes round-trips through the writer at 8 bits exactly (codec.h). */
#define BRIDGE tex_png_bridge
#define EXACT 1
#include "codec.h"
