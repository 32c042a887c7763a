// PQP 1.3 code names its types and constants with the global scope operator, takes their
// addresses, imports them with using-declarations and shadows them with local variables. That
// only compiles if PQP_REAL is a type (not a macro) and the codes and flags are `const int`
// variables (not macros or enumerators), as in PQP 1.3. It also forward-declares PQP's classes and
// PQP_REAL before including PQP.h (as headers of programs that hold a PQP_Model * do), and takes
// pointers to every function and member function of PQP.h, PQP_Internal.h and BV.h with the exact
// types PQP 1.3 gives them (so the accessors are not const members there: PQP 1.3's are not).
// Compiles as C++98 to C++20.

// A program's own header, before PQP.h: forward declarations, and a repeated typedef.
class PQP_Model;
struct PQP_CollideResult;
struct PQP_DistanceResult;
struct PQP_ToleranceResult;
struct CollisionPair;
struct Tri;
struct BV;
typedef double PQP_REAL;
struct Body
{
    PQP_Model *model;
    PQP_REAL position[3];
};

#include "PQP.h"

#include <stdio.h>

static int failures = 0;

#define EXPECT(cond)                                                               \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                            \
        }                                                                          \
    } while (0)

namespace planner {
// A namespace importing PQP's names, as robotics libraries do.
using ::PQP_Model;
using ::PQP_REAL;
using ::PQP_ALL_CONTACTS;
using ::PQP_FIRST_CONTACT;
using ::PQP_OK;

// Builds a one-triangle model at height z with id `id`, through the imported names.
static int build(PQP_Model &m, PQP_REAL z, int id)
{
    PQP_REAL a[3] = {0, 0, z}, b[3] = {1, 0, z}, c[3] = {0, 1, z};
    int rc = m.BeginModel();
    if (rc == PQP_OK) rc = m.AddTri(a, b, c, id);
    if (rc == PQP_OK) rc = m.EndModel();
    return rc;
}
} // namespace planner

// A status code compared in a switch: the constants are integral constant expressions.
static const char *describe(int rc)
{
    switch (rc) {
    case ::PQP_OK: return "ok";
    case ::PQP_ERR_MODEL_OUT_OF_MEMORY: return "model out of memory";
    case ::PQP_ERR_OUT_OF_MEMORY: return "out of memory";
    case ::PQP_ERR_UNPROCESSED_MODEL: return "unprocessed model";
    case ::PQP_ERR_BUILD_OUT_OF_SEQUENCE: return "out of sequence";
    case ::PQP_ERR_BUILD_EMPTY_MODEL: return "empty model";
    default: return "other";
    }
}

// Takes a flag by reference (binds to the constant object, so it must be a variable).
static int flag_value(const int &flag)
{
    return flag;
}

int main()
{
    // ::PQP_REAL is a type; sizeof and arrays of it work.
    ::PQP_REAL R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    ::PQP_REAL T1[3] = {0, 0, 0}, T2[3] = {0, 0, 0};
    EXPECT(sizeof(::PQP_REAL) == sizeof(double));

    // ::PQP_Model, built through the namespace's using-declarations.
    ::PQP_Model a, b;
    EXPECT(planner::build(a, 0.0, 7) == ::PQP_OK);
    EXPECT(planner::build(b, 0.0, 9) == planner::PQP_OK);

    // Addresses of the constants, and the values PQP 1.3 gave them.
    const int *codes[] = {&PQP_OK, &PQP_ERR_MODEL_OUT_OF_MEMORY, &PQP_ERR_OUT_OF_MEMORY,
                          &PQP_ERR_UNPROCESSED_MODEL, &PQP_ERR_BUILD_OUT_OF_SEQUENCE,
                          &PQP_ERR_BUILD_EMPTY_MODEL};
    for (int k = 0; k < 6; k++) EXPECT(*codes[k] == -k);
    EXPECT(*&::PQP_ALL_CONTACTS == 1 && *&::PQP_FIRST_CONTACT == 2);
    EXPECT(flag_value(PQP_FIRST_CONTACT) == 2);
    // Array bounds from a constant.
    char room[::PQP_FIRST_CONTACT + 1];
    EXPECT(sizeof(room) == 3);

    // The qualified flag in a query, and a switch over its status.
    ::PQP_CollideResult cres;
    EXPECT(PQP_Collide(&cres, R, T1, &a, R, T2, &b, ::PQP_FIRST_CONTACT) == ::PQP_OK);
    EXPECT(cres.Colliding() == 1 && cres.NumPairs() == 1);
    EXPECT(cres.Id1(0) == 7 && cres.Id2(0) == 9);
    ::PQP_Model never_built;
    int rc = PQP_Collide(&cres, R, T1, &a, R, T2, &never_built, ::PQP_ALL_CONTACTS);
    EXPECT(rc == ::PQP_ERR_UNPROCESSED_MODEL);
    EXPECT(describe(rc)[0] == 'u');
    EXPECT(describe(never_built.EndModel())[0] == 'e');

    {
        // Local variables named like the constants shadow them (a macro would break this).
        int PQP_OK = 42;
        int PQP_ALL_CONTACTS = PQP_OK + 1;
        EXPECT(PQP_OK == 42 && PQP_ALL_CONTACTS == 43);
        EXPECT(::PQP_OK == 0 && ::PQP_ALL_CONTACTS == 1);
    }

    // Distance through the qualified type of its arguments.
    ::PQP_DistanceResult dres;
    T2[2] = 2.0;
    EXPECT(PQP_Distance(&dres, R, T1, &a, R, T2, &b, (::PQP_REAL)0, (::PQP_REAL)0) == ::PQP_OK);
    EXPECT(dres.Distance() > 1.999999999 && dres.Distance() < 2.000000001);

    // Pointers to the queries and to every member function, with PQP 1.3's types, called
    // through: a body holding a model, one triangle 2 above the other.
    {
        typedef int (*collide_fn)(PQP_CollideResult *, PQP_REAL[3][3], PQP_REAL[3], PQP_Model *,
                                  PQP_REAL[3][3], PQP_REAL[3], PQP_Model *, int);
        typedef int (*distance_fn)(PQP_DistanceResult *, PQP_REAL[3][3], PQP_REAL[3], PQP_Model *,
                                   PQP_REAL[3][3], PQP_REAL[3], PQP_Model *, PQP_REAL, PQP_REAL,
                                   int);
        typedef int (*tolerance_fn)(PQP_ToleranceResult *, PQP_REAL[3][3], PQP_REAL[3],
                                    PQP_Model *, PQP_REAL[3][3], PQP_REAL[3], PQP_Model *,
                                    PQP_REAL, int);
        typedef int (*overlap_fn)(PQP_REAL[3][3], PQP_REAL[3], BV *, BV *);
        typedef PQP_REAL (*bv_distance_fn)(PQP_REAL[3][3], PQP_REAL[3], BV *, BV *);
        collide_fn collide = PQP_Collide;
        distance_fn distance = PQP_Distance;
        tolerance_fn tolerance = PQP_Tolerance;
        overlap_fn overlap = BV_Overlap;
        bv_distance_fn bv_distance = BV_Distance;

        int (PQP_Model::*begin)(int) = &PQP_Model::BeginModel;
        int (PQP_Model::*add)(const PQP_REAL *, const PQP_REAL *, const PQP_REAL *, int) =
            &PQP_Model::AddTri;
        int (PQP_Model::*end)() = &PQP_Model::EndModel;
        int (PQP_Model::*mem_usage)(int) = &PQP_Model::MemUsage;
        BV *(PQP_Model::*child)(int) = &PQP_Model::child;
        int (BV::*leaf)() = &BV::Leaf;
        PQP_REAL (BV::*get_size)() = &BV::GetSize;
        void (BV::*fit)(PQP_REAL[3][3], Tri *, int) = &BV::FitToTris;
        void (PQP_CollideResult::*size_to)(int) = &PQP_CollideResult::SizeTo;
        void (PQP_CollideResult::*add_pair)(int, int) = &PQP_CollideResult::Add;
        void (PQP_CollideResult::*free_pairs)() = &PQP_CollideResult::FreePairsList;
        int (PQP_CollideResult::*c_bv_tests)() = &PQP_CollideResult::NumBVTests;
        int (PQP_CollideResult::*c_tri_tests)() = &PQP_CollideResult::NumTriTests;
        double (PQP_CollideResult::*c_secs)() = &PQP_CollideResult::QueryTimeSecs;
        int (PQP_CollideResult::*colliding)() = &PQP_CollideResult::Colliding;
        int (PQP_CollideResult::*num_pairs)() = &PQP_CollideResult::NumPairs;
        int (PQP_CollideResult::*id1)(int) = &PQP_CollideResult::Id1;
        int (PQP_CollideResult::*id2)(int) = &PQP_CollideResult::Id2;
        int (PQP_DistanceResult::*d_bv_tests)() = &PQP_DistanceResult::NumBVTests;
        int (PQP_DistanceResult::*d_tri_tests)() = &PQP_DistanceResult::NumTriTests;
        double (PQP_DistanceResult::*d_secs)() = &PQP_DistanceResult::QueryTimeSecs;
        PQP_REAL (PQP_DistanceResult::*d_distance)() = &PQP_DistanceResult::Distance;
        const PQP_REAL *(PQP_DistanceResult::*d_p1)() = &PQP_DistanceResult::P1;
        const PQP_REAL *(PQP_DistanceResult::*d_p2)() = &PQP_DistanceResult::P2;
        int (PQP_ToleranceResult::*t_bv_tests)() = &PQP_ToleranceResult::NumBVTests;
        int (PQP_ToleranceResult::*t_tri_tests)() = &PQP_ToleranceResult::NumTriTests;
        double (PQP_ToleranceResult::*t_secs)() = &PQP_ToleranceResult::QueryTimeSecs;
        PQP_REAL (PQP_ToleranceResult::*t_distance)() = &PQP_ToleranceResult::Distance;
        const PQP_REAL *(PQP_ToleranceResult::*t_p1)() = &PQP_ToleranceResult::P1;
        const PQP_REAL *(PQP_ToleranceResult::*t_p2)() = &PQP_ToleranceResult::P2;
        int (PQP_ToleranceResult::*closer)() = &PQP_ToleranceResult::CloserThanTolerance;

        PQP_Model lower, upper;
        Body body = {&upper, {0, 0, 2}};
        PQP_REAL p[3] = {0, 0, 0}, q[3] = {1, 0, 0}, r[3] = {0, 1, 0};
        EXPECT((lower.*begin)(4) == PQP_OK && (lower.*add)(p, q, r, 3) == PQP_OK);
        EXPECT((lower.*end)() == PQP_OK && (lower.*mem_usage)(0) > 0);
        EXPECT(planner::build(*body.model, 0.0, 4) == PQP_OK);
        BV *root = (lower.*child)(0);
        EXPECT((root->*leaf)() == 1 && (root->*get_size)() > 0);
        PQP_REAL I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, O[3] = {0, 0, 0};
        EXPECT(overlap(I, O, root, root) == 1);
        EXPECT(bv_distance(I, body.position, root, (body.model->*child)(0)) >= 0);
        BV fitted;
        (fitted.*fit)(I, lower.tris, 1);
        EXPECT((fitted.*get_size)() > 0);

        PQP_CollideResult c;
        EXPECT(collide(&c, I, O, &lower, I, O, body.model, PQP_ALL_CONTACTS) == PQP_OK);
        EXPECT((c.*colliding)() == 1 && (c.*num_pairs)() == 1);
        EXPECT((c.*id1)(0) == 3 && (c.*id2)(0) == 4);
        // (Test counts are the implementation's: one triangle test here, volume tests vary.)
        EXPECT((c.*c_bv_tests)() >= 0 && (c.*c_tri_tests)() == 1 && (c.*c_secs)() >= 0);
        (c.*size_to)(8);
        (c.*add_pair)(5, 6);
        EXPECT((c.*num_pairs)() == 2 && (c.*id1)(1) == 5 && (c.*id2)(1) == 6);
        (c.*free_pairs)();
        EXPECT((c.*num_pairs)() == 0);

        PQP_DistanceResult d;
        EXPECT(distance(&d, I, O, &lower, I, body.position, body.model, 0, 0, 2) == PQP_OK);
        EXPECT((d.*d_distance)() == 2 && (d.*d_p1)()[2] == 0 && (d.*d_p2)()[2] == 0);
        EXPECT((d.*d_bv_tests)() >= 0 && (d.*d_tri_tests)() >= 1 && (d.*d_secs)() >= 0);

        PQP_ToleranceResult t;
        EXPECT(tolerance(&t, I, O, &lower, I, body.position, body.model, 2.5, 2) == PQP_OK);
        EXPECT((t.*closer)() == 1 && (t.*t_distance)() == 2);
        EXPECT((t.*t_p1)()[2] == 0 && (t.*t_p2)()[2] == 0);
        EXPECT((t.*t_bv_tests)() >= 0 && (t.*t_tri_tests)() >= 1 && (t.*t_secs)() >= 0);
    }

    if (failures != 0) return 1;
    printf("all checks passed\n");
    return 0;
}
