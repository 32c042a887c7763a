"""Bad input raises ValueError naming the argument; nothing crashes."""

import numpy as np
import pytest

import pqp
from conftest import uv_sphere

V, F = uv_sphere()
M = pqp.Model(V, F)
P = [[0, 0, 0.0]]


@pytest.mark.parametrize(
    "vertices, faces, name",
    [
        (V[:, :2], F, "vertices"),
        (V.ravel(), F, "vertices"),
        (np.where(np.arange(len(V))[:, None] == 3, np.nan, V), F, "vertices"),
        (np.where(np.arange(len(V))[:, None] == 3, np.inf, V), F, "vertices"),
        (V * 1e200, F, "vertices"),
        ("abc", F, "vertices"),
        ([[1, 2, 3], [4, 5]], F, "vertices"),
        (V, F + len(V), "faces"),
        (V, F - 1, "faces"),
        (V, F[:, :2], "faces"),
        (V, F + 0.5, "faces"),
        (V, np.zeros((0, 3), int), "faces"),
        (V, np.full_like(F, np.nan, dtype=float), "faces"),
    ],
)
def test_bad_models(vertices, faces, name):
    with pytest.raises(ValueError, match=name):
        pqp.Model(vertices, faces)


def test_model_needs_faces():
    with pytest.raises(TypeError):
        pqp.Model(V)


def scaled(s):
    p = np.eye(4)
    p[:3, :3] *= s
    return p


def reflected():
    p = np.eye(4)
    p[0, 0] = -1
    return p


def nan_pose():
    p = np.eye(4)
    p[1, 3] = np.nan
    return p


def bottom_row():
    p = np.eye(4)
    p[3, 0] = 1
    return p


@pytest.mark.parametrize(
    "pose", [scaled(2.0), reflected(), nan_pose(), bottom_row(), np.eye(3), np.eye(4)[None], "x", (np.eye(3), [1, 2]), (np.eye(2), [1, 2, 3])]
)
def test_bad_poses(pose):
    for call in (
        lambda: pqp.collide(M, pose, M, None),
        lambda: pqp.distance(M, pose, M, None),
        lambda: pqp.tolerance(M, pose, M, None, 0.1),
        lambda: pqp.within_distance(M, pose, M, None, 0.1),
    ):
        with pytest.raises(ValueError, match="pose1"):
            call()
    with pytest.raises(ValueError, match="pose2"):
        pqp.distance(M, None, M, pose)
    with pytest.raises(ValueError, match="pose"):
        pqp.closest_point(M, pose, P)
    with pytest.raises(ValueError, match="pose"):
        pqp.signed_distance(M, pose, P)
    with pytest.raises(ValueError, match="pose"):
        pqp.ray_cast(M, pose, P, P)


def test_bad_query_arguments():
    with pytest.raises(ValueError, match="m1"):
        pqp.collide("not a model", None, M, None)
    with pytest.raises(ValueError, match="m2"):
        pqp.distance(M, None, 42, None)
    with pytest.raises(ValueError, match="m1"):
        pqp.distance((V, F + 1000), None, M, None)
    with pytest.raises(ValueError, match="rel_err"):
        pqp.distance(M, None, M, None, rel_err=-1)
    with pytest.raises(ValueError, match="abs_err"):
        pqp.distance(M, None, M, None, abs_err=float("nan"))
    with pytest.raises(ValueError, match="tolerance"):
        pqp.tolerance(M, None, M, None, -0.1)
    with pytest.raises(ValueError, match="d"):
        pqp.within_distance(M, None, M, None, float("nan"))
    with pytest.raises(ValueError, match="points"):
        pqp.closest_point(M, None, [[np.nan, 0, 0]])
    with pytest.raises(ValueError, match="points"):
        pqp.closest_point(M, None, [0, 0, 0])
    with pytest.raises(ValueError, match="max_distance"):
        pqp.closest_point(M, None, P, max_distance=-1)
    with pytest.raises(ValueError, match="points"):
        pqp.signed_distance(M, None, np.zeros((2, 4)))
    with pytest.raises(ValueError, match="directions"):
        pqp.ray_cast(M, None, P, [[0, 0, 0]])
    with pytest.raises(ValueError, match="directions"):
        pqp.ray_cast(M, None, P, [[0, 0, 1], [0, 0, 1]])
    with pytest.raises(ValueError, match="directions"):
        pqp.ray_cast(M, None, P, [[np.inf, 0, 1]])
    with pytest.raises(ValueError, match="origins"):
        pqp.ray_cast(M, None, [[1e300, 0, 0]], [[0, 0, 1]])
    with pytest.raises(ValueError, match="max_t"):
        pqp.ray_cast(M, None, P, [[0, 0, 1]], max_t=float("nan"))
    with pytest.raises(ValueError, match="radius"):
        pqp.Model.sphere(-1)
    with pytest.raises(ValueError, match="length"):
        pqp.Model.capsule(1, float("inf"))
    with pytest.raises(ValueError, match="z"):
        pqp.Model.box(1, 1, float("nan"))
    with pytest.raises(ValueError, match="vertices"):
        M2 = pqp.Model(V, F)
        M2.refit(V[:-1])
    with pytest.raises(ValueError, match="vertices"):
        M2.refit(np.full_like(V, np.nan))
    # The failed refits left the model as it was.
    assert pqp.distance(M2, None, M, None)[0] == 0.0
    np.testing.assert_array_equal(M2.vertices, V)


def test_bad_batches():
    poses = np.stack([np.eye(4)] * 3)
    with pytest.raises(ValueError, match="poses2"):
        pqp.collide_batch(M, poses, M, poses[:2])
    with pytest.raises(ValueError, match=r"poses1\[1\]"):
        bad = poses.copy()
        bad[1, 0, 0] = 2
        pqp.distance_batch(M, bad, M, poses)
    with pytest.raises(ValueError, match="poses1"):
        pqp.distance_batch(M, np.zeros((3, 3, 3)), M, poses)
    with pytest.raises(ValueError, match="m2"):
        pqp.collide_batch(M, poses, None, poses)


def test_negative_threads():
    with pytest.raises(ValueError, match="threads"):
        pqp.closest_point(M, None, P, threads=-1)
    with pytest.raises(ValueError, match="threads"):
        pqp.collide_batch(M, None, M, None, threads=-2)
    with pytest.raises(ValueError, match="threads"):
        pqp.Model(V, F, threads=-1)
