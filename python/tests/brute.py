"""Brute-force references in NumPy: every triangle (pair) tested, no hierarchy."""

import numpy as np


def posed(vertices, faces, pose):
    """Triangles (k, 3, 3) of a mesh moved by a 4x4 pose."""
    v = np.asarray(vertices, float) @ pose[:3, :3].T + pose[:3, 3]
    return v[np.asarray(faces)]


def point_segment(p, a, b):
    """Distance from points p to segments ab (broadcast over leading axes)."""
    ab = b - a
    denom = np.einsum("...i,...i", ab, ab)
    t = np.einsum("...i,...i", p - a, ab) / np.where(denom > 0, denom, 1.0)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(p - (a + t[..., None] * ab), axis=-1)


def point_triangle(p, tri):
    """Distance from points p (..., 3) to triangles tri (..., 3, 3)."""
    a, b, c = tri[..., 0, :], tri[..., 1, :], tri[..., 2, :]
    n = np.cross(b - a, c - a)
    nn = np.linalg.norm(n, axis=-1)
    n_unit = n / np.where(nn > 0, nn, 1.0)[..., None]
    h = np.einsum("...i,...i", p - a, n_unit)
    q = p - h[..., None] * n_unit
    # Inside the triangle when q is on the inner side of every edge.
    inside = nn > 0
    for u, w in ((a, b), (b, c), (c, a)):
        inside = inside & (np.einsum("...i,...i", np.cross(w - u, q - u), n) >= 0)
    edges = np.minimum(
        np.minimum(point_segment(p, a, b), point_segment(p, b, c)), point_segment(p, c, a)
    )
    return np.where(inside, np.abs(h), edges)


def segment_segment(p0, p1, q0, q1):
    """Distance between segments p0p1 and q0q1 (broadcast), by minimising over both parameters:
    the unconstrained optimum when interior, else the best of the four end-point cases."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a = np.einsum("...i,...i", d1, d1)
    e = np.einsum("...i,...i", d2, d2)
    b = np.einsum("...i,...i", d1, d2)
    c = np.einsum("...i,...i", d1, r)
    f = np.einsum("...i,...i", d2, r)
    den = a * e - b * b
    ok = den > 1e-14 * np.maximum(a * e, 1e-300)
    s = np.where(ok, (b * f - c * e) / np.where(ok, den, 1.0), 0.0)
    t = np.where(ok, (a * f - b * c) / np.where(ok, den, 1.0), 0.0)
    interior = ok & (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)
    pi = p0 + s[..., None] * d1
    qi = q0 + t[..., None] * d2
    d_int = np.where(interior, np.linalg.norm(pi - qi, axis=-1), np.inf)
    ends = np.minimum.reduce(
        [
            point_segment(p0, q0, q1),
            point_segment(p1, q0, q1),
            point_segment(q0, p0, p1),
            point_segment(q1, p0, p1),
        ]
    )
    return np.minimum(d_int, ends)


def segment_crosses(p0, p1, tri):
    """Whether segments p0p1 meet triangles tri (Moller-Trumbore, inclusive bounds)."""
    a, b, c = tri[..., 0, :], tri[..., 1, :], tri[..., 2, :]
    d = p1 - p0
    e1, e2 = b - a, c - a
    h = np.cross(d, e2)
    det = np.einsum("...i,...i", e1, h)
    ok = np.abs(det) > 1e-300
    inv = 1.0 / np.where(ok, det, 1.0)
    s = p0 - a
    u = np.einsum("...i,...i", s, h) * inv
    q = np.cross(s, e1)
    v = np.einsum("...i,...i", d, q) * inv
    t = np.einsum("...i,...i", e2, q) * inv
    return ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0) & (t <= 1)


def tri_tri_overlap(t1, t2):
    """Whether triangles t1, t2 (broadcast) intersect (in general position: an edge of one
    crosses the other)."""
    hit = np.zeros(np.broadcast_shapes(t1.shape, t2.shape)[:-2], bool)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        hit |= segment_crosses(t1[..., i, :], t1[..., j, :], t2)
        hit |= segment_crosses(t2[..., i, :], t2[..., j, :], t1)
    return hit


def tri_tri_distance(t1, t2):
    """Distance between triangles t1, t2 (broadcast): 0 if they meet, else the least of the
    vertex-triangle and edge-edge distances."""
    cands = []
    for k in range(3):
        cands.append(point_triangle(t1[..., k, :], t2))
        cands.append(point_triangle(t2[..., k, :], t1))
    for i, j in ((0, 1), (1, 2), (2, 0)):
        for k, l in ((0, 1), (1, 2), (2, 0)):
            cands.append(segment_segment(t1[..., i, :], t1[..., j, :], t2[..., k, :], t2[..., l, :]))
    d = np.minimum.reduce(cands)
    return np.where(tri_tri_overlap(t1, t2), 0.0, d)


def all_pairs(t1, t2):
    """Broadcast views of every (i, j) pair of two triangle arrays."""
    return t1[:, None], t2[None, :]


def ray_triangles(o, d, tri):
    """First hit t (inf for a miss) and triangle index (-1) of ray o + t d on triangles tri."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    e1, e2 = b - a, c - a
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-300
    inv = 1.0 / np.where(ok, det, 1.0)
    s = o - a
    u = np.einsum("ij,ij->i", s, h) * inv
    q = np.cross(s, e1)
    v = (q @ d) * inv
    t = np.einsum("ij,ij->i", e2, q) * inv
    hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
    t = np.where(hit, t, np.inf)
    k = int(np.argmin(t))
    return (t[k], k) if np.isfinite(t[k]) else (np.inf, -1)
