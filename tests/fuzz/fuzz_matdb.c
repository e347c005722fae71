/* fuzz_matdb.c - libFuzzer target: the materials database (render/matdb.c).
 * Any input must parse or fail with a message; every material parsed must be
 * found again by its name, with finite n and k. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"
#include "render/matdb.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    struct tex_matdb db;

    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    if (tex_matdb_parse(&db, text, "fuzz") == 0) {
        for (int i = 0; i < db.count; i++) {
            if (!tex_matdb_find(&db, db.m[i].name))
                abort();
            for (int j = 0; j < TEX_CURVE_N; j++)
                if (!isfinite(db.m[i].n.v[j]) || !isfinite(db.m[i].k.v[j]))
                    abort();
        }
    }
    tex_matdb_free(&db);
    free(text);
    return 0;
}
