// every_member.cpp -- the program to build against both UNC's PQP 1.3 and pqp-rs, and diff the
// outputs.
//
// It is a legacy PQP 1.3 program (C++98, only the installed headers PQP.h, PQP_Compile.h,
// PQP_Internal.h, Tri.h and BV.h, and the MatVec.h and TriDist.h of PQP 1.3's src/) that uses EVERY
// public constant, type, data member and function of those headers, on small models whose answers
// are known by construction (unit boxes at known offsets, a fence of triangles crossed by a rail,
// two single triangles with one closest pair). It
// prints to stdout, one per line, the answers a correct PQP gives deterministically: constants,
// build counters, triangle ids and coordinates read back from tris (sorted by id: PQP 1.3 reorders
// tris, pqp-rs does not), tree sizes, sorted collision pairs, distances (%.9g), unique closest
// points, closer flags, the relative poses R and T, echoed arguments. It does not print what
// legitimately differs between implementations: test counts, times, memory sizes, bounding-volume
// coordinates, which of several equally close pairs is reported, or members PQP 1.3 leaves
// unspecified (a tolerance result's distance when not closer; qsize when the queue size is 2 or
// less, which PQP 1.3 does not store). So
//
//     g++ every_member.cpp -I<PQP 1.3>/include -I<PQP 1.3>/src -L<PQP 1.3>/lib -lPQP && ./a.out > pqp13.txt
//     g++ every_member.cpp -I<pqp-rs>/include -L<pqp-rs>/lib -lpqp && ./a.out > pqprs.txt
//     diff pqp13.txt pqprs.txt
//
// shows no difference where PQP 1.3 is right. (PQP 1.3 prints warnings on stderr for the
// out-of-sequence calls below and for MemUsage(1); pqp-rs prints nothing on stderr.) The program also
// checks each answer against the known value (EXPECT): it exits with status 1, naming each failed
// check on stderr, if one is wrong.
#include "PQP.h"
#include "PQP_Compile.h"
// PQP_Internal.h comes through PQP.h: PQP 1.3's PQP_Internal.h has no include guard, so a
// PQP 1.3 program cannot include it a second time.
#include "Tri.h"
#include "BV.h"
// Not installed by PQP 1.3's Makefile, but used by its demos and by programs that copied them:
// build against PQP 1.3 with -I<PQP 1.3>/src as well. TriDist() and SegPoints() are in libPQP.a.
#include "MatVec.h"
#include "TriDist.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <algorithm>

static int failures = 0;

#define EXPECT(cond)                                                               \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                            \
        }                                                                          \
    } while (0)

static bool near_value(double x, double want)
{
    return fabs(x - want) <= 1e-12 * (1 + fabs(want));
}

// Values are printed with 9 significant digits; rounding noise below 1e-9 prints as 0.
static double snap(double x)
{
    return fabs(x) < 1e-9 ? 0.0 : x;
}

static void print_vector(const char *label, const PQP_REAL v[3])
{
    printf("%s %.9g %.9g %.9g\n", label, snap(v[0]), snap(v[1]), snap(v[2]));
}

static void print_pose(const char *label, const PQP_REAL R[3][3], const PQP_REAL T[3])
{
    printf("%s R %.9g %.9g %.9g / %.9g %.9g %.9g / %.9g %.9g %.9g T %.9g %.9g %.9g\n", label,
           snap(R[0][0]), snap(R[0][1]), snap(R[0][2]), snap(R[1][0]), snap(R[1][1]),
           snap(R[1][2]), snap(R[2][0]), snap(R[2][1]), snap(R[2][2]), snap(T[0]), snap(T[1]),
           snap(T[2]));
}

static void identity(PQP_REAL R[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) R[i][j] = i == j ? 1.0 : 0.0;
}

// The rotation whose first row is (1,1,1)/sqrt(3): it turns the unit box so that its corner
// (0,0,0) is its unique lowest point in x.
static void corner_first(PQP_REAL R[3][3])
{
    const double a = 1 / sqrt(3.0), b = 1 / sqrt(2.0), c = 1 / sqrt(6.0);
    R[0][0] = a;
    R[0][1] = a;
    R[0][2] = a;
    R[1][0] = b;
    R[1][1] = -b;
    R[1][2] = 0;
    R[2][0] = c;
    R[2][1] = c;
    R[2][2] = -2 * c;
}

// R = R1^T R2 and T = R1^T (T2 - T1) (what every result's R and T hold).
static bool relative_pose_ok(const PQP_REAL R[3][3], const PQP_REAL T[3], PQP_REAL R1[3][3],
                             PQP_REAL T1[3], PQP_REAL R2[3][3], PQP_REAL T2[3])
{
    bool ok = true;
    for (int i = 0; i < 3; i++) {
        double t = 0;
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++) s += R1[k][i] * R2[k][j];
            ok = ok && fabs(R[i][j] - s) <= 1e-12;
        }
        for (int k = 0; k < 3; k++) t += R1[k][i] * (T2[k] - T1[k]);
        ok = ok && fabs(T[i] - t) <= 1e-12;
    }
    return ok;
}

// The 12 triangles of the unit box [0,1]^3 with ids first_id .. first_id + 11.
static void box_triangle(int k, PQP_REAL p[3][3])
{
    static const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                     {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                     {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    for (int v = 0; v < 3; v++)
        for (int a = 0; a < 3; a++) p[v][a] = (faces[k][v] >> (2 - a)) & 1;
}

static void add_box(PQP_Model &m, int first_id)
{
    for (int k = 0; k < 12; k++) {
        PQP_REAL p[3][3];
        box_triangle(k, p);
        EXPECT(m.AddTri(p[0], p[1], p[2], first_id + k) == PQP_OK);
    }
}

// The build counters and whether the arrays are there.
static void print_counters(const char *label, PQP_Model &m)
{
    printf("%s: build_state %d num_tris %d num_tris_alloced %d num_bvs %d num_bvs_alloced %d\n",
           label, m.build_state, m.num_tris, m.num_tris_alloced, m.num_bvs, m.num_bvs_alloced);
}

// tris sorted by id: "id: p1 p2 p3".
static void print_tris_by_id(const char *label, PQP_Model &m)
{
    const int n = m.num_tris;
    Tri *tris = m.tris;
    int order[64];
    EXPECT(n <= 64 && tris != NULL);
    if (n > 64 || tris == NULL) return;
    for (int k = 0; k < n; k++) order[k] = k;
    for (int i = 1; i < n; i++)  // insertion sort by id
        for (int j = i; j > 0 && tris[order[j]].id < tris[order[j - 1]].id; j--)
            std::swap(order[j], order[j - 1]);
    for (int k = 0; k < n; k++) {
        const Tri &t = tris[order[k]];
        printf("%s tri id %d: %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g\n", label, t.id,
               t.p1[0], t.p1[1], t.p1[2], t.p2[0], t.p2[1], t.p2[2], t.p3[0], t.p3[1], t.p3[2]);
    }
}

// Whether point p (model frame) lies in the volume v whose frame is absolute (the root, or a BV
// fitted with FitToTris): the rectangle swept sphere (corner Tr, sides l, radius r, axes the
// columns of R) and the oriented box (centre To, half extents d).
static bool in_bv(const BV &v, const PQP_REAL p[3])
{
    const double tol = 1e-9;
    double qr[3], qo[3];
    for (int i = 0; i < 3; i++) {
        qr[i] = 0;
        qo[i] = 0;
        for (int k = 0; k < 3; k++) {
            qr[i] += v.R[k][i] * (p[k] - v.Tr[k]);
            qo[i] += v.R[k][i] * (p[k] - v.To[k]);
        }
    }
    double x = qr[0] < 0 ? 0 : qr[0] > v.l[0] ? v.l[0] : qr[0];
    double y = qr[1] < 0 ? 0 : qr[1] > v.l[1] ? v.l[1] : qr[1];
    double dr = sqrt((qr[0] - x) * (qr[0] - x) + (qr[1] - y) * (qr[1] - y) + qr[2] * qr[2]);
    bool in_rss = dr <= v.r + tol;
    bool in_obb = fabs(qo[0]) <= v.d[0] + tol && fabs(qo[1]) <= v.d[1] + tol &&
                  fabs(qo[2]) <= v.d[2] + tol;
    return in_rss && in_obb;
}

static bool all_vertices_in(const BV &v, Tri *tris, int n)
{
    bool ok = true;
    for (int k = 0; k < n; k++)
        ok = ok && in_bv(v, tris[k].p1) && in_bv(v, tris[k].p2) && in_bv(v, tris[k].p3);
    return ok;
}

// The hierarchy's shape, PQP's way: b[0] the root; an inner volume's children at first_child and
// first_child + 1, after it; a leaf holds tris[-first_child - 1]. Prints the leaf and inner counts
// and the triangle ids of the leaves, sorted.
static void print_tree(const char *label, PQP_Model &m)
{
    const int nb = m.num_bvs, n = m.num_tris;
    BV *b = m.b;
    EXPECT(b != NULL && nb == 2 * n - 1 && nb <= 127);
    if (b == NULL || nb != 2 * n - 1 || nb > 127) return;
    EXPECT(m.child(0) == b && m.child(nb - 1) == b + nb - 1);
    int leaves = 0, inner = 0, ids[64], children_seen[127];
    bool shape_ok = true;
    for (int k = 0; k < nb; k++) children_seen[k] = 0;
    for (int k = 0; k < nb; k++) {
        BV *v = m.child(k);
        if (v->Leaf()) {
            int t = -v->first_child - 1;
            shape_ok = shape_ok && t >= 0 && t < n && leaves < 64;
            if (shape_ok) ids[leaves++] = m.tris[t].id;
        } else {
            int c = v->first_child;
            shape_ok = shape_ok && c > k && c + 1 < nb;
            if (shape_ok) {
                children_seen[c]++;
                children_seen[c + 1]++;
            }
            inner++;
        }
        shape_ok = shape_ok && v->GetSize() >= 0;
    }
    for (int k = 1; k < nb; k++) shape_ok = shape_ok && children_seen[k] == 1;
    shape_ok = shape_ok && children_seen[0] == 0;
    EXPECT(shape_ok);
    EXPECT(leaves == n && inner == n - 1);
    std::sort(ids, ids + leaves);
    printf("%s tree: %d volumes, %d leaves, %d inner, shape ok %d, leaf ids", label, nb, leaves,
           inner, shape_ok ? 1 : 0);
    for (int k = 0; k < leaves; k++) printf(" %d", ids[k]);
    printf("\n");
    // The root is in the model frame and contains every vertex.
    bool root_ok = all_vertices_in(b[0], m.tris, n);
    EXPECT(root_ok);
    printf("%s root: contains every vertex %d, is a leaf %d\n", label, root_ok ? 1 : 0,
           b[0].Leaf());
}

// The collision pairs, sorted.
static void print_pairs(const char *label, PQP_CollideResult &res)
{
    const int n = res.NumPairs();
    CollisionPair sorted[64];
    EXPECT(n == res.num_pairs && n <= 64);
    for (int k = 0; k < n && k < 64; k++) {
        EXPECT(res.Id1(k) == res.pairs[k].id1 && res.Id2(k) == res.pairs[k].id2);
        sorted[k] = res.pairs[k];
    }
    for (int i = 1; i < n && i < 64; i++)
        for (int j = i; j > 0 && (sorted[j].id1 < sorted[j - 1].id1 ||
                                  (sorted[j].id1 == sorted[j - 1].id1 &&
                                   sorted[j].id2 < sorted[j - 1].id2));
             j--)
            std::swap(sorted[j], sorted[j - 1]);
    printf("%s: Colliding %d NumPairs %d pairs", label, res.Colliding(), n);
    for (int k = 0; k < n && k < 64; k++) printf(" (%d,%d)", sorted[k].id1, sorted[k].id2);
    printf("\n");
}

// Statistics are implementation-dependent: checked, not printed.
template <class Result> static void check_stats(Result &res)
{
    EXPECT(res.num_bv_tests >= 0 && res.NumBVTests() == res.num_bv_tests);
    EXPECT(res.num_tri_tests >= 0 && res.NumTriTests() == res.num_tri_tests);
    EXPECT(res.query_time_secs >= 0 && res.QueryTimeSecs() == res.query_time_secs);
}

int main()
{
    // ---- Constants ---------------------------------------------------------------------------
    printf("PQP_OK %d\n", PQP_OK);
    printf("PQP_ERR_MODEL_OUT_OF_MEMORY %d\n", PQP_ERR_MODEL_OUT_OF_MEMORY);
    printf("PQP_ERR_OUT_OF_MEMORY %d\n", PQP_ERR_OUT_OF_MEMORY);
    printf("PQP_ERR_UNPROCESSED_MODEL %d\n", PQP_ERR_UNPROCESSED_MODEL);
    printf("PQP_ERR_BUILD_OUT_OF_SEQUENCE %d\n", PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    printf("PQP_ERR_BUILD_EMPTY_MODEL %d\n", PQP_ERR_BUILD_EMPTY_MODEL);
    printf("PQP_ALL_CONTACTS %d PQP_FIRST_CONTACT %d\n", PQP_ALL_CONTACTS, PQP_FIRST_CONTACT);
    printf("RSS_TYPE %d OBB_TYPE %d PQP_BV_TYPE %d (RSS %d, OBB %d)\n", RSS_TYPE, OBB_TYPE,
           PQP_BV_TYPE, ((PQP_BV_TYPE) & RSS_TYPE) ? 1 : 0, ((PQP_BV_TYPE) & OBB_TYPE) ? 1 : 0);
    printf("sizeof(PQP_REAL) %d\n", (int)sizeof(PQP_REAL));
    EXPECT(PQP_OK == 0 && PQP_ERR_MODEL_OUT_OF_MEMORY == -1 && PQP_ERR_OUT_OF_MEMORY == -2);
    EXPECT(PQP_ERR_UNPROCESSED_MODEL == -3 && PQP_ERR_BUILD_OUT_OF_SEQUENCE == -4);
    EXPECT(PQP_ERR_BUILD_EMPTY_MODEL == -5);
    EXPECT(PQP_ALL_CONTACTS == 1 && PQP_FIRST_CONTACT == 2);
    EXPECT(RSS_TYPE == 1 && OBB_TYPE == 2 && PQP_BV_TYPE == 3);
    EXPECT(sizeof(PQP_REAL) == sizeof(double));

    // ---- Building: box A (BeginModel with no argument, on the heap) --------------------------
    PQP_Model *a = new PQP_Model;
    print_counters("A fresh", *a);
    printf("A fresh: tris NULL %d, b NULL %d, last_tri NULL %d\n", a->tris == NULL ? 1 : 0,
           a->b == NULL ? 1 : 0, a->last_tri == NULL ? 1 : 0);
    EXPECT(a->build_state == 0 && a->num_tris == 0 && a->num_tris_alloced == 0);
    EXPECT(a->num_bvs == 0 && a->num_bvs_alloced == 0);
    EXPECT(a->tris == NULL && a->b == NULL && a->last_tri == NULL);
    EXPECT(a->BeginModel() == PQP_OK);
    print_counters("A begun", *a);
    EXPECT(a->build_state == 1 && a->num_tris_alloced == 8);
    add_box(*a, 100);
    print_counters("A filled", *a);
    EXPECT(a->num_tris == 12 && a->num_tris_alloced == 16 && a->b == NULL);
    // Before EndModel tris holds the triangles in the order added (in both implementations).
    {
        Tri *t = a->tris;
        printf("A filled: ids in tris order");
        for (int k = 0; k < a->num_tris; k++) {
            printf(" %d", t[k].id);
            EXPECT(t[k].id == 100 + k);
        }
        printf("\n");
    }
    int rc = a->EndModel();
    printf("A EndModel %d\n", rc);
    EXPECT(rc == PQP_OK);
    print_counters("A built", *a);
    EXPECT(a->build_state == 2 && a->num_tris == 12 && a->num_tris_alloced == 12);
    EXPECT(a->num_bvs == 23 && a->num_bvs_alloced == 23);
    printf("A built: last_tri == tris %d, child(0) == b %d\n", a->last_tri == a->tris ? 1 : 0,
           a->child(0) == a->b ? 1 : 0);
    EXPECT(a->last_tri == a->tris && a->child(0) == a->b);
    print_tris_by_id("A", *a);
    print_tree("A", *a);
    // Memory use is implementation-dependent; MemUsage(1) also prints a report in PQP 1.3 (on
    // stderr).
    printf("A MemUsage positive %d\n", a->MemUsage(0) > 0 ? 1 : 0);
    EXPECT(a->MemUsage(0) > 0 && a->MemUsage(1) > 0);

    // ---- Box B (BeginModel(5): the capacity doubles to 10, then 20) --------------------------
    PQP_Model b;
    EXPECT(b.BeginModel(5) == PQP_OK);
    print_counters("B begun", b);
    EXPECT(b.num_tris_alloced == 5);
    add_box(b, 200);
    print_counters("B filled", b);
    EXPECT(b.num_tris_alloced == 20);
    EXPECT(b.EndModel() == PQP_OK);
    print_counters("B built", b);
    EXPECT(b.num_tris == 12 && b.num_tris_alloced == 12 && b.num_bvs == 23);
    print_tree("B", b);

    // ---- Fence (triangle k in the plane x = k, id k) and rail (one thin triangle, id 7) -------
    PQP_Model fence, rail;
    EXPECT(fence.BeginModel(10) == PQP_OK);
    for (int k = 0; k < 10; k++) {
        PQP_REAL p[3] = {0, 0, 0}, q[3] = {0, 1, 0}, r[3] = {0, 0, 1};
        p[0] = q[0] = r[0] = k;
        EXPECT(fence.AddTri(p, q, r, k) == PQP_OK);
    }
    EXPECT(fence.EndModel() == PQP_OK);
    print_tree("fence", fence);
    PQP_REAL ra[3] = {0, 0.2, 0.2}, rb[3] = {3.5, 0.2, 0.2}, rc3[3] = {3.5, 0.3, 0.2};
    EXPECT(rail.BeginModel(1) == PQP_OK);
    EXPECT(rail.AddTri(ra, rb, rc3, 7) == PQP_OK);
    EXPECT(rail.EndModel() == PQP_OK);
    print_counters("rail built", rail);

    // ---- Single triangles C and D (AddTri without BeginModel begins the model) ----------------
    PQP_Model c, d;
    {
        PQP_REAL p[3] = {0, 0, 0}, q[3] = {1, 0, 0}, r[3] = {0, 1, 0};
        EXPECT(c.AddTri(p, q, r, 31) == PQP_OK);
        print_counters("C after AddTri", c);
        EXPECT(c.build_state == 1 && c.num_tris == 1 && c.num_tris_alloced == 8);
        EXPECT(c.EndModel() == PQP_OK);
        PQP_REAL s[3] = {0.25, 0.25, 0}, t[3] = {0.25, 0.25, 1}, u[3] = {1, 1, 1};
        EXPECT(d.BeginModel(1) == PQP_OK);
        EXPECT(d.AddTri(s, t, u, 42) == PQP_OK);
        EXPECT(d.EndModel() == PQP_OK);
    }
    print_counters("C built", c);
    print_tris_by_id("C", c);
    printf("C root: first_child %d Leaf %d\n", c.b[0].first_child, c.child(0)->Leaf());
    EXPECT(c.num_bvs == 1 && c.b[0].first_child == -1 && c.child(0)->Leaf() == 1);
    EXPECT(c.b[0].GetSize() >= 0);

    // ---- Build errors -------------------------------------------------------------------------
    PQP_Model unbuilt;
    EXPECT(unbuilt.BeginModel() == PQP_OK);
    rc = unbuilt.EndModel();
    printf("EndModel without triangles %d\n", rc);
    EXPECT(rc == PQP_ERR_BUILD_EMPTY_MODEL);
    rc = a->EndModel();
    printf("EndModel twice %d\n", rc);
    EXPECT(rc == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    rc = a->AddTri(ra, rb, rc3, 1);
    printf("AddTri after EndModel %d, num_tris %d\n", rc, a->num_tris);
    EXPECT(rc == PQP_ERR_BUILD_OUT_OF_SEQUENCE && a->num_tris == 12);
    {
        // BeginModel on a built model clears it (and says so).
        PQP_Model e;
        add_box(e, 0);
        EXPECT(e.EndModel() == PQP_OK);
        rc = e.BeginModel(3);
        printf("BeginModel on a built model %d\n", rc);
        EXPECT(rc == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        print_counters("E begun again", e);
        EXPECT(e.build_state == 1 && e.num_tris == 0 && e.num_bvs == 0 && e.num_tris_alloced == 3);
        add_box(e, 500);
        EXPECT(e.EndModel() == PQP_OK);
        print_counters("E rebuilt", e);
        print_tris_by_id("E", e);
    }

    PQP_REAL R1[3][3], R2[3][3], T1[3] = {0, 0, 0}, T2[3] = {3, 0, 0};
    identity(R1);
    identity(R2);
    PQP_CollideResult cres;
    PQP_DistanceResult dres;
    PQP_ToleranceResult tres;
    printf("queries on an unbuilt model: collide %d distance %d tolerance %d\n",
           PQP_Collide(&cres, R1, T1, a, R2, T2, &unbuilt),
           PQP_Distance(&dres, R1, T1, &unbuilt, R2, T2, a, 0.0, 0.0),
           PQP_Tolerance(&tres, R1, T1, a, R2, T2, &unbuilt, 1.0));
    EXPECT(PQP_Collide(&cres, R1, T1, &unbuilt, R2, T2, a, PQP_FIRST_CONTACT) ==
           PQP_ERR_UNPROCESSED_MODEL);

    // ---- PQP_CollideResult by hand: SizeTo, Add, FreePairsList -------------------------------
    {
        PQP_CollideResult h;
        printf("fresh collide result: num_pairs %d num_pairs_alloced %d pairs NULL %d Colliding "
               "%d NumPairs %d\n",
               h.num_pairs, h.num_pairs_alloced, h.pairs == NULL ? 1 : 0, h.Colliding(),
               h.NumPairs());
        EXPECT(h.num_pairs == 0 && h.num_pairs_alloced == 0 && h.pairs == NULL);
        h.SizeTo(4);
        printf("SizeTo(4): num_pairs_alloced %d\n", h.num_pairs_alloced);
        EXPECT(h.num_pairs_alloced == 4 && h.pairs != NULL);
        for (int k = 0; k < 5; k++) h.Add(10 + k, 20 + k);
        printf("5 Add: num_pairs %d num_pairs_alloced %d Id1(4) %d Id2(4) %d Colliding %d\n",
               h.num_pairs, h.num_pairs_alloced, h.Id1(4), h.Id2(4), h.Colliding());
        EXPECT(h.num_pairs == 5 && h.num_pairs_alloced == 16 && h.Id1(4) == 14 && h.Id2(4) == 24);
        h.SizeTo(5);
        printf("SizeTo(5): num_pairs_alloced %d pairs", h.num_pairs_alloced);
        for (int k = 0; k < h.num_pairs; k++) printf(" (%d,%d)", h.pairs[k].id1, h.pairs[k].id2);
        printf("\n");
        EXPECT(h.num_pairs_alloced == 5 && h.pairs[0].id1 == 10 && h.pairs[4].id2 == 24);
        h.FreePairsList();
        printf("FreePairsList: num_pairs %d num_pairs_alloced %d pairs NULL %d\n", h.num_pairs,
               h.num_pairs_alloced, h.pairs == NULL ? 1 : 0);
        EXPECT(h.num_pairs == 0 && h.num_pairs_alloced == 0 && h.pairs == NULL);
        // A query replaces pairs added by hand.
        h.Add(-1, -2);
        PQP_REAL Tr[3] = {2.5, 0, 0};
        EXPECT(PQP_Collide(&h, R1, T1, &fence, R2, Tr, &rail) == PQP_OK);
        print_pairs("fence/rail after Add", h);
        EXPECT(h.num_pairs == 4 && h.num_pairs_alloced >= h.num_pairs);
    }

    // ---- PQP_Collide --------------------------------------------------------------------------
    EXPECT(PQP_Collide(&cres, R1, T1, a, R2, T2, &b) == PQP_OK);
    print_pairs("A/B 3 apart", cres);
    print_pose("A/B 3 apart", cres.R, cres.T);
    EXPECT(cres.Colliding() == 0 && cres.NumPairs() == 0);
    EXPECT(relative_pose_ok(cres.R, cres.T, R1, T1, R2, T2));
    check_stats(cres);
    {
        PQP_REAL To[3] = {0.5, 0.5, 0.5};
        EXPECT(PQP_Collide(&cres, R1, T1, a, R2, To, &b, PQP_FIRST_CONTACT) == PQP_OK);
        printf("A/B overlapping, first contact: Colliding %d NumPairs %d\n", cres.Colliding(),
               cres.NumPairs());
        EXPECT(cres.Colliding() == 1 && cres.NumPairs() == 1);
        EXPECT(cres.Id1(0) >= 100 && cres.Id1(0) < 112 && cres.Id2(0) >= 200 && cres.Id2(0) < 212);
    }
    // The rail crosses fence triangles 3, 4, 5, 6 (the planes x = 3..6 between x = 2.5 and 6).
    {
        PQP_REAL Tr[3] = {2.5, 0, 0};
        EXPECT(PQP_Collide(&cres, R1, T1, &fence, R2, Tr, &rail, PQP_ALL_CONTACTS) == PQP_OK);
        print_pairs("fence/rail", cres);
        print_pose("fence/rail", cres.R, cres.T);
        EXPECT(cres.NumPairs() == 4 && cres.num_pairs_alloced >= 4);
        check_stats(cres);
        int seen = 0;
        for (int k = 0; k < cres.num_pairs; k++) {
            EXPECT(cres.pairs[k].id2 == 7);
            if (cres.pairs[k].id1 >= 3 && cres.pairs[k].id1 <= 6) seen |= 1 << cres.pairs[k].id1;
        }
        EXPECT(seen == 0x78);

        // The same scene moved rigidly: both models turned by Q and shifted by t.
        PQP_REAL Q[3][3], t[3] = {0.3, -1.2, 2.0}, Tq[3];
        corner_first(Q);
        for (int i = 0; i < 3; i++) Tq[i] = Q[i][0] * 2.5 + t[i];
        EXPECT(PQP_Collide(&cres, Q, t, &fence, Q, Tq, &rail) == PQP_OK);
        print_pairs("fence/rail moved", cres);
        print_pose("fence/rail moved", cres.R, cres.T);
        EXPECT(cres.NumPairs() == 4);
        EXPECT(relative_pose_ok(cres.R, cres.T, Q, t, Q, Tq));

        EXPECT(PQP_Collide(&cres, Q, t, &fence, Q, Tq, &rail, PQP_FIRST_CONTACT) == PQP_OK);
        bool valid = cres.NumPairs() == 1 && cres.Id1(0) >= 3 && cres.Id1(0) <= 6 &&
                     cres.Id2(0) == 7;
        printf("fence/rail moved, first contact: NumPairs %d, pair valid %d\n", cres.NumPairs(),
               valid ? 1 : 0);
        EXPECT(valid);
    }

    // ---- PQP_Distance ---------------------------------------------------------------------------
    // A and B 3 apart along x: faces x = 1 and x = 3 face each other, distance 2 (many closest
    // pairs: the points are not printed).
    EXPECT(PQP_Distance(&dres, R1, T1, a, R2, T2, &b, 0.0, 0.0) == PQP_OK);
    printf("A/B distance %.9g rel_err %.9g abs_err %.9g\n", dres.Distance(), dres.rel_err,
           dres.abs_err);
    print_pose("A/B distance", dres.R, dres.T);
    EXPECT(near_value(dres.distance, 2.0) && dres.Distance() == dres.distance);
    EXPECT(dres.rel_err == 0.0 && dres.abs_err == 0.0);
    EXPECT(dres.P1() == dres.p1 && dres.P2() == dres.p2);
    check_stats(dres);
    // B turned so that its corner (0,0,0) is its unique nearest point, at (3, 0.5, 0.5): the
    // closest pair is unique, (1, 0.5, 0.5) on A and B's corner, in B's frame (0, 0, 0).
    {
        PQP_REAL Rb[3][3], Tb[3] = {3, 0.5, 0.5};
        corner_first(Rb);
        EXPECT(PQP_Distance(&dres, R1, T1, a, Rb, Tb, &b, 0.0, 0.0) == PQP_OK);
        printf("A/B turned distance %.9g\n", dres.distance);
        print_vector("A/B turned P1", dres.P1());
        print_vector("A/B turned P2", dres.P2());
        print_pose("A/B turned", dres.R, dres.T);
        EXPECT(near_value(dres.distance, 2.0));
        EXPECT(near_value(dres.p1[0], 1) && near_value(dres.p1[1], 0.5) && near_value(dres.p1[2], 0.5));
        EXPECT(fabs(dres.p2[0]) < 1e-12 && fabs(dres.p2[1]) < 1e-12 && fabs(dres.p2[2]) < 1e-12);
        EXPECT(relative_pose_ok(dres.R, dres.T, R1, T1, Rb, Tb));
        // The same with a queue of 10 (PQP 1.3 stores qsize only when it is above 2).
        EXPECT(PQP_Distance(&dres, R1, T1, a, Rb, Tb, &b, 0.0, 0.0, 10) == PQP_OK);
        printf("A/B turned, qsize 10: distance %.9g qsize %d\n", dres.distance, dres.qsize);
        print_vector("A/B turned, qsize 10: p1", dres.p1);
        print_vector("A/B turned, qsize 10: p2", dres.p2);
        EXPECT(near_value(dres.distance, 2.0) && dres.qsize == 10);
        check_stats(dres);
        // last_tri points into the model's tris (PQP 1.3 moves it to the last closest triangle).
        Tri *lt = a->last_tri, *t0 = a->tris;
        bool inside = lt >= t0 && lt < t0 + a->num_tris;
        printf("A last_tri in tris after a distance query %d\n", inside ? 1 : 0);
        EXPECT(inside);
    }
    // Within 10% or 0.1: any answer in [2, 2.1] is right.
    EXPECT(PQP_Distance(&dres, R1, T1, a, R2, T2, &b, 0.1, 0.1) == PQP_OK);
    bool within = dres.distance >= 2.0 - 1e-12 && dres.distance <= 2.1 + 1e-12;
    printf("A/B approximate distance within [2, 2.1] %d, rel_err %.9g abs_err %.9g\n",
           within ? 1 : 0, dres.rel_err, dres.abs_err);
    EXPECT(within && near_value(dres.rel_err, 0.1) && near_value(dres.abs_err, 0.1));
    {
        PQP_REAL To[3] = {0.5, 0.5, 0.5};
        EXPECT(PQP_Distance(&dres, R1, T1, a, R2, To, &b, 0.0, 0.0, 2) == PQP_OK);
        printf("A/B overlapping distance %.9g\n", dres.distance);
        EXPECT(dres.distance == 0.0);
    }

    // ---- PQP_Tolerance --------------------------------------------------------------------------
    // C (z = 0) and D lifted by 1.5: D's vertex (0.25, 0.25, 0) is the unique nearest point, 1.5
    // above C's point (0.25, 0.25, 0).
    {
        PQP_REAL Td[3] = {0, 0, 1.5};
        EXPECT(PQP_Tolerance(&tres, R1, T1, &c, R2, Td, &d, 2.0) == PQP_OK);
        printf("C/D tolerance %.9g: closer %d CloserThanTolerance %d distance %.9g\n",
               tres.tolerance, tres.closer_than_tolerance, tres.CloserThanTolerance(),
               tres.Distance());
        print_vector("C/D tolerance P1", tres.P1());
        print_vector("C/D tolerance P2", tres.P2());
        print_pose("C/D tolerance", tres.R, tres.T);
        EXPECT(tres.closer_than_tolerance == 1 && tres.CloserThanTolerance() == 1);
        EXPECT(tres.tolerance == 2.0 && near_value(tres.distance, 1.5));
        EXPECT(tres.Distance() == tres.distance && tres.P1() == tres.p1 && tres.P2() == tres.p2);
        EXPECT(near_value(tres.p1[0], 0.25) && near_value(tres.p1[1], 0.25) && fabs(tres.p1[2]) < 1e-12);
        EXPECT(near_value(tres.p2[0], 0.25) && near_value(tres.p2[1], 0.25) && fabs(tres.p2[2]) < 1e-12);
        EXPECT(relative_pose_ok(tres.R, tres.T, R1, T1, R2, Td));
        check_stats(tres);
        EXPECT(PQP_Tolerance(&tres, R1, T1, &c, R2, Td, &d, 2.0, 10) == PQP_OK);
        printf("C/D tolerance 2, qsize 10: closer %d distance %.9g qsize %d\n",
               tres.closer_than_tolerance, tres.distance, tres.qsize);
        print_vector("C/D tolerance 2, qsize 10: p1", tres.p1);
        print_vector("C/D tolerance 2, qsize 10: p2", tres.p2);
        EXPECT(tres.closer_than_tolerance == 1 && near_value(tres.distance, 1.5) && tres.qsize == 10);
        // Not closer: only the flag and the tolerance are specified.
        EXPECT(PQP_Tolerance(&tres, R1, T1, &c, R2, Td, &d, 1.0) == PQP_OK);
        printf("C/D tolerance %.9g: closer %d\n", tres.tolerance, tres.CloserThanTolerance());
        EXPECT(tres.closer_than_tolerance == 0 && tres.tolerance == 1.0);
    }
    // A and B 3 apart: within 2.5 (several pairs are: the distance is one of them, <= 2.5), not
    // within 1.5.
    EXPECT(PQP_Tolerance(&tres, R1, T1, a, R2, T2, &b, 2.5) == PQP_OK);
    within = tres.distance >= 2.0 - 1e-12 && tres.distance <= 2.5;
    printf("A/B tolerance %.9g: closer %d, distance within [2, 2.5] %d\n", tres.tolerance,
           tres.closer_than_tolerance, within ? 1 : 0);
    EXPECT(tres.closer_than_tolerance == 1 && within);
    // (qsize is not printed: PQP 1.3 stores it only when the roots' volumes are within the
    // tolerance, which depends on the volumes it fitted.)
    EXPECT(PQP_Tolerance(&tres, R1, T1, a, R2, T2, &b, 1.5, 5) == PQP_OK);
    printf("A/B tolerance %.9g: closer %d\n", tres.tolerance, tres.closer_than_tolerance);
    EXPECT(tres.closer_than_tolerance == 0);
    check_stats(tres);

    // ---- BV: FitToTris, BV_Overlap, BV_Distance -------------------------------------------------
    {
        BV fit;
        memset(&fit, 0, sizeof fit);
        fit.first_child = 5;
        PQP_REAL O[3][3];
        identity(O);
        fit.FitToTris(O, a->tris, a->num_tris);
        bool keeps_o = memcmp(fit.R, O, sizeof O) == 0 && fit.first_child == 5;
        bool contains = all_vertices_in(fit, a->tris, a->num_tris);
        printf("FitToTris on A: R == O %d, contains every vertex %d, Leaf %d, GetSize positive %d\n",
               keeps_o ? 1 : 0, contains ? 1 : 0, fit.Leaf(), fit.GetSize() > 0 ? 1 : 0);
        EXPECT(keeps_o && contains && fit.Leaf() == 0 && fit.GetSize() > 0);
        // The box fitted on A's axes holds the unit box: half extents at least 0.5.
        EXPECT(fit.d[0] >= 0.5 - 1e-12 && fit.d[1] >= 0.5 - 1e-12 && fit.d[2] >= 0.5 - 1e-12);
        EXPECT(fit.l[0] >= 0 && fit.l[1] >= 0 && fit.r >= 0);
    }
    {
        // Two cubes of half side 1: apart when their centres are 3 apart along x, overlapping at
        // 1.5; the second turned 45 degrees about z reaches sqrt(2) from its centre.
        BV b1, b2;
        memset(&b1, 0, sizeof b1);
        memset(&b2, 0, sizeof b2);
        for (int i = 0; i < 3; i++) b1.d[i] = b2.d[i] = 1;
        PQP_REAL R[3][3], T[3] = {3, 0, 0};
        identity(R);
        int apart = BV_Overlap(R, T, &b1, &b2);
        T[0] = 1.5;
        int overlapping = BV_Overlap(R, T, &b1, &b2);
        const double h = sqrt(0.5);
        PQP_REAL Rz[3][3] = {{h, -h, 0}, {h, h, 0}, {0, 0, 1}}, Tz[3] = {3.3, 0, 0};
        int turned_apart = BV_Overlap(Rz, Tz, &b1, &b2);
        Tz[0] = 2.3;
        int turned_overlapping = BV_Overlap(Rz, Tz, &b1, &b2);
        printf("BV_Overlap: %d %d, turned %d %d\n", apart, overlapping, turned_apart,
               turned_overlapping);
        EXPECT(apart == 0 && overlapping == 1 && turned_apart == 0 && turned_overlapping == 1);

        // Unit squares swept by 0.25: stacked 2 apart, and perpendicular with a gap of 2 between
        // edges. BV_Distance is the rectangles' distance less both radii: 1.5.
        b1.l[0] = b1.l[1] = b2.l[0] = b2.l[1] = 1;
        b1.r = b2.r = 0.25;
        PQP_REAL Ts[3] = {0, 0, 2};
        PQP_REAL stacked = BV_Distance(R, Ts, &b1, &b2);
        PQP_REAL Rx[3][3] = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, Tx[3] = {0, 3, 0};
        PQP_REAL perpendicular = BV_Distance(Rx, Tx, &b1, &b2);
        printf("BV_Distance: stacked %.9g, perpendicular %.9g\n", stacked, perpendicular);
        EXPECT(near_value(stacked, 1.5) && near_value(perpendicular, 1.5));
    }

    // ---- MatVec.h and TriDist.h ------------------------------------------------------------
    // Every helper, on small exact inputs; the printed values are exact in binary or rounded to
    // 9 digits. Printing helpers (Mprint, Vprint, ...) write to stdout in both.
    {
        PQP_REAL A[3][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 10}};
        PQP_REAL B[3][3] = {{2, 0, 1}, {1, 3, 0}, {0, 1, 4}};
        PQP_REAL u[3] = {1, 2, 3}, v[3] = {-2, 0.5, 4}, w[3], M[3][3], N[3][3];
        printf("MatVec Mprintg:\n");
        Mprintg(A);
        printf("MatVec Mprint:\n");
        Mprint(B);
        printf("MatVec Mfprint:\n");
        fflush(stdout);
        Mfprint(stdout, A);
        printf("MatVec Vprintg/Vprint/Vfprint:\n");
        Vprintg(u);
        Vprint(v);
        fflush(stdout);
        Vfprint(stdout, u);
        Midentity(M);
        print_pose("MatVec Midentity/Videntity", M, (Videntity(w), w));
        McM(M, A);
        print_pose("MatVec McM", M, u);
        MTcM(M, A);
        print_pose("MatVec MTcM", M, u);
        VcV(w, v);
        print_vector("MatVec VcV", w);
        McolcV(w, A, 2);
        print_vector("MatVec McolcV 2", w);
        Midentity(M);
        McolcMcol(M, 0, A, 1);
        print_pose("MatVec McolcMcol 0<-1", M, u);
        MxMpV(M, A, B, u);
        print_pose("MatVec MxMpV", M, u);
        MxM(M, A, B);
        print_pose("MatVec MxM", M, u);
        MxMT(M, A, B);
        print_pose("MatVec MxMT", M, u);
        MTxM(M, A, B);
        print_pose("MatVec MTxM", M, u);
        MxV(w, A, u);
        print_vector("MatVec MxV", w);
        MxVpV(w, A, u, v);
        print_vector("MatVec MxVpV", w);
        sMxVpV(w, 2, A, u, v);
        print_vector("MatVec sMxVpV", w);
        MTxV(w, A, u);
        print_vector("MatVec MTxV", w);
        sMTxV(w, 0.5, A, u);
        print_vector("MatVec sMTxV", w);
        sMxV(w, -1, A, u);
        print_vector("MatVec sMxV", w);
        VmV(w, u, v);
        print_vector("MatVec VmV", w);
        VpV(w, u, v);
        print_vector("MatVec VpV", w);
        VpVxS(w, u, v, 0.25);
        print_vector("MatVec VpVxS", w);
        MskewV(M, u);
        print_pose("MatVec MskewV", M, u);
        VcrossV(w, u, v);
        print_vector("MatVec VcrossV", w);
        PQP_REAL len3[3] = {3, 4, 12};
        printf("MatVec Vlength %.9g VdotV %.9g VdistV2 %.9g\n", Vlength(len3), VdotV(u, v),
               VdistV2(u, v));
        Vnormalize(len3);
        print_vector("MatVec Vnormalize", len3);
        VxS(w, v, -2);
        print_vector("MatVec VxS", w);
        const PQP_REAL x = -2.5;
        printf("MatVec myfabs %.9g M_PI %.9g QX %d QY %d QZ %d QW %d\n", myfabs(x), (double)M_PI,
               QX, QY, QZ, QW);
        MRotZ(M, (PQP_REAL)(M_PI / 2));
        print_pose("MatVec MRotZ pi/2", M, u);
        MRotX(M, (PQP_REAL)(M_PI / 2));
        print_pose("MatVec MRotX pi/2", M, u);
        MRotY(M, (PQP_REAL)(M_PI / 2));
        print_pose("MatVec MRotY pi/2", M, u);
        double ogl[16];
        MVtoOGL(ogl, A, u);
        printf("MatVec MVtoOGL");
        for (int k = 0; k < 16; k++) printf(" %g", ogl[k]);
        printf("\n");
        PQP_REAL T[3];
        OGLtoMV(M, T, ogl);
        print_pose("MatVec OGLtoMV", M, T);
        // The quaternion (x, y, z, w) of a half turn about z, and a quarter turn about x
        // (unnormalized: MRotQ scales by 2 / |q|^2).
        PQP_REAL q1[4] = {0, 0, 1, 0}, q2[4] = {1, 0, 0, 1};
        MRotQ(M, q1);
        print_pose("MatVec MRotQ z half turn", M, u);
        MRotQ(M, q2);
        print_pose("MatVec MRotQ x quarter turn", M, u);
        // Mqinverse of a rotation is its inverse, the transpose.
        PQP_REAL Rq[3][3];
        MRotZ(Rq, (PQP_REAL)0.5);
        MxM(N, Rq, Rq);
        Mqinverse(M, N);
        MxM(Rq, M, N);
        print_pose("MatVec Mqinverse(R) * R", Rq, u);
        // Meigen of a symmetric matrix with eigenvalues 1, 2, 4: check A v = lambda v; print
        // the sorted eigenvalues (the order and signs of the eigenvectors are unspecified).
        PQP_REAL S[3][3] = {{1, 0, 0}, {0, 3, 1}, {0, 1, 3}}, S0[3][3], E[3][3], ev[3];
        McM(S0, S);
        Meigen(E, ev, S);
        double worst = 0;
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++) {
                double sv = S0[r][0] * E[0][c] + S0[r][1] * E[1][c] + S0[r][2] * E[2][c];
                worst = std::max(worst, fabs(sv - ev[c] * E[r][c]));
            }
        std::sort(ev, ev + 3);
        printf("MatVec Meigen eigenvalues %.9g %.9g %.9g, A v = lambda v %d\n", ev[0], ev[1],
               ev[2], worst < 1e-9 ? 1 : 0);
        EXPECT(near_value(ev[0], 1) && near_value(ev[1], 2) && near_value(ev[2], 4));
        EXPECT(worst < 1e-9);

        // TriDist: two triangles with one closest pair, 1 apart along z.
        PQP_REAL s[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        PQP_REAL t[3][3] = {{0.25, 0.25, 1}, {2, 2, 3}, {2, -1, 3}};
        PQP_REAL p[3], qq[3];
        PQP_REAL d = TriDist(p, qq, s, t);
        printf("TriDist %.9g\n", d);
        print_vector("TriDist p", p);
        print_vector("TriDist q", qq);
        EXPECT(near_value(d, 1));
        // SegPoints: the segments x in [0,1] at y = z = 0 and y in [-1,1] at x = 0.5, z = 2.
        PQP_REAL P0[3] = {0, 0, 0}, A0[3] = {1, 0, 0}, Q0[3] = {0.5, -1, 2}, B0[3] = {0, 2, 0};
        PQP_REAL VEC[3], X[3], Y[3];
        SegPoints(VEC, X, Y, P0, A0, Q0, B0);
        print_vector("SegPoints X", X);
        print_vector("SegPoints Y", Y);
        EXPECT(near_value(X[0], 0.5) && near_value(Y[2], 2) && near_value(VdistV2(X, Y), 4));
        // VEC is a direction from the first segment towards the second (PQP 1.3 does not
        // normalize it): print its direction only.
        PQP_REAL vl = Vlength(VEC);
        PQP_REAL dir[3] = {VEC[0] / vl, VEC[1] / vl, VEC[2] / vl};
        print_vector("SegPoints VEC direction", dir);
    }

    delete a;  // the destructor
    if (failures) {
        fprintf(stderr, "every_member: %d check(s) failed\n", failures);
        return 1;
    }
    printf("every_member: all checks passed\n");
    return 0;
}
