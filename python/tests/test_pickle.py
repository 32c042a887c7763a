"""Pickling through the saved-model format, in this process and in worker processes."""

import multiprocessing
import pickle
import threading

import numpy as np
import pytest

import pqp
from conftest import random_pose, random_soup, uv_sphere


def test_round_trip_answers_the_same(rng):
    v, f = uv_sphere(1.0, 7, 9)
    m = pqp.Model(v, f)
    other = pqp.Model(*random_soup(rng, 25))
    data = pickle.dumps(m)
    back = pickle.loads(data)
    assert isinstance(back, pqp.Model) and back.num_triangles == m.num_triangles
    np.testing.assert_array_equal(back.vertices, m.vertices)
    np.testing.assert_array_equal(back.faces, m.faces)
    for _ in range(20):
        p = random_pose(rng, 1.2)
        assert pqp.distance(back, None, other, p)[0] == pqp.distance(m, None, other, p)[0]
        np.testing.assert_array_equal(pqp.collide(back, None, other, p), pqp.collide(m, None, other, p))
    pts = rng.uniform(-2, 2, (50, 3))
    np.testing.assert_array_equal(pqp.closest_point(back, None, pts)[0], pqp.closest_point(m, None, pts)[0])
    # The unpickled model refits like the original.
    back.refit(v * 2)
    assert pqp.distance(back, None, pqp.Model(v * 2, f), None)[0] == 0.0


@pytest.mark.parametrize("prim", [pqp.Model.sphere(0.5), pqp.Model.capsule(0.2, 1.5), pqp.Model.box(1, 2, 3)])
def test_primitives_round_trip(prim):
    back = pickle.loads(pickle.dumps(prim))
    assert back.kind == prim.kind and repr(back) == repr(prim)


def test_corrupt_pickle_raises():
    m = pqp.Model(*uv_sphere())
    fn, (saved, v, f) = m.__reduce__()
    bad = bytearray(saved)
    bad[len(bad) // 2] ^= 0xFF
    with pytest.raises(ValueError, match="saved model"):
        fn(bytes(bad), v, f)
    with pytest.raises(ValueError):
        fn(saved, v, f[:-1])
    with pytest.raises(ValueError):
        fn(b"", v, f)


def _worker(args):
    model, other, pose = args
    return pqp.distance(model, None, other, pose)[0], len(pqp.collide(model, None, other, pose))


def test_multiprocessing_workers_get_models(rng):
    m = pqp.Model(*uv_sphere(1.0, 7, 9))
    other = pqp.Model(*random_soup(rng, 25))
    poses = [random_pose(rng, 1.5) for _ in range(8)]
    want = [_worker((m, other, p)) for p in poses]
    ctx = multiprocessing.get_context("spawn")
    with ctx.Pool(2) as pool:
        got = pool.map(_worker, [(m, other, p) for p in poses])
    assert got == want


def test_threads_share_a_model(rng):
    """Queries release the GIL and may run on one model from many threads at once."""
    m = pqp.Model(*uv_sphere(1.0, 12, 16))
    pts = rng.uniform(-2, 2, (2000, 3))
    want = pqp.closest_point(m, None, pts, threads=1)[0]
    out = [None] * 4

    def run(k):
        out[k] = pqp.closest_point(m, None, pts, threads=1)[0]

    ts = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for o in out:
        np.testing.assert_array_equal(o, want)


def test_queries_release_the_gil(rng):
    """Another Python thread runs while a query is under way (it could not if the GIL were held)."""
    m = pqp.Model(*uv_sphere(1.0, 40, 80))
    pts = rng.uniform(-2, 2, (20000, 3))
    m2 = pqp.Model(*uv_sphere(1.0, 30, 60))
    poses = np.stack([random_pose(rng, 2.5) for _ in range(100)])
    big = uv_sphere(1.0, 100, 200)
    calls = [
        lambda: pqp.closest_point(m, None, pts, threads=1),
        lambda: pqp.signed_distance(m, None, pts[:2000], threads=1),
        lambda: pqp.distance_batch(m, None, m2, poses, threads=1),
        lambda: pqp.Model(*big, threads=1),
    ]
    for call in calls:
        window = []
        ticks = []
        done = threading.Event()

        def run():
            import time

            t0 = time.perf_counter()
            call()
            window.extend([t0, time.perf_counter()])
            done.set()

        import time

        t = threading.Thread(target=run)
        t.start()
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0)
        t.join()
        inside = sum(window[0] < x < window[1] for x in ticks)
        assert inside >= 10, (inside, window[1] - window[0])
