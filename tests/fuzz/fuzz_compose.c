/* fuzz_compose - the pattern composition language's lexer, parser and interpreter
 *
 * Scripts run with small limits (images of at most 48 x 48 pixels, blur
 * radius 4) and without files, so every input is cheap; anything the
 * interpreter accepts is evaluated, transforms and operators included.
 */
#include <stddef.h>
#include <stdint.h>

#include "base/map.h"
#include "lang/script.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct tex_script_opts o = {48 * 48, 0, 0, 4};
    tex_map *m;

    if (size > 4096)
        return 0;
    m = tex_script_run((const char *)data, size, "fuzz", &o);
    tex_map_free(m);
    return 0;
}
