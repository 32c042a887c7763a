"""pqp (the Python package) beside python-fcl and trimesh, in one run, on the same models and
poses, checking that the answers agree.

    pip install ./python python-fcl trimesh rtree   # in a virtual environment
    python bench/python/bench.py [--reps 3] [--poses 10000] [--points 100000]

Rows: building a model of 40k and of 1M triangles; collision and distance at N pose pairs, for
models of 40k and of 400 triangles (a Python loop of python-fcl calls, a Python loop of pqp
calls, one pqp batch call); closest points
of M points near the surface (trimesh.proximity.closest_point, pqp.closest_point). Each row is timed `reps` times,
the implementations alternating within each repetition; the table gives the median and the
minimum, and each row's ratio of medians against the peer.
"""

import argparse
import os
import statistics
import sys
import time

import numpy as np

import pqp

try:
    import fcl
except ImportError:  # pragma: no cover
    fcl = None
try:
    import trimesh
except ImportError:  # pragma: no cover
    trimesh = None


def sphere_mesh(n_lat, n_lon, radius=1.0, seed=0):
    """A closed UV sphere with a little radial noise (so that it is not perfectly regular)."""
    rng = np.random.default_rng(seed)
    th = np.pi * np.arange(1, n_lat) / n_lat
    ph = 2 * np.pi * np.arange(n_lon) / n_lon
    t, p = np.meshgrid(th, ph, indexing="ij")
    ring = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1).reshape(-1, 3)
    v = np.vstack([[0, 0, 1], ring, [0, 0, -1]])
    v *= radius * (1 + 0.01 * rng.uniform(-1, 1, (len(v), 1)))
    south = len(v) - 1
    j = np.arange(n_lon)
    jn = (j + 1) % n_lon
    faces = [np.stack([np.zeros(n_lon, int), 1 + j, 1 + jn], 1)]
    for i in range(n_lat - 2):
        r0, r1 = 1 + i * n_lon, 1 + (i + 1) * n_lon
        faces.append(np.stack([r0 + j, r1 + j, r1 + jn], 1))
        faces.append(np.stack([r0 + j, r1 + jn, r0 + jn], 1))
    r = 1 + (n_lat - 2) * n_lon
    faces.append(np.stack([r + j, np.full(n_lon, south), r + jn], 1))
    return v, np.vstack(faces).astype(np.int64)


def random_rotations(rng, n):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
        ],
        1,
    )


def poses(rng, n, dist_lo, dist_hi):
    """n poses: random rotations, translations at a random distance in [dist_lo, dist_hi]."""
    p = np.tile(np.eye(4), (n, 1, 1))
    p[:, :3, :3] = random_rotations(rng, n)
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    p[:, :3, 3] = d * rng.uniform(dist_lo, dist_hi, (n, 1))
    return p


def fcl_model(v, f):
    g = fcl.BVHModel()
    g.beginModel(len(v), len(f))
    g.addSubModel(v, f.astype(np.int32))
    g.endModel()
    return g


def timed(fn):
    t = time.perf_counter()
    out = fn()
    return time.perf_counter() - t, out


def pose_rows(results, rng, args, v, f, label):
    """Collision and distance of a model against itself at N poses: a python-fcl loop, a pqp
    loop, one pqp batch call."""
    m = pqp.Model(v, f)
    g = fcl_model(v, f)
    n = args.poses
    # Collision: the second model at 1.7-2.3 from the first (about half the poses collide).
    p2 = poses(rng, n, 1.7, 2.3)
    req = fcl.CollisionRequest()
    o1 = fcl.CollisionObject(g, fcl.Transform())
    o2 = fcl.CollisionObject(g, fcl.Transform())

    def fcl_collide():
        out = np.empty(n, bool)
        for i in range(n):
            o2.setTransform(fcl.Transform(p2[i, :3, :3], p2[i, :3, 3]))
            out[i] = fcl.collide(o1, o2, req, fcl.CollisionResult()) > 0
        return out

    def pqp_collide_loop():
        out = np.empty(n, bool)
        for i in range(n):
            out[i] = len(pqp.collide(m, None, m, p2[i], first=True)) > 0
        return out

    def pqp_collide_batch():
        return pqp.collide_batch(m, None, m, p2)

    runs = {k: [] for k in ("fcl", "loop", "batch")}
    answers = {}
    for _ in range(args.reps):
        for k, fn in (("fcl", fcl_collide), ("loop", pqp_collide_loop), ("batch", pqp_collide_batch)):
            t, answers[k] = timed(fn)
            runs[k].append(t)
    agree = int((answers["fcl"] == answers["loop"]).sum()), int((answers["fcl"] == answers["batch"]).sum())
    print(f"collision {label}: {answers['fcl'].sum()} of {n} collide; pqp agrees on {agree}", file=sys.stderr)
    results.append((f"collide, {n} poses ({label})", [("python-fcl loop", runs["fcl"]), ("pqp loop", runs["loop"]), ("pqp.collide_batch", runs["batch"])]))

    # Distance: separated, the second model at 2.05-3.0 (the spheres' radii are about 1).
    p3 = poses(rng, n, 2.05, 3.0)
    dreq = fcl.DistanceRequest()

    def fcl_distance():
        out = np.empty(n)
        for i in range(n):
            o2.setTransform(fcl.Transform(p3[i, :3, :3], p3[i, :3, 3]))
            out[i] = fcl.distance(o1, o2, dreq, fcl.DistanceResult())
        return out

    def pqp_distance_loop():
        out = np.empty(n)
        for i in range(n):
            out[i] = pqp.distance(m, None, m, p3[i])[0]
        return out

    def pqp_distance_batch():
        return pqp.distance_batch(m, None, m, p3)

    runs = {k: [] for k in ("fcl", "loop", "batch")}
    for _ in range(args.reps):
        for k, fn in (("fcl", fcl_distance), ("loop", pqp_distance_loop), ("batch", pqp_distance_batch)):
            t, answers[k] = timed(fn)
            runs[k].append(t)
    err = np.abs(answers["fcl"] - answers["batch"]).max(), np.abs(answers["loop"] - answers["batch"]).max()
    print(f"distance {label}: max |fcl - pqp| {err[0]:.2e}, |loop - batch| {err[1]:.2e}", file=sys.stderr)
    results.append((f"distance, {n} poses ({label})", [("python-fcl loop", runs["fcl"]), ("pqp loop", runs["loop"]), ("pqp.distance_batch", runs["batch"])]))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--poses", type=int, default=10000)
    ap.add_argument("--points", type=int, default=100000)
    ap.add_argument("--skip-1m", action="store_true")
    args = ap.parse_args()
    rng = np.random.default_rng(2026)
    results = []  # (row, impl, [seconds])
    load = os.getloadavg()

    v40, f40 = sphere_mesh(101, 200)  # 39,800 triangles
    v1m, f1m = sphere_mesh(501, 1000)  # 999,000 triangles
    print(f"models: {len(f40)} and {len(f1m)} triangles; load average {load}", file=sys.stderr)

    # Builds.
    for name, v, f, reps in (("build 40k", v40, f40, args.reps), ("build 1M", v1m, f1m, 1 if args.skip_1m else args.reps)):
        t_fcl, t_pq1, t_pq = [], [], []
        for _ in range(reps):
            t_fcl.append(timed(lambda: fcl_model(v, f))[0])
            t_pq1.append(timed(lambda: pqp.Model(v, f, threads=1))[0])
            t_pq.append(timed(lambda: pqp.Model(v, f))[0])
        results.append((name, [("python-fcl BVHModel", t_fcl), ("pqp.Model threads=1", t_pq1), ("pqp.Model (all cores)", t_pq)]))

    m40 = pqp.Model(v40, f40)
    for v, f, label in ((v40, f40, "40k vs 40k"), (*sphere_mesh(11, 20), "400 vs 400")):
        pose_rows(results, rng, args, v, f, label)

    # Closest points: in a shell around the surface (from 0.9 to 1.1 times the radius).
    q = args.points
    pts = rng.normal(size=(q, 3))
    pts *= rng.uniform(0.9, 1.1, (q, 1)) / np.linalg.norm(pts, axis=1, keepdims=True)
    tm = trimesh.Trimesh(v40, f40, process=False)
    runs = {k: [] for k in ("trimesh", "pqp1", "pqp")}
    for _ in range(args.reps):
        t, (c_t, d_t, _) = timed(lambda: trimesh.proximity.closest_point(tm, pts))
        runs["trimesh"].append(t)
        t, (d1, _, _) = timed(lambda: pqp.closest_point(m40, None, pts, threads=1))
        runs["pqp1"].append(t)
        t, (d, _, _) = timed(lambda: pqp.closest_point(m40, None, pts))
        runs["pqp"].append(t)
    print(f"closest points: max |trimesh - pqp| {np.abs(d_t - d).max():.2e}", file=sys.stderr)
    results.append((f"closest points, {q} (40k)", [("trimesh.proximity", runs["trimesh"]), ("pqp threads=1", runs["pqp1"]), ("pqp (all cores)", runs["pqp"])]))

    print(f"\nload average at start {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}, at end "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()) + f"; {os.cpu_count()} cores; reps {args.reps}\n")
    print("| workload | implementation | median s | min s | peer / this (medians) |")
    print("|---|---|---:|---:|---:|")
    for name, impls in results:
        peer = statistics.median(impls[0][1])
        for impl, ts in impls:
            med = statistics.median(ts)
            print(f"| {name} | {impl} | {med:.4f} | {min(ts):.4f} | {peer / med:.1f}x |")


if __name__ == "__main__":
    main()
