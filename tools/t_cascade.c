/* t_cascade - fill the subregions of a region-id map with other maps */
#include <stdlib.h>
#include <string.h>

#include "ops/compose.h"
#include "textura.h"

struct opts {
    float fallback[4];
    int regions, resize;
};

static const struct tex_param rows[] = {
    TEX_COLOR_N("default", struct opts, fallback, 0, "#000000",
                "colour of the regions given no map"),
    TEX_INT(struct opts, regions, 0, 0, 0, 65535, "N",
            "treat IDS as region ids 1..N even without the textura:subregions attribute "
            "(0: use the attribute)"),
    TEX_ENUM(struct opts, resize, 0, "error", "error|scale|tile",
             "how region maps of another size than IDS are brought to its size"),
    {0}};

static const struct tex_tool tool = {
    "t_cascade", "IDS K=MAP...",
    "a cascade of texture maps: region K of the region-id map IDS is filled with MAP",
    TEX_OPT_OUTPUT | TEX_OPT_MAPS, rows, 2, -1};

/* The cascade of a band of the ids and of each region's map */
struct cascade_job {
    int n, nreg;
    const long *key;
    const tex_map **maps; /* nreg + 1 */
    const float *fallback;
};

static tex_map *cascade_band(tex_map *const *bands, void *arg)
{
    struct cascade_job *j = arg;

    for (int k = 0; k < j->n; k++)
        j->maps[j->key[k]] = bands[k + 1];
    return tex_cascade(bands[0], j->nreg, j->maps, j->fallback);
}

int main(int argc, char **argv)
{
    struct tex_common c;
    struct opts o;
    int i = tex_cli_parse(&tool, argc, argv, &c, &o), n = argc - i - 1, nreg;
    int stdin_used = !strcmp(argv[i], "-");
    tex_map *ids, **maps, *r;
    long *key = calloc(n, sizeof *key);

    if (!key)
        tex_usage_die("out of memory");
    /* Check every K=MAP before reading anything. */
    for (int k = 0; k < n; k++) {
        const char *a = argv[i + 1 + k], *eq = strchr(a, '=');
        char *e;
        key[k] = strtol(a, &e, 10);
        if (!eq || e != eq || e == a || key[k] < 1 || key[k] > 65535 || !eq[1])
            tex_usage_die("region maps are K=MAP with K in 1..65535 (got '%s')", a);
        if (!strcmp(eq + 1, "-") && stdin_used++)
            tex_usage_die("standard input (-) can be read only once");
        for (int j = 0; j < k; j++)
            if (key[j] == key[k])
                tex_usage_die("region %ld is given two maps", key[k]);
    }
    /* The ids and the maps on pipes or in scanline EXR files of one size go a band at a
     * time, in lockstep, to an output that takes rows; anything else is read whole. */
    tex_lockstep *l = tex_cli_lockstep_new(n + 1);
    const tex_map *head = tex_cli_lockstep_add(l, 0, argv[i]);
    nreg = o.regions ? o.regions : head->subregions;
    if (nreg < 1)
        tex_usage_die("%s has no textura:subregions attribute: it is not a region-id map (give "
                      "--regions N to use its values as ids)", argv[i]);
    for (int k = 0; k < n; k++)
        if (key[k] > nreg)
            tex_usage_die("region %ld does not exist: %s has regions 1..%d", key[k], argv[i],
                          nreg);
    if (!(maps = calloc(nreg + 1, sizeof *maps)))
        tex_usage_die("out of memory");
    for (int k = 0; k < n; k++)
        tex_cli_lockstep_add(l, k + 1, strchr(argv[i + 1 + k], '=') + 1);
    if (tex_cli_lockstep_streams(l, &c)) {
        struct cascade_job j = {n, nreg, key, (const tex_map **)maps, o.fallback};
        tex_cli_lockstep_write(l, &c, 0, cascade_band, &j);
        tex_cli_lockstep_free(l);
        free(maps), free(key), free(c.cmdline);
        return 0;
    }
    ids = tex_cli_lockstep_whole(l, 0);
    for (int k = 0; k < n; k++) {
        const char *a = strchr(argv[i + 1 + k], '=') + 1;
        tex_map *m = tex_cli_lockstep_whole(l, k + 1);
        if (!(maps[key[k]] = tex_fit(m, ids->w, ids->h, (enum tex_fit)o.resize, a)))
            tex_die();
        tex_map_free(m);
    }
    tex_cli_lockstep_free(l);
    if (!(r = tex_cascade(ids, nreg, (const tex_map *const *)maps, o.fallback)))
        tex_die();
    tex_cli_write(r, &c);
    tex_map_free(r);
    for (int k = 0; k <= nreg; k++)
        tex_map_free(maps[k]);
    free(maps);
    free(key);
    tex_map_free(ids);
    free(c.cmdline);
    return 0;
}
