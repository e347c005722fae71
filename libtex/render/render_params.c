/* render_params.c - the parameters of t_apply(5) scenes as rows
 *
 * Each block of the scene language is one table (param.h): the parser reads
 * the block through it, application-function results are clamped to its
 * ranges, and t_apply --help-scene and the lists of t_apply(5) print it.
 * Rows read by the parser's own code (a shading model, a material, a
 * falloff) are TEX_P_SPECIAL: they keep their help and range here, and name
 * their reader (render_scene.c).  Every default and range is written here or
 * in the constant the code shares (render_ct.h's, spectrum.h's), once.
 */
#include <math.h>
#include <stddef.h>

#include "lang/expr.h"
#include "render/anisotropic.h"
#include "render/hypertexture.h"
#include "render/render_ct.h"
#include "render/scene.h"

#define INF HUGE_VAL /* -INF, INF: a point or a direction, any numbers */
#define N3 (1u << 3)
#define KIND(k) (1u << (k))
#define STR_(x) #x
#define STR(x) STR_(x) /* a constant's value in help text */

const struct tex_param tex_settings_rows[] = {
    TEX_ROW("image", struct tex_scene, settings.w, TEX_P_INT, "640,480", 1, TEX_SCENE_MAX_SIDE, 2,
            0, "W H", "image size in pixels"),
    TEX_ROW("samples", struct tex_scene, settings.spp, TEX_P_INT, "1", 1, 4096, 1, 0, "N",
            "samples per pixel, stratified when N is a square"),
    TEX_ROW("depth", struct tex_scene, settings.depth, TEX_P_INT, "5", 0, 64, 1, 0, "N",
            "maximum recursion depth of reflected and refracted rays"),
    {"bailout", 0, TEX_P_REAL, offsetof(struct tex_scene, settings.bailout), 1.0 / 255, 0, 1, NULL,
     NULL, 0, "W", "rays weighing less than W are not traced (0: trace to the depth)", 1, 0, 0,
     NULL, NULL, NULL, NULL},
    TEX_ROW("threads", struct tex_scene, settings.threads, TEX_P_INT, "0", 0, 1024, 1, 0, "N",
            "OpenMP threads (0: one per core)"),
    TEX_SPECIAL("seed", 0, TEX_SEED_MAX, "0", "N",
                "seed of the sample positions and area-light jitter", tex_scene_read_seed),
    TEX_ROW_ENUM("filter", struct tex_scene, settings.filter, "on", "off|on",
                 "mip-mapped texture lookups"),
    TEX_ROW("ambient", struct tex_scene, ambient, TEX_P_FLOAT, "1,1,1", 0, 1e6, 3, 0, "R G B",
            "ambient light Ia (surfaces scale it by Ka)"),
    TEX_ROW("background", struct tex_scene, background, TEX_P_FLOAT, "0,0,0", 0, 1e6, 3, 0,
            "R G B", "colour of rays that hit nothing"),
    TEX_SPECIAL("colour", 1, TEX_COLOUR_MAX, "rgb", "rgb|spectral [N]",
                "the colour model: RGB, or N spectral bands (default " STR(TEX_BANDS_DEFAULT) ")",
                tex_scene_read_colour),
    TEX_SPECIAL("materials", 0, 0, NULL, "FILE",
                "read the materials database for the material statements that follow",
                tex_scene_read_materials),
    {0}};

const struct tex_param tex_camera_rows[] = {
    TEX_ROW("eye", struct tex_scene, eye, TEX_P_REAL, "0,0,-5", -INF, INF, 3, 0, "X Y Z",
            "position of the eye"),
    TEX_ROW("look", struct tex_scene, look, TEX_P_REAL, "0,0,0", -INF, INF, 3, 0, "X Y Z",
            "the point looked at (not the eye)"),
    TEX_ROW("up", struct tex_scene, up, TEX_P_REAL, "0,1,0", -INF, INF, 3, 0, "X Y Z",
            "the up direction (not along the view)"),
    TEX_ROW("fov", struct tex_scene, fov, TEX_P_REAL, "45", 0.01, 179, 1, 0, "DEG",
            "horizontal field of view in degrees"),
    {0}};

#define LIT(k) KIND(TEX_LIGHT_##k)
#define PLACED (LIT(POINT) | LIT(SPOT) | LIT(AREA))
#define LROW(name, f, T, d, lo, hi, n, meta, kinds, help)                                         \
    {name, 0, T, offsetof(struct tex_light, f), 0, lo, hi, d, NULL, 0, meta, help, n, 0, kinds,  \
     NULL, NULL, NULL, NULL}
const struct tex_param tex_light_rows[] = {
    LROW("colour", colour, TEX_P_FLOAT, "1,1,1", 0, 1e6, 3, "R G B", 0,
         "colour of the light (also color)"),
    LROW("intensity", intensity, TEX_P_REAL, "1", 0, 1e9, 1, "I", 0,
         "the colour, or the spectrum at luminance 1, times I"),
    TEX_SPECIAL("spectrum", 100, 1e6, NULL, "NAME|blackbody K",
                "a CIE illuminant (D65, A, E, F2...) or Planck's law at K kelvin, instead of "
                "the colour", tex_scene_read_spectrum),
    LROW("direction", direction, TEX_P_REAL, "0,1,0", -INF, INF, 3, "X Y Z", LIT(DISTANT),
         "distant: the direction from the scene towards the light"),
    LROW("position", pos, TEX_P_REAL, "0,0,0", -INF, INF, 3, "X Y Z", PLACED,
         "point, spot, area: where the light is (area: a corner)"),
    TEX_SPECIAL("falloff", 0, 1e9, "none", "none|square|C1 C2 C3",
                "point, spot, area: fatt = 1, 1/d^2 or min(1/(C1 + C2 d + C3 d^2), 1)",
                tex_scene_read_falloff, .kinds = PLACED),
    LROW("at", at, TEX_P_REAL, "0,0,0", -INF, INF, 3, "X Y Z", LIT(SPOT),
         "spot: the point the spot light is aimed at (required)"),
    LROW("angle", angle, TEX_P_REAL, "30", 0.01, 90, 1, "DEG", LIT(SPOT),
         "spot: half-angle of the cone in degrees"),
    LROW("exponent", exponent, TEX_P_REAL, "0", 0, 1e4, 1, "C", LIT(SPOT),
         "spot: the light falls off as cos^C of the angle to the axis"),
    LROW("edge1", edge1, TEX_P_REAL, "1,0,0", -INF, INF, 3, "X Y Z", LIT(AREA),
         "area: first edge of the parallelogram"),
    LROW("edge2", edge2, TEX_P_REAL, "0,0,1", -INF, INF, 3, "X Y Z", LIT(AREA),
         "area: second edge of the parallelogram"),
    LROW("samples", samples, TEX_P_INT, "4", 1, 32, 1, "N", LIT(AREA),
         "area: sampled on an N x N jittered grid"),
    {0}};

/* Rows 0..6 are the application-function parameters Ka..ior, in enum tex_sparam order. */
const struct tex_param tex_surface_rows[] = {
    TEX_ROW("Ka", struct tex_surface, ka, TEX_P_FLOAT, "0.1", 0, 1, 1, 0, "K",
            "ambient coefficient: the ambient term is Ka x Kd x Ia"),
    TEX_ROW("Kd", struct tex_surface, kd, TEX_P_FLOAT, "0.8", 0, 1, 3, (1u << 1) | N3, "R [G B]",
            "diffuse colour, a grey level or RGB"),
    TEX_ROW("Ks", struct tex_surface, ks, TEX_P_FLOAT, "0", 0, 1, 3, 1u << 1, "K",
            "specular coefficient (white highlights)"),
    TEX_ROW("n", struct tex_surface, n, TEX_P_REAL, "20", 0.1, 10000, 1, 0, "N",
            "Phong exponent of the highlights"),
    TEX_ROW("Kr", struct tex_surface, kr, TEX_P_REAL, "0", 0, 1, 1, 0, "K",
            "reflection coefficient"),
    TEX_ROW("Kt", struct tex_surface, kt, TEX_P_REAL, "0", 0, 1, 1, 0, "K",
            "transmission coefficient"),
    TEX_ROW("ior", struct tex_surface, ior, TEX_P_REAL, "1", 0.1, 10, 1, 0, "N",
            "index of refraction (a dielectric material gives its own)"),
    TEX_SPECIAL("model", 0, 0, "phong", "phong|cook-torrance|ward|ashikhmin-shirley",
                "the shading model (ward and ashikhmin-shirley: anisotropic, Ward 1992 and "
                "Ashikhmin-Shirley 2000, with Cook-Torrance's material and specular)",
                tex_scene_read_model),
    TEX_SPECIAL("character", 0, 0, NULL, TEX_CHARACTERS,
                "an optical character (thesis 4.4): a consistent Ka, Kd, Ks, n, Kr, Kt and ior "
                "for those of them the surface does not give",
                tex_scene_read_character),
    TEX_SPECIAL("material", 0, 0, NULL, "NAME",
                "optical constants n + ik from the materials database", tex_scene_read_material),
    TEX_SPECIAL("facets", TEX_CT_M_MIN, TEX_CT_M_MAX, "beckmann " STR(TEX_CT_M),
                "beckmann M|blinn NS",
                "Cook-Torrance microfacets: Beckmann's slope M (" STR(TEX_CT_M_MIN) ".." STR(
                    TEX_CT_M_MAX) ") or Blinn's exponent NS (0.." STR(TEX_CT_NS_MAX) "); beta DEG "
                "(" STR(TEX_CT_BETA_MIN) ".." STR(TEX_CT_BETA_MAX) ") instead of the number gives "
                "the lobe's half-maximum angle",
                tex_scene_read_facets),
    TEX_SPECIAL("specular", 0, 1, STR(TEX_CT_S), "S",
                "Cook-Torrance's, Ward's and Ashikhmin-Shirley's specular fraction (the diffuse "
                "one is 1 - S)",
                tex_scene_read_specular),
    TEX_ROW("alpha", struct tex_surface, alpha, TEX_P_REAL,
            STR(TEX_ANISO_ALPHA) "," STR(TEX_ANISO_ALPHA), TEX_ANISO_ALPHA_MIN,
            TEX_ANISO_ALPHA_MAX, 2, (1u << 1) | (1u << 2),
            "AU [AV]", "ward, ashikhmin-shirley: the roughness along the tangent and across it "
            "(one number: both), Beckmann's slopes; ashikhmin-shirley's exponents are "
            "2/A^2 - 2"),
    TEX_SPECIAL("tangent", 0, 0, "u", "u|v|X Y Z",
                "ward, ashikhmin-shirley: the tangent the highlight stretches across, the "
                "direction the shape's own mapping's u or v grows in, or a world direction "
                "(not along a plane's normal)", tex_scene_read_tangent),
    TEX_SPECIAL("apply", 0, 0, NULL, "TEXTURE { ... }",
                "apply a texture through application functions (any number, in order)",
                tex_scene_read_apply),
    TEX_SPECIAL("blend", 0, 0, NULL, "SURFACE",
                "the surface an application function's blend = h mixes in (shaded with its "
                "own textures, as a mixture of the two)", tex_scene_read_blend),
    {0}};

/* The targets beyond the surface's own rows (no storage: the renderer's per hit) */
#define TARGET(name, lo, hi, meta, help) {name, 0, TEX_P_REAL, 0, 0, lo, hi, NULL, NULL, 0, meta, \
                                          help, 0, 0, 0, NULL, NULL, NULL, NULL}
const struct tex_character tex_characters[] = {
    {"matte", {{"Ka", "0.1"}, {"Kd", "0.9"}, {"Ks", "0"}, {"n", "5"}, {"Kr", "0"}, {"Kt", "0"}}},
    {"glossy", {{"Ka", "0.1"}, {"Kd", "0.6"}, {"Ks", "0.4"}, {"n", "60"}, {"Kr", "0"},
                {"Kt", "0"}}},
    {"metal", {{"Ka", "0.1"}, {"Kd", "0.25"}, {"Ks", "0.45"}, {"n", "150"}, {"Kr", "0.3"},
               {"Kt", "0"}}},
    {"glass", {{"Ka", "0"}, {"Kd", "0.05"}, {"Ks", "0.15"}, {"n", "300"}, {"Kr", "0.1"},
               {"Kt", "0.7"}, {"ior", "1.5"}}},
    /* the thesis's varnished table (4.5): a uniform brightness of high specularity */
    {"varnished", {{"Ka", "0.1"}, {"Kd", "0.5"}, {"Ks", "0.3"}, {"n", "400"}, {"Kr", "0.2"},
                   {"Kt", "0"}}},
    {NULL, {{NULL}}}};

const struct tex_param tex_target_rows[] = {
    TARGET("bump", -1000, 1000, "S",
           "bump mapping: the normal tilts by S times the map's gradient across the surface"),
    TARGET("m", TEX_CT_M_MIN, TEX_CT_M_MAX, "M", "Cook-Torrance: Beckmann's slope of the microfacets"),
    TARGET("s", 0, 1, "S",
           "Cook-Torrance, ward, ashikhmin-shirley: the specular fraction (the diffuse one is "
           "1 - S)"),
    TARGET("blend", 0, 1, "W",
           "the weight of the surface named by the surface's blend (its light times W, this "
           "surface's times 1 - W)"),
    TARGET("normal", 0, 1, "R G B",
           "a tangent-space normal map (x along u, y against v, z out), encoded 0.5 + 0.5 n as "
           "t_filter normal and t_d_noise --normal write it"),
    TARGET("gradient", -1e6, 1e6, "DU DV",
           "bump mapping from a height gradient per texture unit (t_filter gradient; "
           "t_d_noise's times its frequency): N tilts by DU grad u + DV grad v"),
    TARGET("P", -1e6, 1e6, "D",
           "the point (table 4.1): moved D world units along the normal, where the textures "
           "after it are looked up and the light is shaded"),
    TARGET("au", TEX_ANISO_ALPHA_MIN, TEX_ANISO_ALPHA_MAX, "A",
           "ward, ashikhmin-shirley: the roughness along the tangent"),
    TARGET("av", TEX_ANISO_ALPHA_MIN, TEX_ANISO_ALPHA_MAX, "A",
           "ward, ashikhmin-shirley: the roughness across the tangent"),
    TARGET("angle", -36000, 36000, "DEG",
           "ward, ashikhmin-shirley: the tangent turned DEG degrees about the normal"),
    TARGET("tangent", 0, 1, "R G B",
           "ward, ashikhmin-shirley: a flow field, the tangent's direction in the surface "
           "encoded 0.5 + 0.5 d (R along u, G against v, as a normal map's; B unread)"),
    {0}};

const struct tex_param *tex_sparam_row(enum tex_sparam sp)
{
    return sp >= TEX_SP_BUMP ? &tex_target_rows[sp - TEX_SP_BUMP] : &tex_surface_rows[sp];
}

const struct tex_param tex_apply_rows[] = {
    TEX_ROW_ENUM("mapping", struct tex_apply, mapping, "natural",
                 "natural|sphere|cylinder|cone|box|planar|solid|world|wavy|cross",
                 "how a hit point finds its (u,v) or (u,v,w)"),
    TEX_ROW("axis", struct tex_apply, axis, TEX_P_REAL, "0,1,0", -1e9, 1e9, 3, 0, "X Y Z",
            "projections: the direction a planar, wavy, cylinder, cone or sphere mapping "
            "projects along (not zero)"),
    TEX_SPECIAL("translate", 0, 0, NULL, "X Y Z",
                "projections: move the texture by (X, Y, Z) relative to the object",
                tex_scene_read_translate),
    TEX_SPECIAL("rotate", 0, 0, NULL, "X Y Z",
                "projections: turn the texture X degrees about x, then Y about y, then Z about "
                "z, relative to the object", tex_scene_read_rotate),
    TEX_ROW("wave", struct tex_apply, wave, TEX_P_REAL, "0.1,1", -1e6, 1e6, 2, 0, "A L",
            "wavy: the planar projection swept along a sine path, u shifted by "
            "A sin(2 pi y / L) (L > 0)"),
    TEX_SPECIAL("cross", 0, 0, NULL, "TEXTURE",
                "cross: the second map, on the y-z plane; the first lies on x-y",
                tex_scene_read_cross),
    TEX_ROW_ENUM("combine", struct tex_apply, combine, "product", "product|min|max",
                 "cross: how the two maps' values combine"),
    TEX_ROW("window", struct tex_apply, u1, TEX_P_REAL, "0,0,1,1", 0, 1, 4, 0, "U1 V1 U2 V2",
            "where the map lies in (u,v), with U1 < U2 and V1 < V2"),
    TEX_ROW("repeat", struct tex_apply, nu, TEX_P_REAL, "1,1", 1e-3, 1e6, 2, 0, "NU NV",
            "times the map repeats inside the window (fixed-size placement)"),
    TEX_SPECIAL("stretch", 0, 0, NULL, NULL, "the map once across the window: repeat 1 1",
                tex_scene_read_stretch),
    TEX_ROW("size", struct tex_apply, size, TEX_P_REAL, "0,0", 0, 1e9, 2, 0, "W H",
            "natural mapping: the map's size in the object's units, repeating every W along u "
            "and H along v (non-elastic); 0 0: stretched once across the shape"),
    TEX_ROW("scale", struct tex_apply, scale, TEX_P_REAL, "1", 1e-9, 1e9, 1, 0, "S",
            "planar and world mappings: texture units per world unit"),
    TEX_SPECIAL("region", 1, 1 << 24, NULL, "N { ... }",
                "application functions for subregion N of the map only", tex_scene_read_region),
    {0}};

/* The shapes' words, each for its shapes only.  Their ranges take any number:
 * the parser checks them against each other ("sphere radius must be > 0",
 * "box needs min < max on every axis"), so the help states the conditions. */
#define SHP(k) KIND(TEX_SHAPE_##k)
#define OROW(name, f, d, n, meta, kinds, help)                                                    \
    {name, 0, TEX_P_REAL, offsetof(struct tex_shape_params, f), 0, -INF, INF, d, NULL, 0, meta,  \
     help, n, 0, kinds, NULL, NULL, NULL, NULL}
const struct tex_param tex_object_rows[] = {
    OROW("centre", centre, "0,0,0", 3, "X Y Z", SHP(SPHERE) | SHP(TORUS),
         "sphere, torus: the centre (also center)"),
    OROW("radius", radius, "1", 1, "R", SHP(SPHERE) | SHP(CYLINDER),
         "sphere, cylinder: the radius (> 0)"),
    OROW("min", min, "-1,-1,-1", 3, "X Y Z", SHP(BOX), "box: the corner of least x, y and z"),
    OROW("max", max, "1,1,1", 3, "X Y Z", SHP(BOX),
         "box: the opposite corner (above min on every axis)"),
    OROW("base", base, "0,0,0", 3, "X Y Z", SHP(CYLINDER) | SHP(CONE) | SHP(INF_CONE),
         "cylinder, cone: the centre of the base cap; inf_cone: a point on its axis"),
    OROW("top", top, "0,1,0", 3, "X Y Z", SHP(CYLINDER) | SHP(CONE) | SHP(INF_CONE),
         "cylinder, cone: the centre of the top cap (not the base); inf_cone: a second point "
         "on its axis, one map length along it from base"),
    OROW("radius1", radius1, "1", 1, "R0", SHP(CONE) | SHP(INF_CONE),
         "cone, inf_cone: the radius at the base (>= 0)"),
    OROW("radius2", radius2, "0", 1, "R1", SHP(CONE) | SHP(INF_CONE),
         "cone, inf_cone: the radius at the top (>= 0; not both radii 0)"),
    OROW("normal", normal, "0,1,0", 3, "X Y Z", SHP(PLANE),
         "plane: the normal n of the half-space n.x <= d (not zero)"),
    OROW("distance", distance, "0", 1, "D", SHP(PLANE),
         "plane: d, the plane's distance from the origin along n"),
    OROW("axis", axis, "0,1,0", 3, "X Y Z", SHP(TORUS),
         "torus: the axis the ring turns about (not zero)"),
    OROW("major", major, "1", 1, "R", SHP(TORUS),
         "torus: the radius of the circle the tube's centre runs round (>= 0)"),
    OROW("minor", minor, "0.25", 1, "R", SHP(TORUS), "torus: the radius of the tube (> 0)"),
    TEX_SPECIAL("surface", 0, 0, NULL, "NAME",
                "the surface, inherited by the parts of a CSG object that name none",
                tex_scene_read_surface),
    TEX_SPECIAL("translate", 0, 0, NULL, "X Y Z", "move the object by (X, Y, Z)",
                tex_scene_read_translate),
    TEX_SPECIAL("rotate", 0, 0, NULL, "X Y Z",
                "turn the object X degrees about x, then Y about y, then Z about z",
                tex_scene_read_rotate),
    TEX_SPECIAL("scale", 0, 0, NULL, "S | X Y Z",
                "scale the object by S, or by X, Y and Z along the axes (not 0)",
                tex_scene_read_scale),
    {0}};

const struct tex_param tex_environment_rows[] = {
    TEX_ROW("intensity", struct tex_environment, intensity, TEX_P_REAL, "1", 0, 1e9, 1, 0, "I",
            "the map's values times I"),
    TEX_ROW("rotate", struct tex_environment, rotate, TEX_P_REAL, "0,0,0", -1e6, 1e6, 3, 0,
            "X Y Z", "turn the map X degrees about x, then Y about y, then Z about z"),
    {0}};

/* hypertexture { }: over struct tex_hyper (hypertexture.h; marched by volume.c) */
#define HROW(name, f, d, lo, hi, meta, help) \
    TEX_ROW(name, struct tex_hyper, f, TEX_P_REAL, d, lo, hi, 1, 0, meta, help)
const struct tex_param tex_hyper_rows[] = {
    HROW("absorption", absorption, "1", 0, 1e6, "A",
         "light absorbed per unit length where the opacity is 1"),
    HROW("scattering", scattering, "0", 0, 1e6, "S",
         "light scattered per unit length where the opacity is 1 (single scattering toward "
         "each light, shadow rays through the volume)"),
    HROW("phase", phase, "0", -0.99, 0.99, "G",
         "Henyey-Greenstein's g: 0 isotropic, above 0 forward (brightest looking toward a "
         "light), below 0 backward"),
    HROW("step", step, "0.05", 1e-6, 1e6, "DT",
         "the march's longest step in world units (the pixel's footprint where wider)"),
    HROW("shadow-step", shadow_step, "0", 0, 1e6, "DT",
         "the step of shadow rays through the volume (0: twice step)"),
    HROW("tolerance", tolerance, "0.01", 1e-9, 1e6, "E",
         "the optical depth a step may change by: where the extinction changes by g per unit "
         "length, steps shrink to sqrt(E / g), down to a sixteenth of step"),
    HROW("jitter", jitter, "1", 0, 1, "J",
         "the share of a step its sample moves by a hash of the ray (0: the midpoint)"),
    HROW("ambient", ambient, "0.1", 0, 1e6, "K",
         "the scattered share of the ambient light (K x colour x Ia per unit of scattering)"),
    {0}};

/* The application functions of a hypertexture, in enum tex_hyper_fn order (no storage; the
 * default is what an absent function gives) */
#define HFN(name, d, lo, hi, meta, help) {name, 0, TEX_P_REAL, 0, 0, lo, hi, d, NULL, 0, meta, \
                                          help, 0, 0, 0, NULL, NULL, NULL, NULL}
const struct tex_param tex_hyper_fn_rows[] = {
    HFN("density", "D", 0, 1, "H",
        "H, Perlin and Hoffert's modulated density (also written H = ...)"),
    HFN("opacity", "H", 0, 1e6, "O",
        "the extinction's share: absorption and scattering times O per unit length"),
    HFN("colour", "1", 0, 1, "R G B", "the scattered light's colour, the albedo (also color)"),
    HFN("emission", "0", 0, 1e6, "R G B", "light emitted per unit length, a fire's"),
    {0}};

/* A density's words (hypertexture.h): KIND bits of enum tex_hdensity_kind */
#define HD(k) KIND(TEX_HD_##k)
#define DROW(name, f, d, lo, hi, n, meta, kinds, help)                                           \
    {name, 0, TEX_P_REAL, offsetof(struct tex_hdensity, f), 0, lo, hi, d, NULL, 0, meta, help,  \
     n, 0, kinds, NULL, NULL, NULL, NULL}
const struct tex_param tex_hdensity_rows[] = {
    DROW("centre", centre, "0,0,0", -INF, INF, 3, "X Y Z", HD(SPHERE),
         "sphere: the centre c (also center)"),
    DROW("radius", radius, "1", -INF, INF, 1, "R", HD(SPHERE) | HD(CYLINDER),
         "sphere, cylinder: the radius r (> 0)"),
    DROW("soft", soft, "0", 0, 1e9, 1, "S",
         HD(SPHERE) | HD(BOX) | HD(CYLINDER),
         "the soft region's width s, centred on the surface (sphere: at most 2 r); 0: a hard "
         "edge"),
    DROW("min", min, "-1,-1,-1", -INF, INF, 3, "X Y Z", HD(BOX), "box: the corner of least x, y, z"),
    DROW("max", max, "1,1,1", -INF, INF, 3, "X Y Z", HD(BOX),
         "box: the opposite corner (above min on every axis)"),
    DROW("base", base, "0,0,0", -INF, INF, 3, "X Y Z", HD(CYLINDER),
         "cylinder: the centre of the base cap"),
    DROW("top", top, "0,1,0", -INF, INF, 3, "X Y Z", HD(CYLINDER),
         "cylinder: the centre of the top cap (not the base)"),
    {0}};

const struct tex_scene_block tex_scene_blocks[] = {
    {"settings", tex_settings_rows}, {"camera", tex_camera_rows}, {"light", tex_light_rows},
    {"environment", tex_environment_rows},
    {"texture", tex_field_rows},     {"surface", tex_surface_rows}, {"apply", tex_apply_rows},
    {"targets", tex_target_rows},
    {"object", tex_object_rows},     {"hypertexture", tex_hyper_rows},
    {"hyperfunctions", tex_hyper_fn_rows}, {"density", tex_hdensity_rows}, {NULL, NULL}};

/* lang/expr.h's functions, then the scene's own palette(NAME, x) */
int tex_scene_function(int i, struct tex_scene_word *w)
{
    int n = 0;
    while (tex_expr_funcs[n].name)
        n++;
    if (i < 0 || i > n)
        return 0;
    if (i == n)
        *w = (struct tex_scene_word){"palette", "NAME, x",
                                     "the colour of palette NAME at the mean of x in [0, 1]"};
    else
        *w = (struct tex_scene_word){tex_expr_funcs[i].name, tex_expr_funcs[i].args,
                                     tex_expr_funcs[i].help};
    return 1;
}
