// PQP 1.3's side of the benchmark: compiled against PQP 1.3's own headers (and nothing of pqp-rs),
// see pqp13_peer.hpp.
#include "pqp13_peer.hpp"

#include <PQP.h>

#include <cmath>

namespace pqp13 {

struct Model {
    PQP_Model m;
};

struct Results {
    PQP_CollideResult c;
    PQP_DistanceResult d;
    PQP_ToleranceResult t;
};

namespace {

// PQP 1.3's matrices and vectors from the 9 + 3 doubles of a pose.
struct Pose13 {
    PQP_REAL R[3][3], T[3];
    Pose13(const double* r, const double* t) {
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) R[i][j] = r[3 * i + j];
            T[i] = t[i];
        }
    }
};

}  // namespace

Model* build(const double* tris, std::size_t n) {
    Model* model = new Model;
    int rc = model->m.BeginModel(static_cast<int>(n));
    for (std::size_t k = 0; k < n && rc == PQP_OK; ++k) {
        const double* t = tris + 9 * k;
        rc = model->m.AddTri(t, t + 3, t + 6, static_cast<int>(k));
    }
    if (rc == PQP_OK) rc = model->m.EndModel();
    if (rc != PQP_OK) {
        delete model;
        return nullptr;
    }
    return model;
}

void destroy(Model* m) { delete m; }

Results* results_create() { return new Results; }
void results_destroy(Results* r) { delete r; }

int collide(Results* r, const double* R1, const double* T1, Model* m1, const double* R2,
            const double* T2, Model* m2, bool all) {
    Pose13 a(R1, T1), b(R2, T2);
    return PQP_Collide(&r->c, a.R, a.T, &m1->m, b.R, b.T, &m2->m,
                       all ? PQP_ALL_CONTACTS : PQP_FIRST_CONTACT);
}

std::vector<std::pair<int, int>> pairs(Results* r) {
    std::vector<std::pair<int, int>> out;
    for (int k = 0; k < r->c.NumPairs(); ++k) out.emplace_back(r->c.Id1(k), r->c.Id2(k));
    return out;
}

double distance(Results* r, const double* R1, const double* T1, Model* m1, const double* R2,
                const double* T2, Model* m2, double rel_err, double abs_err, int qsize) {
    Pose13 a(R1, T1), b(R2, T2);
    const int rc = PQP_Distance(&r->d, a.R, a.T, &m1->m, b.R, b.T, &m2->m, rel_err, abs_err, qsize);
    return rc == PQP_OK ? r->d.Distance() : std::nan("");
}

int tolerance(Results* r, const double* R1, const double* T1, Model* m1, const double* R2,
              const double* T2, Model* m2, double tol, int qsize) {
    Pose13 a(R1, T1), b(R2, T2);
    const int rc = PQP_Tolerance(&r->t, a.R, a.T, &m1->m, b.R, b.T, &m2->m, tol, qsize);
    return rc == PQP_OK ? r->t.CloserThanTolerance() : -1;
}

int memory_usage(Model* m) { return m->m.MemUsage(0); }

}  // namespace pqp13

namespace pqp13 {

double distance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                      const double* T2, Model* m2, double rel_err, double abs_err) {
    Pose13 a(R1, T1), b(R2, T2);
    PQP_DistanceResult dres;
    PQP_Distance(&dres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, rel_err, abs_err);
    return dres.Distance();
}

int collide_first_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                        const double* T2, Model* m2) {
    Pose13 a(R1, T1), b(R2, T2);
    PQP_CollideResult cres;
    PQP_Collide(&cres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, PQP_FIRST_CONTACT);
    return cres.Colliding();
}

int tolerance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                    const double* T2, Model* m2, double tol) {
    Pose13 a(R1, T1), b(R2, T2);
    PQP_ToleranceResult tres;
    PQP_Tolerance(&tres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, tol);
    return tres.CloserThanTolerance();
}

}  // namespace pqp13

namespace pqp13 {
int distance_bv_tests(const double* R1, const double* T1, Model* m1, const double* R2,
                      const double* T2, Model* m2, double rel_err, double abs_err) {
    Pose13 a(R1, T1), b(R2, T2);
    PQP_DistanceResult dres;
    PQP_Distance(&dres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, rel_err, abs_err);
    return dres.NumBVTests();
}
}  // namespace pqp13
