"""The same quantities as python-fcl and trimesh (both from PyPI) on the same models and poses."""

import numpy as np
import pytest

import pqp
from conftest import random_pose, random_soup, uv_sphere

fcl = pytest.importorskip("fcl")


def fcl_object(v, f, pose):
    g = fcl.BVHModel()
    g.beginModel(len(v), len(f))
    g.addSubModel(np.asarray(v, float), np.asarray(f, np.int32))
    g.endModel()
    return fcl.CollisionObject(g, fcl.Transform(pose[:3, :3], pose[:3, 3]))


def fcl_pairs(o1, o2):
    req = fcl.CollisionRequest(num_max_contacts=100000, enable_contact=True)
    res = fcl.CollisionResult()
    fcl.collide(o1, o2, req, res)
    return {(c.b1, c.b2) for c in res.contacts}


def fcl_distance(o1, o2):
    res = fcl.DistanceResult()
    return fcl.distance(o1, o2, fcl.DistanceRequest(enable_nearest_points=True), res)


@pytest.mark.parametrize("seed", range(4))
def test_collide_and_distance_match_fcl(seed):
    rng = np.random.default_rng(100 + seed)
    v1, f1 = uv_sphere(1.0, 8, 10)
    v2, f2 = random_soup(rng, 60, 1.2, 0.3)
    m1, m2 = pqp.Model(v1, f1), pqp.Model(v2, f2)
    poses1 = np.stack([random_pose(rng, 2.2) for _ in range(20)])
    poses2 = np.stack([random_pose(rng, 0.3) for _ in range(20)])
    hits = pqp.collide_batch(m1, poses1, m2, poses2)
    dists = pqp.distance_batch(m1, poses1, m2, poses2)
    n_hit = 0
    for i in range(20):
        o1, o2 = fcl_object(v1, f1, poses1[i]), fcl_object(v2, f2, poses2[i])
        ours = {tuple(p) for p in pqp.collide(m1, poses1[i], m2, poses2[i]).tolist()}
        assert ours == fcl_pairs(o1, o2)
        assert hits[i] == bool(ours)
        n_hit += bool(ours)
        if not ours:
            d = fcl_distance(o1, o2)
            assert dists[i] == pytest.approx(d, abs=1e-9)
            assert pqp.distance(m1, poses1[i], m2, poses2[i])[0] == dists[i]
    assert 0 < n_hit < 20


def test_primitives_match_fcl(rng):
    v, f = uv_sphere(1.0, 8, 10)
    mesh_obj = lambda p: fcl_object(v, f, p)  # noqa: E731
    mesh = pqp.Model(v, f)
    shapes = [
        (pqp.Model.sphere(0.4), fcl.Sphere(0.4)),
        (pqp.Model.box(0.5, 0.8, 1.1), fcl.Box(0.5, 0.8, 1.1)),
        (pqp.Model.capsule(0.3, 1.0), fcl.Capsule(0.3, 1.0)),
    ]
    for ours, theirs in shapes:
        for _ in range(10):
            p, q = random_pose(rng, 2.5), random_pose(rng, 0.2)
            o = fcl.CollisionObject(theirs, fcl.Transform(p[:3, :3], p[:3, 3]))
            res = fcl.CollisionResult()
            hit = fcl.collide(o, mesh_obj(q), fcl.CollisionRequest(), res) > 0
            d_ours = pqp.distance(ours, p, mesh, q)[0]
            if not hit:
                # FCL's shape-mesh distance goes through GJK: agree to its tolerance.
                assert d_ours == pytest.approx(fcl_distance(o, mesh_obj(q)), abs=1e-5)
            elif d_ours > 1e-6:
                pytest.fail(f"fcl reports contact, distance {d_ours}")


def test_closest_points_match_trimesh(rng):
    trimesh = pytest.importorskip("trimesh")
    tm = trimesh.creation.icosphere(subdivisions=2)
    m = pqp.Model(tm)
    pts = rng.uniform(-2, 2, (500, 3))
    c_t, d_t, f_t = trimesh.proximity.closest_point(tm, pts)
    d, c, faces = pqp.closest_point(m, None, pts)
    np.testing.assert_allclose(d, d_t, atol=1e-9)
    np.testing.assert_allclose(c, c_t, atol=1e-6)
    # trimesh's signed distance is positive inside: ours is negative inside.
    np.testing.assert_allclose(pqp.signed_distance(m, None, pts), -trimesh.proximity.signed_distance(tm, pts), atol=1e-9)
    # A Trimesh wherever a model goes.
    assert pqp.distance(tm, None, m, None)[0] == 0.0
    assert pqp.Model(tm).num_triangles == len(tm.faces)
