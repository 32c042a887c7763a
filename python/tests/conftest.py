import numpy as np
import pytest


def random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    return q


def random_pose(rng, spread=1.0):
    p = np.eye(4)
    p[:3, :3] = random_rotation(rng)
    p[:3, 3] = rng.uniform(-spread, spread, 3)
    return p


def uv_sphere(radius=1.0, n_lat=6, n_lon=8, center=(0, 0, 0)):
    """A closed, outward-wound UV sphere (2 poles, (n_lat - 1) rings)."""
    verts = [[0, 0, radius]]
    for i in range(1, n_lat):
        th = np.pi * i / n_lat
        for j in range(n_lon):
            ph = 2 * np.pi * j / n_lon
            verts.append([radius * np.sin(th) * np.cos(ph), radius * np.sin(th) * np.sin(ph), radius * np.cos(th)])
    verts.append([0, 0, -radius])
    faces = []
    south = len(verts) - 1
    for j in range(n_lon):
        faces.append([0, 1 + j, 1 + (j + 1) % n_lon])
    for i in range(n_lat - 2):
        r0, r1 = 1 + i * n_lon, 1 + (i + 1) * n_lon
        for j in range(n_lon):
            a, b = r0 + j, r0 + (j + 1) % n_lon
            c, d = r1 + j, r1 + (j + 1) % n_lon
            faces.append([a, c, d])
            faces.append([a, d, b])
    r = 1 + (n_lat - 2) * n_lon
    for j in range(n_lon):
        faces.append([r + j, south, r + (j + 1) % n_lon])
    return np.asarray(verts, float) + np.asarray(center, float), np.asarray(faces, np.int64)


def random_soup(rng, n=40, size=1.0, tri_size=0.4):
    """n random triangles (disconnected), as vertices and faces."""
    centers = rng.uniform(-size, size, (n, 1, 3))
    v = (centers + rng.uniform(-tri_size, tri_size, (n, 3, 3))).reshape(-1, 3)
    return v, np.arange(3 * n).reshape(n, 3)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
