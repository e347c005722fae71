/* render_media.c - the stack of transparent media a refracted ray is inside
 *
 * A solid is identified by its top-level object, so the surfaces of one CSG
 * tree (a hollow glass's outer and inner walls) enter and leave one medium.
 * Leaving a solid that is not the innermost (overlapping solids) removes it
 * where it lies; the medium beyond is then the innermost one left.
 */
#include <string.h>

#include "render/scene.h"

double tex_media_ior(const struct tex_media *m)
{
    return m && m->n > 0 ? m->ior[m->n - 1] : 1;
}

void tex_media_cross(const struct tex_media *m, const struct tex_object *ob, int entering,
                     double ior, struct tex_media *out, double *n1, double *n2)
{
    out->n = m ? m->n : 0; /* the stack's used part: most rays carry none or one */
    if (out->n) {
        memcpy(out->ob, m->ob, out->n * sizeof *out->ob);
        memcpy(out->ior, m->ior, out->n * sizeof *out->ior);
    }
    *n1 = tex_media_ior(out);
    if (entering) {
        if (out->n == TEX_MEDIA_MAX) { /* forget the outermost */
            memmove(out->ob, out->ob + 1, (TEX_MEDIA_MAX - 1) * sizeof *out->ob);
            memmove(out->ior, out->ior + 1, (TEX_MEDIA_MAX - 1) * sizeof *out->ior);
            out->n--;
        }
        out->ob[out->n] = ob;
        out->ior[out->n++] = ior;
        *n2 = ior;
        return;
    }
    /* leaving: the surface's own index is the side we come from */
    *n1 = ior;
    for (int i = out->n - 1; i >= 0; i--) {
        if (out->ob[i] == ob) {
            memmove(out->ob + i, out->ob + i + 1, (out->n - 1 - i) * sizeof *out->ob);
            memmove(out->ior + i, out->ior + i + 1, (out->n - 1 - i) * sizeof *out->ior);
            out->n--;
            break;
        }
    }
    *n2 = tex_media_ior(out);
}
