// See fresh_cxx.hpp: pqp-rs's PQP.h, each query as a legacy PQP program writes it.
#include "fresh_cxx.hpp"

#include <PQP.h>

namespace fresh_cxx {

struct Model {
    PQP_Model m;
};

namespace {

struct Pose {
    PQP_REAL R[3][3], T[3];
    Pose(const double* r, const double* t) {
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

double distance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                      const double* T2, Model* m2, double rel_err, double abs_err) {
    Pose a(R1, T1), b(R2, T2);
    PQP_DistanceResult dres;
    PQP_Distance(&dres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, rel_err, abs_err);
    return dres.Distance();
}

int collide_first_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                        const double* T2, Model* m2) {
    Pose a(R1, T1), b(R2, T2);
    PQP_CollideResult cres;
    PQP_Collide(&cres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, PQP_FIRST_CONTACT);
    return cres.Colliding();
}

int tolerance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                    const double* T2, Model* m2, double tol) {
    Pose a(R1, T1), b(R2, T2);
    PQP_ToleranceResult tres;
    PQP_Tolerance(&tres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, tol);
    return tres.CloserThanTolerance();
}

double distance_reused(const double* R1, const double* T1, Model* m1, const double* R2,
                       const double* T2, Model* m2, double rel_err, double abs_err) {
    static PQP_DistanceResult dres;
    Pose a(R1, T1), b(R2, T2);
    PQP_Distance(&dres, a.R, a.T, &m1->m, b.R, b.T, &m2->m, rel_err, abs_err);
    return dres.Distance();
}

}  // namespace fresh_cxx
