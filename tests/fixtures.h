/* fixtures.h - maps and renders that several unit tests build
 *
 *   tex_map *m = unit_random_map(64, 64, 3, seed);  // uniform [0,1) samples
 *   tex_map *img = unit_render_text(text, 0);       // a scene from text; 0: its own threads
 *
 * Failures print a "# ..." line with libtex's message and return NULL.
 */
#ifndef FIXTURES_H
#define FIXTURES_H

#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "base/map.h"
#include "render/scene.h"
#include "base/rng.h"

static inline tex_map *unit_random_map(int w, int h, int nc, uint64_t seed)
{
    tex_map *m = tex_map_new(w, h, nc);
    tex_rng r;
    tex_rng_seed(&r, seed);
    for (size_t i = 0; m && i < tex_map_samples(m); i++)
        m->px[i] = (float)tex_rng_uniform(&r);
    return m;
}

static inline tex_map *unit_render_text(const char *text, int threads)
{
    struct tex_scene *s = tex_scene_parse(text, strlen(text), "test.scene");
    if (!s) {
        printf("# parse: %s\n", tex_errmsg());
        return NULL;
    }
    if (threads)
        s->settings.threads = threads;
    tex_map *m = tex_render(s, NULL, NULL);
    if (!m)
        printf("# render: %s\n", tex_errmsg());
    tex_scene_free(s);
    return m;
}

#endif
