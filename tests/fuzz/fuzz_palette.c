/* fuzz_palette.c - libFuzzer target: palette files (tex_palette_parse, textura-palette(5)).
 * Any input must parse or fail with a message; a parsed palette must look up
 * finite colours anywhere in [0,1] and write out without error. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "textura.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    tex_palette *p;

    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    p = tex_palette_parse(text, size, "fuzz");
    free(text);
    if (!p)
        return 0;
    for (int i = 0; i <= 16; i++) {
        float c[4];
        tex_palette_lookup(p, (float)i / 16.0f, c);
        for (int k = 0; k < 4; k++)
            if (!isfinite(c[k]))
                abort();
    }
    FILE *null = fopen("/dev/null", "w");
    if (null) {
        if (tex_palette_write(p, null) < 0)
            abort();
        fclose(null);
    }
    tex_palette_free(p);
    return 0;
}
