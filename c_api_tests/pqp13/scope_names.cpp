// PQP 1.3 code names its types and constants with the global scope operator, takes their
// addresses, imports them with using-declarations and shadows them with local variables. That
// only compiles if PQP_REAL is a type (not a macro) and the codes and flags are `const int`
// variables (not macros or enumerators), as in PQP 1.3. Compiles as C++98 to C++20.
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

    if (failures != 0) return 1;
    printf("all checks passed\n");
    return 0;
}
