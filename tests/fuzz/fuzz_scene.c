/* fuzz_scene.c - libFuzzer target for the t_apply scene parser
 *
 * Build: make fuzz (from the top; tests/fuzz/Makefile compiles libtex in,
 * instrumented), which writes build/fuzz/fuzz_scene.
 * Run:  build/fuzz/fuzz_scene -max_total_time=600 tests/fuzz/corpus-scene tests/fuzz/seeds-scene
 *
 * Each input is parsed as a scene; a scene that parses is prepared and
 * rendered at 4x3 pixels with one sample, so the geometry, CSG and
 * texture code see what the parser lets through.  Textures without a size
 * are sampled at 16x16 (512x512 in t_apply), and inputs naming a size are
 * skipped, so every input is cheap.  Map files are not read (a scene
 * naming one fails to parse cleanly).
 */
#define _GNU_SOURCE /* memmem */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "render/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* keep the fuzzer away from the file system and standard input, and
     * from sampling primitives into maps of up to 8192^2 (seconds each;
     * the mip-map path is covered by the unit tests) */
    static const struct tex_scene_opts small = {16};
    if (memmem(data, size, "file", 4) || memmem(data, size, "size", 4))
        return 0;
    struct tex_scene *s = tex_scene_parse_opts((const char *)data, size, "fuzz.scene", &small);
    if (!s)
        return 0;
    s->settings.w = 4;
    s->settings.h = 3;
    s->settings.spp = 1;
    s->settings.threads = 1;
    if (s->settings.depth > 4)
        s->settings.depth = 4;
    if (tex_scene_prepare(s) == 0) {
        tex_map *m = tex_render(s, NULL, NULL);
        tex_map_free(m);
    }
    tex_scene_free(s);
    return 0;
}
