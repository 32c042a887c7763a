"""Every query against NumPy brute force over all triangles (pairs) on small models."""

import numpy as np
import pytest

import pqp
from brute import all_pairs, point_triangle, posed, ray_triangles, tri_tri_distance, tri_tri_overlap
from conftest import random_pose, random_soup, uv_sphere


def brute_pairs(v1, f1, p1, v2, f2, p2):
    t1, t2 = posed(v1, f1, p1), posed(v2, f2, p2)
    return tri_tri_distance(*all_pairs(t1, t2)), tri_tri_overlap(*all_pairs(t1, t2))


def pair_set(a):
    return {tuple(r) for r in np.asarray(a).tolist()}


@pytest.mark.parametrize("seed", range(6))
def test_pair_queries_match_brute_force(seed):
    rng = np.random.default_rng(seed)
    v1, f1 = random_soup(rng, 30)
    v2, f2 = uv_sphere(0.7, 5, 7)
    m1, m2 = pqp.Model(v1, f1), pqp.Model(v2, f2)
    for _ in range(8):
        p1, p2 = random_pose(rng, 0.5), random_pose(rng, 0.8)
        d_all, hit_all = brute_pairs(v1, f1, p1, v2, f2, p2)
        pairs = pqp.collide(m1, p1, m2, p2)
        assert pairs.dtype == np.int64 and pairs.shape[1] == 2
        assert pair_set(pairs) == pair_set(np.argwhere(hit_all))
        first = pqp.collide(m1, p1, m2, p2, first=True)
        assert len(first) == min(1, len(pairs))
        assert pair_set(first) <= pair_set(pairs)
        d, q1, q2 = pqp.distance(m1, p1, m2, p2)
        assert d == pytest.approx(d_all.min(), abs=1e-12)
        # The closest points are on the posed models and d apart.
        assert np.linalg.norm(q1 - q2) == pytest.approx(d, abs=1e-12)
        assert point_triangle(q1, posed(v1, f1, p1)).min() < 1e-12
        assert point_triangle(q2, posed(v2, f2, p2)).min() < 1e-12
        da, _, _ = pqp.distance(m1, p1, m2, p2, rel_err=0.1, abs_err=0.05)
        assert d - 1e-12 <= da <= min(d * 1.1, d + 0.05) + 1e-12
        for tol in (0.05, 0.2):
            within, dists = pqp.within_distance(m1, p1, m2, p2, tol)
            assert pair_set(within) == pair_set(np.argwhere(d_all <= tol))
            np.testing.assert_allclose(dists, d_all[within[:, 0], within[:, 1]], atol=1e-12)
            if abs(d - tol) > 1e-9:
                assert pqp.tolerance(m1, p1, m2, p2, tol) == (d <= tol)


def test_point_queries_match_brute_force(rng):
    v, f = uv_sphere(1.0, 6, 9)
    m = pqp.Model(v, f)
    pose = random_pose(rng, 0.3)
    pts = rng.uniform(-2, 2, (300, 3))
    tris = posed(v, f, pose)
    d_all = point_triangle(pts[:, None], tris[None])
    d, c, faces = pqp.closest_point(m, pose, pts)
    np.testing.assert_allclose(d, d_all.min(axis=1), atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(c - pts, axis=1), d, atol=1e-12)
    np.testing.assert_allclose(d_all[np.arange(len(pts)), faces], d, atol=1e-12)
    # Within a max distance, farther points get inf, nan, -1.
    d2, c2, f2 = pqp.closest_point(m, pose, pts, max_distance=0.5)
    far = d_all.min(axis=1) > 0.5
    assert np.all(np.isinf(d2[far])) and np.all(np.isnan(c2[far])) and np.all(f2[far] == -1)
    np.testing.assert_allclose(d2[~far], d[~far], atol=1e-12)
    # Signed: negative inside the closed sphere (inside its polyhedron: every face's plane).
    sd = pqp.signed_distance(m, pose, pts)
    np.testing.assert_allclose(np.abs(sd), d, atol=1e-12)
    a, b, cc = tris[:, 0], tris[:, 1], tris[:, 2]
    n = np.cross(b - a, cc - a)
    centre = pose[:3, 3]
    n *= np.sign(np.einsum("ij,ij->i", n, a - centre))[:, None]
    inside = np.all(np.einsum("qkj,kj->qk", pts[:, None] - a[None], n) < 0, axis=1)
    assert np.array_equal(sd < 0, inside & (d > 0))
    # Threads give the same answers.
    for threads in (1, 2, 5):
        assert np.array_equal(pqp.closest_point(m, pose, pts, threads=threads)[0], d)
        assert np.array_equal(pqp.signed_distance(m, pose, pts, threads=threads), sd)


def test_ray_cast_matches_brute_force(rng):
    v, f = random_soup(rng, 50)
    m = pqp.Model(v, f)
    pose = random_pose(rng, 0.2)
    tris = posed(v, f, pose)
    o = rng.uniform(-3, 3, (200, 3))
    d = rng.uniform(-1, 1, (200, 3)) - 0.3 * o
    t, faces = pqp.ray_cast(m, pose, o, d)
    hits = 0
    for i in range(len(o)):
        bt, bk = ray_triangles(o[i], d[i], tris)
        assert t[i] == pytest.approx(bt, rel=1e-9, abs=1e-12)
        if np.isfinite(bt):
            hits += 1
            assert faces[i] == bk or abs(ray_triangles(o[i], d[i], tris[[faces[i]]])[0] - bt) < 1e-9
        else:
            assert faces[i] == -1
    assert hits > 10
    t2, _ = pqp.ray_cast(m, pose, o, d, max_t=0.5)
    assert np.all((t2 <= 0.5) | np.isinf(t2))
    np.testing.assert_array_equal(t2[t <= 0.5], t[t <= 0.5])


def test_batches_match_single_calls(rng):
    v1, f1 = uv_sphere(0.5, 5, 6)
    v2, f2 = random_soup(rng, 30)
    m1, m2 = pqp.Model(v1, f1), pqp.Model(v2, f2)
    poses1 = np.stack([random_pose(rng, 1.5) for _ in range(100)])
    poses2 = np.stack([random_pose(rng, 0.2) for _ in range(100)])
    hit = pqp.collide_batch(m1, poses1, m2, poses2)
    dist = pqp.distance_batch(m1, poses1, m2, poses2, threads=2)
    assert hit.dtype == bool and dist.dtype == np.float64 and hit.shape == dist.shape == (100,)
    for i in range(100):
        assert hit[i] == (len(pqp.collide(m1, poses1[i], m2, poses2[i], first=True)) > 0)
        assert dist[i] == pqp.distance(m1, poses1[i], m2, poses2[i])[0]
    assert 0 < hit.sum() < 100
    # A single pose on one side is used for every query.
    one = pqp.distance_batch(m1, poses1, m2, None)
    assert one[7] == pqp.distance(m1, poses1[7], m2, None)[0]
    assert pqp.collide_batch(m1, np.zeros((0, 4, 4)), m2, None).shape == (0,)


def test_poses_as_pairs_and_dtypes(rng):
    v, f = uv_sphere(1.0)
    m = pqp.Model(v.astype(np.float32), f.astype(np.uint16))
    m64 = pqp.Model(v.tolist(), f.astype(np.float64))
    p = random_pose(rng)
    d = pqp.distance(m, None, m64, p)[0]
    assert pqp.distance(m64, np.eye(4), m64, (p[:3, :3], p[:3, 3]))[0] == pytest.approx(d, abs=1e-6)
    assert pqp.distance(m64, None, m64, (p[:3, :3].tolist(), list(p[:3, 3])))[0] == pytest.approx(d, abs=1e-6)
    np.testing.assert_array_equal(m64.faces, f)
    assert m64.vertices.dtype == np.float64 and m64.num_triangles == len(f)
    # A (vertices, faces) pair where a model goes.
    assert pqp.distance((v, f), None, m64, p)[0] == pqp.distance(m64, None, m64, p)[0]


def test_primitives_against_analytic(rng):
    v, f = uv_sphere(1.0, 8, 12)
    mesh = pqp.Model(v, f)
    tris = posed(v, f, np.eye(4))
    for _ in range(10):
        c = rng.uniform(-4, 4, 3)
        pose = np.eye(4)
        pose[:3, 3] = c
        ball = pqp.Model.sphere(0.3)
        want = max(point_triangle(c[None], tris).min() - 0.3, 0.0)
        assert pqp.distance(ball, pose, mesh, None)[0] == pytest.approx(want, abs=1e-12)
        assert pqp.tolerance(ball, pose, mesh, None, want + 1e-6)
        assert (len(pqp.collide(ball, pose, mesh, None)) > 0) == (want == 0.0)
    box = pqp.Model.box(1.0, 2.0, 3.0)
    cap = pqp.Model.capsule(0.5, 2.0)
    t = np.eye(4)
    t[:3, 3] = [0, 0, 4]
    # Box's top face at z = 1.5, capsule's bottom at 4 - 1 - 0.5 = 2.5.
    assert pqp.distance(box, None, cap, t)[0] == pytest.approx(1.0, abs=1e-12)
    assert box.kind == "box" and cap.kind == "capsule" and box.num_triangles == 0
    with pytest.raises(ValueError, match="model"):
        pqp.closest_point(box, None, [[0, 0, 0]])
    with pytest.raises(ValueError, match="refit"):
        box.refit(np.zeros((0, 3)))


def test_refit_matches_rebuild(rng):
    v, f = uv_sphere(1.0, 6, 8)
    m = pqp.Model(v, f)
    other = pqp.Model(*random_soup(rng, 20))
    v2 = v * 1.3 + rng.normal(scale=0.05, size=v.shape)
    m.refit(v2)
    rebuilt = pqp.Model(v2, f)
    np.testing.assert_array_equal(m.vertices, v2)
    for _ in range(10):
        p = random_pose(rng, 1.0)
        assert pqp.distance(m, None, other, p)[0] == pytest.approx(pqp.distance(rebuilt, None, other, p)[0], abs=1e-12)
        assert pair_set(pqp.collide(m, None, other, p)) == pair_set(pqp.collide(rebuilt, None, other, p))


def test_batch_poses_as_lists_and_primitive_points(rng):
    m = pqp.Model(*uv_sphere(0.5))
    ps = [random_pose(rng, 2.0) for _ in range(2)]
    # A list of two 4x4 matrices is a batch of two, not an (R, T) pair.
    np.testing.assert_array_equal(pqp.distance_batch(m, None, m, ps), pqp.distance_batch(m, None, m, np.stack(ps)))
    ball = pqp.Model.sphere(0.25)
    for p in ps:
        d, q1, q2 = pqp.distance(m, None, ball, p)
        assert np.linalg.norm(q1 - q2) == pytest.approx(d, abs=1e-12)
        # The ball's closest point is on its surface, in world coordinates.
        assert np.linalg.norm(q2 - p[:3, 3]) == pytest.approx(0.25, abs=1e-12)
