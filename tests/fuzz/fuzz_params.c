/* fuzz_params.c - libFuzzer target: option values through every parameter type.
 * The first byte picks the row, the rest is the text. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

struct p {
    int n, flag, e;
    double x;
    struct tex_reals l;
    float col[4];
    const char *s;
};

static const struct tex_param rows[] = {
    TEX_INT(struct p, n, 'n', 4, -5, 30, "N", "int"),
    TEX_REAL(struct p, x, 0, 0.5, -1e6, 1e6, "X", "real"),
    TEX_FLAG(struct p, flag, 0, "flag"),
    TEX_ENUM(struct p, e, 0, "b", "a|b|c|minkowski", "enum"),
    TEX_REALS(struct p, l, 0, "1,2", -10, 10, TEX_REALS_MAX, "LIST", "list"),
    TEX_COLOR(struct p, col, 0, "#ff8000", "colour"),
    TEX_STRING(struct p, s, 0, NULL, "S", "string"),
    {0}};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct p v;
    char *text;

    if (size < 1)
        return 0;
    if (!(text = malloc(size)))
        return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    tex_params_defaults(rows, &v);
    if (tex_param_set(&rows[data[0] % 7], &v, text) == 0) {
        if (v.n < -5 || v.n > 30 || !(v.x >= -1e6 && v.x <= 1e6) || v.e < 0 || v.e > 3 ||
            v.l.n < 0 || v.l.n > TEX_REALS_MAX)
            abort(); /* a value outside its declared range got through */
    }
    free(text);
    return 0;
}
