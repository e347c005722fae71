/* vecmath.c - affine transforms: products, inverses and the scene's placements */
#include <math.h>

#include "render/vecmath.h"

void tex_xform_identity(tex_xform *t)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            t->m[i][j] = i == j;
}

void tex_xform_mul(tex_xform *r, const tex_xform *a, const tex_xform *b)
{
    tex_xform t;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++) {
            double s = j == 3 ? a->m[i][3] : 0;
            for (int k = 0; k < 3; k++)
                s += a->m[i][k] * b->m[k][j];
            t.m[i][j] = s;
        }
    }
    *r = t;
}

int tex_xform_invert(tex_xform *r, const tex_xform *a)
{
    const double(*m)[4] = a->m;
    double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    if (!(fabs(det) > 1e-300) || !isfinite(det))
        return -1;
    double id = 1 / det;
    tex_xform t;
    t.m[0][0] = c00 * id;
    t.m[1][0] = c01 * id;
    t.m[2][0] = c02 * id;
    t.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * id;
    t.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * id;
    t.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * id;
    t.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * id;
    t.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * id;
    t.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * id;
    for (int i = 0; i < 3; i++)
        t.m[i][3] = -(t.m[i][0] * m[0][3] + t.m[i][1] * m[1][3] + t.m[i][2] * m[2][3]);
    *r = t;
    return 0;
}

void tex_xform_translate(tex_xform *t, tex_v3 v)
{
    tex_xform_identity(t);
    t->m[0][3] = v.x, t->m[1][3] = v.y, t->m[2][3] = v.z;
}

void tex_xform_scale(tex_xform *t, tex_v3 v)
{
    tex_xform_identity(t);
    t->m[0][0] = v.x, t->m[1][1] = v.y, t->m[2][2] = v.z;
}

static void rot_axis(tex_xform *t, int axis, double deg)
{
    double a = deg * M_PI / 180, c = cos(a), s = sin(a);
    int i = (axis + 1) % 3, j = (axis + 2) % 3;
    tex_xform_identity(t);
    t->m[i][i] = c, t->m[i][j] = -s;
    t->m[j][i] = s, t->m[j][j] = c;
}

/* t after turns of r.x degrees about x, then r.y about y, then r.z about z */
void tex_xform_rotate(tex_xform *t, tex_v3 r)
{
    tex_xform a, b, c;
    rot_axis(&a, 0, r.x);
    rot_axis(&b, 1, r.y);
    rot_axis(&c, 2, r.z);
    tex_xform_mul(&a, &b, &a);
    tex_xform_mul(&a, &c, &a);
    tex_xform_mul(t, &a, t);
}

/* A frame taking the y axis to unit a. */
void tex_xform_frame(tex_xform *t, tex_v3 origin, tex_v3 a, double ylen, double r)
{
    tex_v3 y = tex_v3_norm(a);
    /* x: world x (or z) made perpendicular to y, so that an upright plane keeps
     * the world's x and z as its planar coordinates */
    tex_v3 h = fabs(y.x) < 0.9 ? tex_v3_make(1, 0, 0) : tex_v3_make(0, 0, 1);
    tex_v3 x = tex_v3_norm(tex_v3_madd(h, y, -tex_v3_dot(h, y))), z = tex_v3_cross(x, y);
    tex_xform_identity(t);
    for (int i = 0; i < 3; i++) {
        t->m[i][0] = tex_v3_get(x, i) * r;
        t->m[i][1] = tex_v3_get(y, i) * ylen;
        t->m[i][2] = tex_v3_get(z, i) * r;
        t->m[i][3] = tex_v3_get(origin, i);
    }
}
