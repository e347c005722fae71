// kdtree.cpp - FLANN's single kd-tree behind kdtree.h: the index and searches its C API
// makes for FLANN_INDEX_KDTREE_SINGLE on Euclidean distance, with the same parameters.
//
// FLANN's util/params.h includes <iostream>, whose static initialiser would start
// libstdc++'s locales in every tool before main; only its unused print_params names
// std::cout, so the header is kept out and cout declared.
#define _GLIBCXX_IOSTREAM 1
#include <ostream>
namespace std {
extern ostream cout;
}
#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <cmath>
#include <new>

#include "base/error.h"
#include "base/kdtree.h"

template <typename T> using tree_of = flann::KDTreeSingleIndex<flann::L2<T>>;

struct tex_kdtree {
    tree_of<float> *f; // one of the two, by the points' type
    tree_of<double> *d;
    double *wide;      // float points whose splits overflow a float, widened (d holds them)
};

template <typename T> static tree_of<T> *build(const T *pts, long n, int dim, int leaf)
{
    try {
        flann::IndexParams p;
        p["leaf_max_size"] = leaf;
        // FLANN reads the rows through a non-const matrix but does not write them
        auto *ix = new tree_of<T>(flann::Matrix<T>(const_cast<T *>(pts), n, dim), p);
        ix->buildIndex();
        return ix;
    } catch (std::bad_alloc &) {
        tex_error("out of memory for the kd-tree of %ld points", n);
    } catch (std::exception &e) {
        tex_error("FLANN could not build the kd-tree: %s", e.what());
    }
    return nullptr;
}

// The search parameters of FLANN's C API (create_search_params) as callers set them
static flann::SearchParams search_params(float eps, int sorted)
{
    flann::SearchParams sp(flann::FLANN_CHECKS_UNLIMITED, eps, sorted != 0);
    sp.max_neighbors = -1;
    sp.cores = 1;
    return sp;
}

template <typename T>
static int knn(const tree_of<T> *ix, const T *q, int nq, int k, float eps, int sorted, int *ind,
               T *d2)
{
    if (!ix)
        return tex_error("kd-tree search: the tree holds points of another type");
    try {
        flann::Matrix<int> mi(ind, nq, k);
        flann::Matrix<T> md(d2, nq, k);
        ix->knnSearch(flann::Matrix<T>(const_cast<T *>(q), nq, ix->veclen()), mi, md, k,
                      search_params(eps, sorted));
        return 0;
    } catch (std::bad_alloc &) {
        return tex_error("out of memory in a kd-tree search");
    } catch (std::exception &e) {
        return tex_error("FLANN could not search the kd-tree: %s", e.what());
    }
}

// A tree of T's points in its slot
template <typename T>
static tex_kdtree *new_tree(const T *pts, long n, int dim, int leaf, tree_of<T> *tex_kdtree::*slot)
{
    tex_kdtree *t = new (std::nothrow) tex_kdtree{nullptr, nullptr, nullptr};
    if (!t) {
        tex_error("out of memory");
        return nullptr;
    }
    if (!(t->*slot = build(pts, n, dim, leaf))) {
        delete t;
        return nullptr;
    }
    return t;
}

// Whether FLANN's split of some axis, (min + max) / 2, or its span overflows a float (it then
// asserts that points lie on both sides of an infinite cut, and aborts)
static int splits_overflow(const float *pts, long n, int dim)
{
    for (int j = 0; j < dim; j++) {
        float lo = pts[j], hi = pts[j];
        for (long i = 1; i < n; i++)
            lo = pts[i * dim + j] < lo ? pts[i * dim + j] : lo,
            hi = pts[i * dim + j] > hi ? pts[i * dim + j] : hi;
        if (!std::isfinite(lo + hi) || !std::isfinite(hi - lo))
            return 1;
    }
    return 0;
}

tex_kdtree *tex_kdtree_new_f(const float *pts, long n, int dim, int leaf)
{
    if (!splits_overflow(pts, n, dim))
        return new_tree(pts, n, dim, leaf, &tex_kdtree::f);
    // such points in doubles: the same neighbours, the splits finite
    double *w = new (std::nothrow) double[(size_t)n * dim];
    if (!w) {
        tex_error("out of memory");
        return nullptr;
    }
    for (size_t i = 0; i < (size_t)n * dim; i++)
        w[i] = pts[i];
    tex_kdtree *t = new_tree(w, n, dim, leaf, &tex_kdtree::d);
    if (!t)
        delete[] w;
    else
        t->wide = w;
    return t;
}

tex_kdtree *tex_kdtree_new_d(const double *pts, long n, int dim, int leaf)
{
    return new_tree(pts, n, dim, leaf, &tex_kdtree::d);
}

int tex_kdtree_knn_f(const tex_kdtree *t, const float *q, int nq, int k, float eps, int sorted,
                     int *ind, float *d2)
{
    if (!t->wide)
        return knn(t->f, q, nq, k, eps, sorted, ind, d2);
    size_t nd = (size_t)nq * t->d->veclen();
    double *wq = new (std::nothrow) double[nd], *wd = new (std::nothrow) double[(size_t)nq * k];
    int r = wq && wd ? 0 : tex_error("out of memory");
    for (size_t i = 0; !r && i < nd; i++)
        wq[i] = q[i];
    if (!r && (r = knn(t->d, wq, nq, k, eps, sorted, ind, wd)) == 0)
        for (size_t i = 0; i < (size_t)nq * k; i++)
            d2[i] = (float)wd[i];
    delete[] wq;
    delete[] wd;
    return r;
}

int tex_kdtree_knn_d(const tex_kdtree *t, const double *q, int nq, int k, float eps, int sorted,
                     int *ind, double *d2)
{
    return knn(t->d, q, nq, k, eps, sorted, ind, d2);
}

int tex_kdtree_radius_d(const tex_kdtree *t, const double *q, float r2, int max, int *ind,
                        double *d2)
{
    if (!t->d)
        return tex_error("kd-tree search: the tree holds points of another type");
    try {
        flann::Matrix<int> mi(ind, 1, max);
        flann::Matrix<double> md(d2, 1, max);
        return t->d->radiusSearch(flann::Matrix<double>(const_cast<double *>(q), 1, t->d->veclen()),
                                  mi, md, r2, search_params(0, 0));
    } catch (std::bad_alloc &) {
        return tex_error("out of memory in a kd-tree search");
    } catch (std::exception &e) {
        return tex_error("FLANN could not search the kd-tree: %s", e.what());
    }
}

void tex_kdtree_free(tex_kdtree *t)
{
    if (t) {
        delete t->f;
        delete t->d;
        delete[] t->wide;
        delete t;
    }
}
