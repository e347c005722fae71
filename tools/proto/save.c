/* save.c - saving into the folder t_proto serves: plain names only, never through a
 * symlink, written whole or not at all */
#define _GNU_SOURCE /* renameat2 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "textura.h"
#include "proto.h"

/* The map and project files the editor may write */
const char *const map_exts[] = {"png", "exr", "tif", "pfm", NULL};
static const char *const proj_exts[] = {"tproj", "txt", NULL};

/* NAME.pal, a plain file in the working folder (the palette editor saves there). */
int is_saved_palette(const char *name)
{
    struct stat st;
    size_t n = strlen(name);
    if (n < 5 || n > 100 || strcmp(name + n - 4, ".pal") || name[0] == '.' || strchr(name, '/'))
        return 0;
    for (const char *s = name; *s; s++)
        if (!(*s == '.' || *s == '_' || *s == '-' || (*s >= '0' && *s <= '9') ||
              (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z')))
            return 0;
    return fstatat(proto.workfd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
}

/* A plain name in the working folder: no folder part, no "..", no leading dot, not a
 * symlink; ext one of the allowed extensions for the kind. */
int save_name(struct pipeline *pl, const char *name, const char *const *exts)
{
    struct stat st;
    const char *dot;
    if (!name || !*name || strlen(name) > 100 || strchr(name, '/') || name[0] == '.' ||
        strstr(name, ".."))
        return fail(pl, "save names are plain file names in the working folder (got '%.40s')",
                    name ? name : "");
    for (const char *s = name; *s; s++)
        if (!(*s == '.' || *s == '_' || *s == '-' || (*s >= '0' && *s <= '9') ||
              (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z')))
            return fail(pl, "save names use letters, digits, '.', '_' and '-' (got '%.40s')",
                        name);
    if (fstatat(proto.workfd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
        return fail(pl, "'%s' exists and is not a plain file (a symlink or a folder)", name);
    if (!(dot = strrchr(name, '.')))
        return fail(pl, "'%s' needs an extension", name);
    for (int i = 0; exts[i]; i++)
        if (!strcmp(dot + 1, exts[i]))
            return 0;
    return fail(pl, "'%s': the extension must be one of the kind's (%s...)", name, exts[0]);
}

/* The last stage writes name's format on standard output (the shell redirects it). */
int to_file(struct pipeline *pl, const char *name)
{
    return arg(pl, word(pl, "--format=%s", strrchr(name, '.') + 1));
}

/* Write text to name in the working folder, atomically, never through a symlink, and over
 * an existing file only when the request says overwrite=1 (the page asks first): else
 * pl->exists is set. */
static int save_text(struct pipeline *pl, const char *name, const char *text, size_t n)
{
    char tmp[160];
    snprintf(tmp, sizeof tmp, ".%s.%d.tmp", name, (int)getpid());
    int fd =
        openat(proto.workfd, tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
        return fail(pl, "cannot write '%s': %s", name, strerror(errno));
    int ok = write(fd, text, n) == (ssize_t)n;
    ok &= close(fd) == 0;
    if (ok && renameat2(proto.workfd, tmp, proto.workfd, name,
                        pl->overwrite ? 0 : RENAME_NOREPLACE) < 0) {
        int e = errno;
        unlinkat(proto.workfd, tmp, 0);
        if (e == EEXIST) {
            pl->exists = 1;
            return fail(pl, "'%s' exists: saving again replaces it (overwrite=1)", name);
        }
        return fail(pl, "cannot write '%s': %s", name, strerror(e));
    }
    if (!ok) {
        unlinkat(proto.workfd, tmp, 0);
        return fail(pl, "cannot write '%s'", name);
    }
    return 0;
}

/* /api/save: a map, palette, command line, scene or project into the work directory */
unsigned api_save(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out)
{
    struct tex_str b = {0};
    static const char *const pal_exts[] = {"pal", NULL};
    static const char *const sh_exts[] = {"sh", "txt", NULL};
    static const char *const scene_exts[] = {"scene", "txt", NULL};
    const char *kind = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "kind");
    const char *name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "name");
    const char *body = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "text");
    const char *over = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "overwrite");
    int size = get_size(c, pl, 512), rc = -1;
    kind = kind ? kind : "";
    pl->overwrite = over && !strcmp(over, "1");
    if (!strcmp(kind, "palette") || !strcmp(kind, "project")) {
        /* text the page made: a palette file, or a project (the query) */
        if (save_name(pl, name, kind[1] == 'a' ? pal_exts : proj_exts) == 0) {
            if (!body || strlen(body) > MAX_GRAPH)
                fail(pl, "the %s's text is missing or longer than %d bytes", kind, MAX_GRAPH);
            else if (kind[1] == 'a') {
                tex_palette *p = tex_palette_parse(body, strlen(body), name);
                rc = p ? save_text(pl, name, body, strlen(body)) : fail(pl, "%s", tex_errmsg());
                tex_palette_free(p);
            } else if (project_check(pl, body) == 0) { /* loads back: JSON, its graph runs */
                rc = save_text(pl, name, body, strlen(body));
            }
        }
    } else if (!strcmp(kind, "graph")) {
        /* a graph's export: the script, the t_compose script or the scene */
        const char *form = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "form");
        static const char *const tc_exts[] = {"tc", "txt", NULL};
        form = form ? form : "sh";
        if (save_name(pl, name, form[0] == 's' ? sh_exts : form[0] == 'c' ? tc_exts
                                                                          : scene_exts) == 0 &&
            graph_export(c, pl, form, MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND,
                                                                  "map"), &b) == 0) {
            rc = save_text(pl, name, b.s, b.n);
        }
    } else if (size < 0 || build(c, pl, size) < 0) {
        ;
    } else if (!strcmp(kind, "map")) {
        /* the map as the command line makes it: standard output, into the file */
        if (save_name(pl, name, map_exts) == 0 && to_file(pl, name) == 0 && !run(pl, out))
            rc = save_text(pl, name, out->s, out->n);
        free(out->s);
        *out = (struct tex_str){0};
    } else if (!strcmp(kind, "cmdline") || !strcmp(kind, "scene")) {
        if (save_name(pl, name, kind[0] == 'c' ? sh_exts : scene_exts) == 0) {
            const char *map = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "map");
            if (kind[0] == 's') { /* the scene's texture statement, its map from standard input */
                tex_str_add(&b, "# ");
                cmdline(pl, &b);
                tex_str_add(&b, " | t_apply THIS.scene\ntexture map file -\n");
            } else if (save_name(pl, map, map_exts) == 0 && to_file(pl, map) == 0) {
                tex_str_add(&b, "#!/bin/sh\n");
                cmdline(pl, &b);
                tex_str_add(&b, " > %s\n", map);
            }
            rc = b.n ? save_text(pl, name, b.s, b.n) : -1;
        }
    } else {
        fail(pl, "kind must be map, palette, cmdline, scene, project or graph (got '%.20s')",
             kind);
    }
    if (rc == 0)
        tex_str_add(out, "saved %s", name);
    free(b.s);
    return rc == 0 ? 200 : pl->exists ? 409 : 400;
}

/* /api/load: a project's text into out */
unsigned api_load(struct MHD_Connection *c, struct pipeline *pl, struct tex_str *out)
{
    unsigned code = 400;
    const char *name = MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, "name");
    if (save_name(pl, name, proj_exts) == 0) {
        int fd = openat(proto.workfd, name, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
        tex_buf tb = {0};
        if (fd < 0 || tex_read_fd(fd, &tb, name) < 0 || tb.len > MAX_GRAPH)
            fail(pl, "cannot read project '%s'", name);
        else {
            tex_str_bytes(out, (const char *)tb.data, tb.len);
            code = 200;
        }
        if (fd >= 0)
            close(fd);
        tex_buf_free(&tb);
    }
    return code;
}
