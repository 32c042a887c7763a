/*
 * PQP_Internal.h -- PQP 1.3's classes (PQP_Model and the query results), as pqp-rs provides them.
 *
 * Every public data member and member function of PQP 1.3's classes is here, with its meaning.
 * The classes are header-only wrappers over the C interface <pqp/pqp.h>; include PQP.h, which
 * includes this file and declares the queries.
 *
 * PQP_Model's internals (tris, b, child(n), last_tri) are a view that the library builds the first
 * time a program reads them and keeps until the model is rebuilt or destroyed: a program that never
 * reads them pays no memory for them. tris, b and last_tri are small objects that convert to Tri *
 * and BV * wherever a pointer is expected (m.tris[i], m.b + k, Tri *t = m.tris, m.b->R,
 * memcpy(dst, m.tris, ...)); in a template that deduces one type from both m.tris and a Tri *
 * (std::vector<Tri> v(m.tris, m.tris + n)), write &m.tris[0]. Writes through these pointers change
 * the view, not the model that queries use.
 */
#ifndef PQP_INTERNAL_H
#define PQP_INTERNAL_H

#ifndef __cplusplus
#error "PQP_Internal.h is a C++ header; C code includes <pqp/pqp.h>"
#endif

#include "BV.h"
#include "PQP_Compile.h"
#include "Tri.h"
#include "pqp/pqp_cxx.h"

#include <limits.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <new>
#if __cplusplus >= 201103L
#include <utility>
#endif

class PQP_Model;

namespace pqp_detail {

/* A C handle owned by a C++ object: made by Create (again on demand, if allocation failed or the
 * object was moved from) and freed by Destroy. A copy of the owner starts with a handle of its own
 * (handles keep only what speeds up the next query: the answer lives in the owner's members);
 * from C++11 a move takes the handle along. */
template <typename H, H *(*Create)(), void (*Destroy)(H *)> class owned_handle
{
public:
    owned_handle() : h_(Create()) {}
    owned_handle(const owned_handle &) : h_(Create()) {}
    owned_handle &operator=(const owned_handle &) { return *this; }
#if __cplusplus >= 201103L
    owned_handle(owned_handle &&other) noexcept : h_(other.h_) { other.h_ = NULL; }
    owned_handle &operator=(owned_handle &&other) noexcept
    {
        std::swap(h_, other.h_);
        return *this;
    }
#endif
    ~owned_handle() { Destroy(h_); }

    /* The handle, made now if there is none; NULL only if it cannot be allocated. */
    H *get()
    {
        if (h_ == NULL) h_ = Create();
        return h_;
    }
    /* The handle as it is (NULL if there is none). */
    const H *peek() const { return h_; }

private:
    H *h_;
};

/* A 64-bit counter as PQP's int (saturating). */
inline int clamp_to_int(int64_t v)
{
    if (v > INT_MAX) return INT_MAX;
    if (v < INT_MIN) return INT_MIN;
    return static_cast<int>(v);
}

/* The library's view of a model (pqp_model_tris, pqp_model_bvs) in the records of Tri.h and BV.h,
 * which have the C records' layout for the matching PQP_REAL (double: pqp_tri, pqp_bv; float:
 * pqp_tri_float, pqp_bv_float). NULL when the model has none (no handle, or for b, not built).
 * Partial specialisations, so that only the one for PQP_REAL is compiled; the layout assertions
 * name Unused to be checked only there. */
template <typename Real, typename Unused> struct model_view;

template <typename Unused> struct model_view<double, Unused>
{
    static Tri *tris(const pqp_model *m)
    {
#if __cplusplus >= 201103L
        static_assert(sizeof(Tri) + 0 * sizeof(Unused *) == sizeof(pqp_tri),
                      "Tri has pqp_tri's layout");
#endif
        const pqp_tri *t = NULL;
        int n = 0;
        if (m == NULL || pqp_model_tris(m, &t, &n) != PQP_OK) return NULL;
        return reinterpret_cast<Tri *>(const_cast<pqp_tri *>(t));
    }
    static BV *bvs(const pqp_model *m)
    {
#if __cplusplus >= 201103L
        static_assert(sizeof(BV) + 0 * sizeof(Unused *) == sizeof(pqp_bv),
                      "BV has pqp_bv's layout");
#endif
        const pqp_bv *b = NULL;
        int n = 0;
        if (m == NULL || pqp_model_bvs(m, &b, &n) != PQP_OK) return NULL;
        return reinterpret_cast<BV *>(const_cast<pqp_bv *>(b));
    }
};

template <typename Unused> struct model_view<float, Unused>
{
    static Tri *tris(const pqp_model *m)
    {
#if __cplusplus >= 201103L
        static_assert(sizeof(Tri) + 0 * sizeof(Unused *) == sizeof(pqp_tri_float),
                      "Tri has pqp_tri_float's layout");
#endif
        const pqp_tri_float *t = NULL;
        int n = 0;
        if (m == NULL || pqp_model_tris_float(m, &t, &n) != PQP_OK) return NULL;
        return reinterpret_cast<Tri *>(const_cast<pqp_tri_float *>(t));
    }
    static BV *bvs(const pqp_model *m)
    {
#if __cplusplus >= 201103L
        static_assert(sizeof(BV) + 0 * sizeof(Unused *) == sizeof(pqp_bv_float),
                      "BV has pqp_bv_float's layout");
#endif
        const pqp_bv_float *b = NULL;
        int n = 0;
        if (m == NULL || pqp_model_bvs_float(m, &b, &n) != PQP_OK) return NULL;
        return reinterpret_cast<BV *>(const_cast<pqp_bv_float *>(b));
    }
};

typedef model_view<PQP_REAL, void> view;

/* What PQP_Model::tris, b and last_tri are: a pointer read from the library's view of the model
 * whose handle is at *handle, each time it is used. Kind is 0 for tris, 1 for b, 2 for last_tri
 * (the first triangle of a built model, NULL before). */
template <typename Record, int Kind> class view_pointer
{
public:
    operator Record *() const { return get(); }
    Record *operator->() const { return get(); }

private:
    friend class ::PQP_Model;
    explicit view_pointer(pqp_model *const *handle) : handle_(handle) {}
    /* Assigning a model does not re-aim its members (PQP_Model's operator= copies the model). */
    view_pointer &operator=(const view_pointer &) { return *this; }

    Record *get() const;

    pqp_model *const *handle_;
};

template <> inline Tri *view_pointer<Tri, 0>::get() const
{
    return view::tris(*handle_);
}

template <> inline BV *view_pointer<BV, 1>::get() const
{
    return view::bvs(*handle_);
}

template <> inline Tri *view_pointer<Tri, 2>::get() const
{
    return pqp_model_build_state(*handle_) == PQP_BUILD_STATE_PROCESSED ? view::tris(*handle_)
                                                                          : NULL;
}

/* Poses and relative poses in double, as the C interface takes them. */
inline void relative_pose(PQP_REAL R[3][3], PQP_REAL T[3], const double R1[9], const double T1[3],
                          const double R2[9], const double T2[3])
{
    /* PQP 1.3 stores [R, T] = [R1, T1]^-1 [R2, T2] = [R1^T R2, R1^T (T2 - T1)]: model 2's frame in
     * model 1's. */
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            double s = 0.0;
            for (int k = 0; k < 3; k++) s += R1[3 * k + i] * R2[3 * k + j];
            R[i][j] = (PQP_REAL)s;
        }
        double t = 0.0;
        for (int k = 0; k < 3; k++) t += R1[3 * k + i] * (T2[k] - T1[k]);
        T[i] = (PQP_REAL)t;
    }
}

inline void identity(PQP_REAL R[3][3], PQP_REAL T[3])
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) R[i][j] = (PQP_REAL)(i == j ? 1 : 0);
        T[i] = 0;
    }
}

inline void copy3(PQP_REAL out[3], const PQP_REAL v[3])
{
    for (int i = 0; i < 3; i++) out[i] = v[i];
}

inline void copy_pose(PQP_REAL R[3][3], PQP_REAL T[3], const PQP_REAL R0[3][3],
                      const PQP_REAL T0[3])
{
    for (int i = 0; i < 3; i++) copy3(R[i], R0[i]);
    copy3(T, T0);
}

} /* namespace pqp_detail */

/* A triangle model. Build it with BeginModel, AddTri (once per triangle) and EndModel; it can then
 * be queried, from any number of threads at once, and is immutable until the next BeginModel.
 * Copies are deep and independent (PQP 1.3's were shallow and freed the same arrays twice). */
class PQP_Model
{
public:
    /* 0 empty (fresh or cleared), 1 begun (triangles being added), 2 built (EndModel succeeded). */
    int build_state;

    /* The triangles in the order added, with their ids (PQP 1.3 reordered them; pqp-rs does not).
     * Converts to Tri *; NULL on a model with no triangles. */
    pqp_detail::view_pointer<Tri, 0> tris;
    /* Triangles added so far. */
    int num_tris;
    /* Room PQP 1.3 would have reserved for triangles: the BeginModel hint (8 if < 1), doubled when
     * full, and num_tris after EndModel. The library manages its own storage; this is informative. */
    int num_tris_alloced;

    /* The hierarchy (see BV.h): 2 num_tris - 1 volumes after EndModel. Converts to BV *; NULL
     * before EndModel. */
    pqp_detail::view_pointer<BV, 1> b;
    /* 2 num_tris - 1 after EndModel, else 0. */
    int num_bvs;
    int num_bvs_alloced;

    /* PQP 1.3 kept the last closest triangle here, written by every distance query, which made a
     * model unsafe to share between threads. pqp-rs's queries do not write to models: this is the
     * first triangle of a built model (as in PQP 1.3 right after EndModel) and NULL before. The
     * closest triangles of a query are in its result (pqp_distance_result_triangles). */
    pqp_detail::view_pointer<Tri, 2> last_tri;

    /* Volume n of the hierarchy (&b[n]); NULL before EndModel. */
    BV *child(int n)
    {
        BV *bvs = b;
        return bvs != NULL ? bvs + n : NULL;
    }

    PQP_Model() : tris(&pqp_handle_), b(&pqp_handle_), last_tri(&pqp_handle_), pqp_handle_(NULL)
    {
        pqp_handle_ = pqp_model_create();
        sync_counts();
    }

    PQP_Model(const PQP_Model &other)
        : tris(&pqp_handle_), b(&pqp_handle_), last_tri(&pqp_handle_), pqp_handle_(NULL)
    {
        copy_from(other);
    }

    PQP_Model &operator=(const PQP_Model &other)
    {
        if (this != &other) {
            pqp_model_destroy(pqp_handle_);
            pqp_handle_ = NULL;
            copy_from(other);
        }
        return *this;
    }

#if __cplusplus >= 201103L
    PQP_Model(PQP_Model &&other) noexcept
        : tris(&pqp_handle_), b(&pqp_handle_), last_tri(&pqp_handle_), pqp_handle_(NULL)
    {
        take_from(other);
    }

    PQP_Model &operator=(PQP_Model &&other) noexcept
    {
        if (this != &other) {
            pqp_model_destroy(pqp_handle_);
            pqp_handle_ = NULL;
            take_from(other);
        }
        return *this;
    }
#endif

    ~PQP_Model() { pqp_model_destroy(pqp_handle_); }

    /* Starts the model; n is a capacity hint. On a model already begun or built, clears it, begins
     * it and returns PQP_ERR_BUILD_OUT_OF_SEQUENCE (as PQP 1.3). */
    int BeginModel(int n = 8)
    {
        if (!ensure()) return PQP_ERR_MODEL_OUT_OF_MEMORY;
        int rc = pqp_model_begin(pqp_handle_, n);
        num_tris_alloced = n > 0 ? n : 8;
        sync_counts();
        return rc;
    }

    /* Adds a triangle with the caller's id (reported by queries). Before BeginModel it begins the
     * model (PQP_OK); after EndModel it is ignored and returns PQP_ERR_BUILD_OUT_OF_SEQUENCE. A
     * vertex with a NaN, infinite or huge (beyond 1e150) coordinate is refused with
     * PQP_ERR_NONFINITE_COORDINATE: the triangle is not added, and the model is begun (if it was
     * empty) and otherwise as it was. NULL vertices: PQP_ERR_NULL_POINTER, nothing changes. */
    int AddTri(const PQP_REAL *p1, const PQP_REAL *p2, const PQP_REAL *p3, int id)
    {
        if (p1 == NULL || p2 == NULL || p3 == NULL) return PQP_ERR_NULL_POINTER;
        if (!ensure()) return PQP_ERR_MODEL_OUT_OF_MEMORY;
        double a[3], c[3], e[3];
        pqp_detail::widen3(a, p1);
        pqp_detail::widen3(c, p2);
        pqp_detail::widen3(e, p3);
        if (build_state == PQP_BUILD_STATE_EMPTY) num_tris_alloced = 8;
        int rc = pqp_model_add_tri(pqp_handle_, a, c, e, id);
        sync_counts();
        while (num_tris > num_tris_alloced && num_tris_alloced < INT_MAX / 2) num_tris_alloced *= 2;
        return rc;
    }

    /* Builds the model's hierarchy; after it the model can be queried. PQP_ERR_BUILD_EMPTY_MODEL
     * if no triangle was added (the model stays unbuilt), PQP_ERR_BUILD_OUT_OF_SEQUENCE if it is
     * already built (as PQP 1.3). */
    int EndModel()
    {
        if (!ensure()) return PQP_ERR_MODEL_OUT_OF_MEMORY;
        int rc = pqp_model_end(pqp_handle_);
        sync_counts();
        return rc;
    }

    /* Bytes held by the model (clamped to INT_MAX), including the view of tris and b once read.
     * Never prints, whatever msg is. */
    int MemUsage(int msg)
    {
        (void)msg;
        uint64_t bytes = pqp_model_memory_usage(pqp_handle_);
        return bytes > static_cast<uint64_t>(INT_MAX) ? INT_MAX : static_cast<int>(bytes);
    }

    /* pqp-rs extension: the C handle (NULL only if it could not be allocated). */
    pqp_model *pqp_handle() { return pqp_handle_; }
    const pqp_model *pqp_handle() const { return pqp_handle_; }

private:
    /* A handle to work on: made again if allocation failed before, or after a move. */
    bool ensure()
    {
        if (pqp_handle_ == NULL) pqp_handle_ = pqp_model_create();
        return pqp_handle_ != NULL;
    }

    /* The counters PQP 1.3 kept, from the library's state. */
    void sync_counts()
    {
        build_state = pqp_model_build_state(pqp_handle_);
        num_tris = pqp_model_num_tris(pqp_handle_);
        bool built = build_state == PQP_BUILD_STATE_PROCESSED;
        num_bvs = built ? 2 * num_tris - 1 : 0;
        num_bvs_alloced = num_bvs;
        if (built) num_tris_alloced = num_tris;
        if (build_state == PQP_BUILD_STATE_EMPTY) num_tris_alloced = 0;
    }

    void copy_from(const PQP_Model &other)
    {
        /* Like a standard container's copy, this throws std::bad_alloc when memory runs out. */
        if (other.pqp_handle_ != NULL && pqp_model_clone(&pqp_handle_, other.pqp_handle_) != PQP_OK)
            throw std::bad_alloc();
        num_tris_alloced = other.num_tris_alloced;
        sync_counts();
    }

#if __cplusplus >= 201103L
    void take_from(PQP_Model &other)
    {
        pqp_handle_ = other.pqp_handle_;
        num_tris_alloced = other.num_tris_alloced;
        other.pqp_handle_ = NULL;
        other.sync_counts();
        sync_counts();
    }
#endif

    pqp_model *pqp_handle_;
};

/* One colliding triangle pair: the ids given to AddTri. */
struct CollisionPair
{
    int id1;
    int id2;
};

/* The answer of PQP_Collide. */
struct PQP_CollideResult
{
    /* Bounding-volume tests and triangle-pair tests of the last query, and its wall-clock time. */
    int num_bv_tests;
    int num_tri_tests;
    double query_time_secs;

    /* Model 2's frame in model 1's for the last query: R = R1^T R2, T = R1^T (T2 - T1). */
    PQP_REAL R[3][3];
    PQP_REAL T[3];

    /* The colliding pairs: pairs[0 .. num_pairs), in an array of num_pairs_alloced. */
    int num_pairs_alloced;
    int num_pairs;
    CollisionPair *pairs;

    PQP_CollideResult()
        : num_bv_tests(0), num_tri_tests(0), query_time_secs(0.0), num_pairs_alloced(0),
          num_pairs(0), pairs(NULL)
    {
        pqp_detail::identity(R, T);
    }

    /* Copies have pair arrays of their own (PQP 1.3's shared one and freed it twice). */
    PQP_CollideResult(const PQP_CollideResult &other)
        : num_bv_tests(0), num_tri_tests(0), query_time_secs(0.0), num_pairs_alloced(0),
          num_pairs(0), pairs(NULL)
    {
        copy_from(other);
    }

    PQP_CollideResult &operator=(const PQP_CollideResult &other)
    {
        if (this != &other) copy_from(other);
        return *this;
    }

#if __cplusplus >= 201103L
    PQP_CollideResult(PQP_CollideResult &&other) noexcept
        : num_bv_tests(0), num_tri_tests(0), query_time_secs(0.0), num_pairs_alloced(0),
          num_pairs(0), pairs(NULL)
    {
        swap(other);
    }
    PQP_CollideResult &operator=(PQP_CollideResult &&other) noexcept
    {
        if (this != &other) swap(other);
        return *this;
    }
#endif

    ~PQP_CollideResult() { delete[] pairs; }

    /* Resizes the pair array to n entries (n >= num_pairs; a smaller n is ignored, as PQP 1.3 did
     * after printing an error). Keeps the array as it was if memory runs out. */
    void SizeTo(int n)
    {
        if (n < num_pairs || n < 0) return;
        CollisionPair *grown = new (std::nothrow) CollisionPair[n > 0 ? n : 1];
        if (grown == NULL) return;
        if (num_pairs > 0) memcpy(grown, pairs, sizeof(CollisionPair) * num_pairs);
        delete[] pairs;
        pairs = grown;
        num_pairs_alloced = n;
    }

    /* Appends the pair (i1, i2), growing the array as PQP 1.3 did (to 2 num_pairs_alloced + 8). */
    void Add(int i1, int i2)
    {
        if (num_pairs >= num_pairs_alloced) SizeTo(num_pairs_alloced * 2 + 8);
        if (num_pairs >= num_pairs_alloced) return; /* out of memory */
        pairs[num_pairs].id1 = i1;
        pairs[num_pairs].id2 = i2;
        num_pairs++;
    }

    int NumBVTests() { return num_bv_tests; }
    int NumTriTests() { return num_tri_tests; }
    double QueryTimeSecs() { return query_time_secs; }

    /* Frees the list of colliding pairs (queries otherwise reuse it). */
    void FreePairsList()
    {
        delete[] pairs;
        pairs = NULL;
        num_pairs = num_pairs_alloced = 0;
        pqp_collide_result_free_pairs(handle_.get());
    }

    /* 1 if the last query found a colliding triangle pair, else 0. */
    int Colliding() { return num_pairs > 0; }
    /* Number of colliding pairs found. */
    int NumPairs() { return num_pairs; }
    /* The ids of pair k (0 <= k < NumPairs(); -1 outside, where PQP 1.3 read out of bounds). */
    int Id1(int k) { return k >= 0 && k < num_pairs ? pairs[k].id1 : -1; }
    int Id2(int k) { return k >= 0 && k < num_pairs ? pairs[k].id2 : -1; }

    /* pqp-rs extension: the C handle (for the C functions PQP 1.3 did not have). After a copy it
     * holds no answer: copies carry the members above. */
    pqp_collide_result *pqp_handle() { return handle_.get(); }
    const pqp_collide_result *pqp_handle() const { return handle_.peek(); }

    /* Copies the last query's answer from the C result into the members; PQP_ERR_OUT_OF_MEMORY
     * (members unchanged) if the pair array cannot grow. */
    int pqp_take_answer(const double R1[9], const double T1[3], const double R2[9],
                        const double T2[3])
    {
        int n = pqp_collide_result_num_pairs(handle_.peek());
        const pqp_contact_pair *found = pqp_collide_result_pairs(handle_.peek());
        if (n > num_pairs_alloced) {
            int saved = num_pairs;
            num_pairs = 0;
            SizeTo(n);
            num_pairs = saved;
            if (n > num_pairs_alloced) return PQP_ERR_OUT_OF_MEMORY;
        }
        for (int k = 0; k < n; k++) {
            pairs[k].id1 = found[k].id1;
            pairs[k].id2 = found[k].id2;
        }
        num_pairs = n;
        num_bv_tests = pqp_detail::clamp_to_int(pqp_collide_result_num_bv_tests(handle_.peek()));
        num_tri_tests = pqp_detail::clamp_to_int(pqp_collide_result_num_tri_tests(handle_.peek()));
        query_time_secs = pqp_collide_result_query_time_secs(handle_.peek());
        pqp_detail::relative_pose(R, T, R1, T1, R2, T2);
        return PQP_OK;
    }

private:
    void copy_from(const PQP_CollideResult &other)
    {
        /* Like a standard container's copy, this throws std::bad_alloc when memory runs out. */
        CollisionPair *copied = NULL;
        if (other.num_pairs_alloced > 0) {
            copied = new CollisionPair[other.num_pairs_alloced];
            if (other.num_pairs > 0)
                memcpy(copied, other.pairs, sizeof(CollisionPair) * other.num_pairs);
        }
        delete[] pairs;
        pairs = copied;
        num_pairs = other.num_pairs;
        num_pairs_alloced = other.num_pairs_alloced;
        num_bv_tests = other.num_bv_tests;
        num_tri_tests = other.num_tri_tests;
        query_time_secs = other.query_time_secs;
        pqp_detail::copy_pose(R, T, other.R, other.T);
    }

#if __cplusplus >= 201103L
    void swap(PQP_CollideResult &other)
    {
        std::swap(num_bv_tests, other.num_bv_tests);
        std::swap(num_tri_tests, other.num_tri_tests);
        std::swap(query_time_secs, other.query_time_secs);
        std::swap(R, other.R);
        std::swap(T, other.T);
        std::swap(num_pairs_alloced, other.num_pairs_alloced);
        std::swap(num_pairs, other.num_pairs);
        std::swap(pairs, other.pairs);
        std::swap(handle_, other.handle_);
    }
#endif

    pqp_detail::owned_handle<pqp_collide_result, &pqp_collide_result_create,
                             &pqp_collide_result_destroy>
        handle_;
};

#if PQP_BV_TYPE & RSS_TYPE

/* The answer of PQP_Distance. */
struct PQP_DistanceResult
{
    int num_bv_tests;
    int num_tri_tests;
    double query_time_secs;

    /* Model 2's frame in model 1's for the last query: R = R1^T R2, T = R1^T (T2 - T1). */
    PQP_REAL R[3][3];
    PQP_REAL T[3];

    /* The error bounds the last query was asked for. */
    PQP_REAL rel_err;
    PQP_REAL abs_err;

    /* The distance found (0 when the models touch or overlap), within the error bounds, and a pair
     * of points that far apart: p1 on model 1 in model 1's frame, p2 on model 2 in model 2's. */
    PQP_REAL distance;
    PQP_REAL p1[3];
    PQP_REAL p2[3];
    /* The queue size the last query was given. */
    int qsize;

    /* Copies carry the members (and start with a triangle cache of their own); from C++11 on,
     * results also move. */
    PQP_DistanceResult() { clear(); }

    int NumBVTests() { return num_bv_tests; }
    int NumTriTests() { return num_tri_tests; }
    double QueryTimeSecs() { return query_time_secs; }

    PQP_REAL Distance() { return distance; }
    const PQP_REAL *P1() { return p1; }
    const PQP_REAL *P2() { return p2; }

    /* pqp-rs extension: the C handle, which also keeps the triangle cache and search front that
     * speed up the next query on the same models. A copy starts with a fresh one. */
    pqp_distance_result *pqp_handle() { return handle_.get(); }
    const pqp_distance_result *pqp_handle() const { return handle_.peek(); }

    /* Copies the last query's answer from the C result into the members. */
    void pqp_take_answer(const double R1[9], const double T1[3], const double R2[9],
                         const double T2[3], PQP_REAL rel, PQP_REAL abs, int queue)
    {
        num_bv_tests = pqp_detail::clamp_to_int(pqp_distance_result_num_bv_tests(handle_.peek()));
        num_tri_tests = pqp_detail::clamp_to_int(pqp_distance_result_num_tri_tests(handle_.peek()));
        query_time_secs = pqp_distance_result_query_time_secs(handle_.peek());
        pqp_detail::relative_pose(R, T, R1, T1, R2, T2);
        rel_err = rel;
        abs_err = abs;
        distance = (PQP_REAL)pqp_distance_result_distance(handle_.peek());
        pqp_detail::narrow3(p1, pqp_distance_result_p1(handle_.peek()));
        pqp_detail::narrow3(p2, pqp_distance_result_p2(handle_.peek()));
        qsize = queue;
    }

private:
    void clear()
    {
        num_bv_tests = num_tri_tests = qsize = 0;
        query_time_secs = 0.0;
        pqp_detail::identity(R, T);
        rel_err = abs_err = distance = 0;
        for (int i = 0; i < 3; i++) p1[i] = p2[i] = 0;
    }
    pqp_detail::owned_handle<pqp_distance_result, &pqp_distance_result_create,
                             &pqp_distance_result_destroy>
        handle_;
};

/* The answer of PQP_Tolerance. */
struct PQP_ToleranceResult
{
    int num_bv_tests;
    int num_tri_tests;
    double query_time_secs;

    /* Model 2's frame in model 1's for the last query: R = R1^T R2, T = R1^T (T2 - T1). */
    PQP_REAL R[3][3];
    PQP_REAL T[3];

    /* 1 if the models are within the tolerance (distance <= tolerance), else 0. */
    int closer_than_tolerance;
    /* The tolerance the last query was asked for. */
    PQP_REAL tolerance;

    /* When closer: the distance of a triangle pair within the tolerance and its points (p1 on
     * model 1 in its frame, p2 on model 2 in its frame). Otherwise: a lower bound on the distance,
     * greater than the tolerance (PQP 1.3 left these meaningless then). */
    PQP_REAL distance;
    PQP_REAL p1[3];
    PQP_REAL p2[3];
    /* The queue size the last query was given. */
    int qsize;

    /* Copies carry the members; from C++11 on, results also move. */
    PQP_ToleranceResult() { clear(); }

    int NumBVTests() { return num_bv_tests; }
    int NumTriTests() { return num_tri_tests; }
    double QueryTimeSecs() { return query_time_secs; }

    int CloserThanTolerance() { return closer_than_tolerance; }
    PQP_REAL Distance() { return distance; }
    const PQP_REAL *P1() { return p1; }
    const PQP_REAL *P2() { return p2; }

    /* pqp-rs extension: the C handle. A copy starts with a fresh one. */
    pqp_tolerance_result *pqp_handle() { return handle_.get(); }
    const pqp_tolerance_result *pqp_handle() const { return handle_.peek(); }

    /* Copies the last query's answer from the C result into the members. */
    void pqp_take_answer(const double R1[9], const double T1[3], const double R2[9],
                         const double T2[3], PQP_REAL tol, int queue)
    {
        num_bv_tests = pqp_detail::clamp_to_int(pqp_tolerance_result_num_bv_tests(handle_.peek()));
        num_tri_tests =
            pqp_detail::clamp_to_int(pqp_tolerance_result_num_tri_tests(handle_.peek()));
        query_time_secs = pqp_tolerance_result_query_time_secs(handle_.peek());
        pqp_detail::relative_pose(R, T, R1, T1, R2, T2);
        closer_than_tolerance = pqp_tolerance_result_closer_than_tolerance(handle_.peek());
        tolerance = tol;
        distance = (PQP_REAL)pqp_tolerance_result_distance(handle_.peek());
        pqp_detail::narrow3(p1, pqp_tolerance_result_p1(handle_.peek()));
        pqp_detail::narrow3(p2, pqp_tolerance_result_p2(handle_.peek()));
        qsize = queue;
    }

private:
    void clear()
    {
        num_bv_tests = num_tri_tests = qsize = closer_than_tolerance = 0;
        query_time_secs = 0.0;
        pqp_detail::identity(R, T);
        tolerance = distance = 0;
        for (int i = 0; i < 3; i++) p1[i] = p2[i] = 0;
    }
    pqp_detail::owned_handle<pqp_tolerance_result, &pqp_tolerance_result_create,
                             &pqp_tolerance_result_destroy>
        handle_;
};

#endif /* PQP_BV_TYPE & RSS_TYPE */

#endif /* PQP_INTERNAL_H */
