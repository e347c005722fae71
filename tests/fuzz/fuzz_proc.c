/* fuzz_proc - composed primitives: the definitions language, its compiler to row code,
 * and evaluation
 *
 * Every definition the reader accepts is started and evaluated over a small grid
 * (8 x 8, and at 3D points when it is solid), so calls, arguments checked by the
 * callees' rows and the row code all run.
 */
#include <stddef.h>
#include <stdint.h>

#include "lang/proc.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct tex_procs *set;
    const struct tex_primitive *p;

    if (size > 4096 || !(set = tex_procs_new()))
        return 0;
    if (tex_procs_load(set, (const char *)data, size, "fuzz") == 0)
        for (int i = 0; (p = tex_procs_get(set, i)); i++) {
            struct tex_field *f = tex_field_new(p);
            if (f && tex_field_init(f, 8, 8) == 0) {
                double u[5] = {0, 0.25, 0.5, 0.75, 1}, w[5] = {0.1, 0.9, -3, 7, 0.5};
                float out[5];
                tex_map_free(tex_field_sample(f));
                if (p->eval3)
                    p->eval3(f, 5, u, w, w, out);
            }
            tex_field_free(f);
        }
    tex_procs_free(set);
    return 0;
}
