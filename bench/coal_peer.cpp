// Coal's side of the benchmark, see coal_peer.hpp.
#include "coal_peer.hpp"

#include <coal/BVH/BVH_model.h>
#include <coal/BV/OBBRSS.h>
#include <coal/collision.h>
#include <coal/distance.h>

#include <limits>

namespace coalpeer {

struct Model {
    coal::BVHModel<coal::OBBRSS> m;
};

namespace {

coal::Transform3s pose(const double* R, const double* T) {
    coal::Matrix3s r;
    r << R[0], R[1], R[2], R[3], R[4], R[5], R[6], R[7], R[8];
    return coal::Transform3s(r, coal::Vec3s(T[0], T[1], T[2]));
}

coal::CollisionRequest request(bool all) {
    // No contact points (as in the FCL columns): only the triangle pairs.
    coal::CollisionRequest req(coal::NO_REQUEST, all ? std::numeric_limits<std::size_t>::max() : 1);
    return req;
}

}  // namespace

Model* build(const double* tris, std::size_t n) {
    Model* model = new Model;
    model->m.beginModel(static_cast<unsigned int>(n), static_cast<unsigned int>(3 * n));
    for (std::size_t k = 0; k < n; ++k) {
        const double* t = tris + 9 * k;
        model->m.addTriangle(coal::Vec3s(t[0], t[1], t[2]), coal::Vec3s(t[3], t[4], t[5]),
                             coal::Vec3s(t[6], t[7], t[8]));
    }
    model->m.endModel();
    return model;
}

void destroy(Model* m) { delete m; }

std::vector<std::pair<int, int>> collide(const double* R1, const double* T1, Model* m1,
                                         const double* R2, const double* T2, Model* m2, bool all) {
    coal::CollisionResult res;
    coal::collide(&m1->m, pose(R1, T1), &m2->m, pose(R2, T2), request(all), res);
    std::vector<std::pair<int, int>> out;
    for (std::size_t k = 0; k < res.numContacts(); ++k)
        out.emplace_back(res.getContact(k).b1, res.getContact(k).b2);
    return out;
}

std::size_t collide_count(const double* R1, const double* T1, Model* m1, const double* R2,
                          const double* T2, Model* m2, bool all) {
    coal::CollisionResult res;
    return coal::collide(&m1->m, pose(R1, T1), &m2->m, pose(R2, T2), request(all), res);
}

double distance(const double* R1, const double* T1, Model* m1, const double* R2,
                const double* T2, Model* m2, double rel_err, double abs_err) {
    // No nearest points (the distance only); signed distance is Coal's default.
    coal::DistanceRequest req(false, true, rel_err, abs_err);
    coal::DistanceResult res;
    return coal::distance(&m1->m, pose(R1, T1), &m2->m, pose(R2, T2), req, res);
}

}  // namespace coalpeer
