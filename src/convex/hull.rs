//! The convex hull of a point set as a closed triangulated surface (incremental, quickhull order).
//!
//! Every decision is an exact orientation sign (`predicates::orient3d`), so the combinatorics are
//! those of the exact hull of the input doubles whatever their degeneracy: a point is added only if
//! it is strictly beyond some triangle, the triangles it sees strictly form a disc whose boundary
//! (the horizon) is coned to it, and points that are not strictly beyond any new triangle are inside
//! or on the new hull and dropped (Barber, Dobkin and Huhdanpaa's outside sets). Coplanar points
//! therefore leave coplanar triangles and sometimes non-extreme vertices (in a facet or on an edge);
//! `model.rs` merges the former into polygons and removes the latter.

use super::predicates::{P3, collinear, orient3d};
use crate::error::Error;
use std::collections::HashMap;

/// A closed, outward-oriented triangle surface over a point array.
pub(crate) struct TriSurface {
    /// Vertex indices, counter-clockwise seen from outside.
    pub tris: Vec<[u32; 3]>,
    /// `nbrs[t][i]`: the triangle across edge `(tris[t][i], tris[t][(i + 1) % 3])`.
    pub nbrs: Vec<[u32; 3]>,
}

struct HullTri {
    v: [u32; 3],
    n: [u32; 3],
    alive: bool,
    /// Points strictly beyond this triangle and assigned to it.
    outside: Vec<u32>,
    /// Float normal (not unit), only to pick the furthest point: a heuristic, never a decision.
    normal: [f64; 3],
}

fn sub(a: &P3, b: &P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: &P3, b: &P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: &P3, b: &P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl HullTri {
    fn new(v: [u32; 3], pts: &[P3]) -> HullTri {
        let (a, b, c) = (
            &pts[v[0] as usize],
            &pts[v[1] as usize],
            &pts[v[2] as usize],
        );
        HullTri {
            v,
            n: [u32::MAX; 3],
            alive: true,
            outside: Vec::new(),
            normal: cross(&sub(b, a), &sub(c, a)),
        }
    }

    /// Whether `p` is strictly beyond the triangle's plane (exact).
    fn sees(&self, pts: &[P3], p: &P3) -> bool {
        orient3d(
            &pts[self.v[0] as usize],
            &pts[self.v[1] as usize],
            &pts[self.v[2] as usize],
            p,
        ) > 0
    }
}

/// Four affinely independent points, or `DegeneratePoints` when all points are coplanar (this
/// includes fewer than four distinct points and collinear sets).
fn initial_simplex(pts: &[P3]) -> Result<[u32; 4], Error> {
    if pts.len() < 4 {
        return Err(Error::DegeneratePoints);
    }
    // Extreme in x, then the furthest from it: both only heuristics for a well-shaped start.
    let i0 = (0..pts.len())
        .min_by(|&i, &j| pts[i][0].total_cmp(&pts[j][0]))
        .unwrap_or(0);
    let p0 = pts[i0];
    let i1 = (0..pts.len())
        .max_by(|&i, &j| {
            let (di, dj) = (sub(&pts[i], &p0), sub(&pts[j], &p0));
            dot(&di, &di).total_cmp(&dot(&dj, &dj))
        })
        .unwrap_or(0);
    if pts[i1] == p0 {
        return Err(Error::DegeneratePoints);
    }
    let p1 = pts[i1];
    let d01 = sub(&p1, &p0);
    let by_area = |i: usize| {
        let c = cross(&d01, &sub(&pts[i], &p0));
        dot(&c, &c)
    };
    let mut i2 = (0..pts.len())
        .max_by(|&i, &j| by_area(i).total_cmp(&by_area(j)))
        .unwrap_or(0);
    if collinear(&p0, &p1, &pts[i2]) {
        i2 = (0..pts.len())
            .find(|&i| !collinear(&p0, &p1, &pts[i]))
            .ok_or(Error::DegeneratePoints)?;
    }
    let p2 = pts[i2];
    let nrm = cross(&d01, &sub(&p2, &p0));
    let by_height = |i: usize| dot(&nrm, &sub(&pts[i], &p0)).abs();
    let mut i3 = (0..pts.len())
        .max_by(|&i, &j| by_height(i).total_cmp(&by_height(j)))
        .unwrap_or(0);
    if orient3d(&p0, &p1, &p2, &pts[i3]) == 0 {
        i3 = (0..pts.len())
            .find(|&i| orient3d(&p0, &p1, &p2, &pts[i]) != 0)
            .ok_or(Error::DegeneratePoints)?;
    }
    Ok([i0 as u32, i1 as u32, i2 as u32, i3 as u32])
}

/// Links the neighbours of the given triangles through their shared directed edges.
fn link(tris: &mut [HullTri], ids: &[u32]) -> Result<(), Error> {
    let mut by_edge: HashMap<(u32, u32), (u32, usize)> = HashMap::new();
    for &t in ids {
        for i in 0..3 {
            let v = tris[t as usize].v;
            by_edge.insert((v[i], v[(i + 1) % 3]), (t, i));
        }
    }
    for &t in ids {
        for i in 0..3 {
            let v = tris[t as usize].v;
            let &(u, _) = by_edge
                .get(&(v[(i + 1) % 3], v[i]))
                .ok_or(Error::Internal)?;
            tris[t as usize].n[i] = u;
        }
    }
    Ok(())
}

/// The hull of `pts` (distinct points, already scaled so that the predicates are exact).
pub(crate) fn hull(pts: &[P3]) -> Result<TriSurface, Error> {
    let s = initial_simplex(pts)?;
    let (a, b, c, d) = if orient3d(
        &pts[s[0] as usize],
        &pts[s[1] as usize],
        &pts[s[2] as usize],
        &pts[s[3] as usize],
    ) < 0
    {
        (s[0], s[1], s[2], s[3])
    } else {
        (s[0], s[2], s[1], s[3])
    };
    // With d below abc these four triangles face outwards.
    let mut tris: Vec<HullTri> = [[a, b, c], [a, d, b], [b, d, c], [c, d, a]]
        .iter()
        .map(|&v| HullTri::new(v, pts))
        .collect();
    link(&mut tris, &[0, 1, 2, 3])?;
    for (i, p) in pts.iter().enumerate() {
        if s.contains(&(i as u32)) {
            continue;
        }
        if let Some(t) = (0..4).find(|&t| tris[t].sees(pts, p)) {
            tris[t].outside.push(i as u32);
        }
    }
    let mut pending: Vec<u32> = (0..4u32)
        .filter(|&t| !tris[t as usize].outside.is_empty())
        .collect();
    // Per-triangle marks for the visibility search: `epoch * 2` visible, `epoch * 2 + 1` not.
    let mut mark: Vec<u64> = vec![0; 4];
    let mut epoch: u64 = 0;
    let mut visible: Vec<u32> = Vec::new();
    let mut horizon: Vec<(u32, u32, u32)> = Vec::new();
    let mut start: HashMap<u32, u32> = HashMap::new();
    let mut orphans: Vec<u32> = Vec::new();

    while let Some(t0) = pending.pop() {
        let t0 = t0 as usize;
        if !tris[t0].alive || tris[t0].outside.is_empty() {
            continue;
        }
        // The furthest outside point (in floating point; any outside point would be correct).
        let base = pts[tris[t0].v[0] as usize];
        let nrm = tris[t0].normal;
        let &ip = tris[t0]
            .outside
            .iter()
            .max_by(|&&i, &&j| {
                let hi = dot(&nrm, &sub(&pts[i as usize], &base));
                let hj = dot(&nrm, &sub(&pts[j as usize], &base));
                hi.total_cmp(&hj)
            })
            .ok_or(Error::Internal)?;
        let p = pts[ip as usize];

        // Triangles strictly visible from p: a connected set containing t0.
        epoch += 1;
        mark.resize(tris.len(), 0);
        visible.clear();
        visible.push(t0 as u32);
        mark[t0] = epoch * 2;
        let mut k = 0;
        while k < visible.len() {
            let t = visible[k] as usize;
            k += 1;
            for i in 0..3 {
                let u = tris[t].n[i] as usize;
                if mark[u] == epoch * 2 || mark[u] == epoch * 2 + 1 {
                    continue;
                }
                if tris[u].sees(pts, &p) {
                    mark[u] = epoch * 2;
                    visible.push(u as u32);
                } else {
                    mark[u] = epoch * 2 + 1;
                }
            }
        }
        // Horizon edges, oriented as in their visible triangle, with the hidden neighbour.
        horizon.clear();
        for &t in &visible {
            let tr = &tris[t as usize];
            for i in 0..3 {
                let u = tr.n[i];
                if mark[u as usize] != epoch * 2 {
                    horizon.push((tr.v[i], tr.v[(i + 1) % 3], u));
                }
            }
        }
        // Cone the horizon to p. The horizon is a simple cycle, so each vertex starts one edge.
        start.clear();
        let first_new = tris.len() as u32;
        for &(ha, hb, hidden) in &horizon {
            let id = tris.len() as u32;
            let mut nt = HullTri::new([ha, hb, ip], pts);
            nt.n[0] = hidden;
            tris.push(nt);
            if start.insert(ha, id).is_some() {
                return Err(Error::Internal);
            }
            let h = &mut tris[hidden as usize];
            let slot = (0..3)
                .find(|&j| h.v[j] == hb && h.v[(j + 1) % 3] == ha)
                .ok_or(Error::Internal)?;
            h.n[slot] = id;
        }
        for id in first_new..tris.len() as u32 {
            let hb = tris[id as usize].v[1];
            let next = *start.get(&hb).ok_or(Error::Internal)?;
            tris[id as usize].n[1] = next;
            tris[next as usize].n[2] = id;
        }
        // Hand the visible triangles' outside points to the new triangles.
        orphans.clear();
        for &t in &visible {
            let tr = &mut tris[t as usize];
            tr.alive = false;
            orphans.extend(tr.outside.drain(..).filter(|&q| q != ip));
            tr.outside = Vec::new();
        }
        for &q in &orphans {
            let pq = &pts[q as usize];
            if let Some(t) =
                (first_new..tris.len() as u32).find(|&t| tris[t as usize].sees(pts, pq))
            {
                tris[t as usize].outside.push(q);
            }
        }
        for t in first_new..tris.len() as u32 {
            if !tris[t as usize].outside.is_empty() {
                pending.push(t);
            }
        }
    }

    // Compact the live triangles.
    let mut new_id = vec![u32::MAX; tris.len()];
    let mut out = TriSurface {
        tris: Vec::new(),
        nbrs: Vec::new(),
    };
    for (t, tr) in tris.iter().enumerate() {
        if tr.alive {
            new_id[t] = out.tris.len() as u32;
            out.tris.push(tr.v);
        }
    }
    for tr in tris.iter().filter(|t| t.alive) {
        let mut n = [0u32; 3];
        for i in 0..3 {
            n[i] = new_id[tr.n[i] as usize];
            if n[i] == u32::MAX {
                return Err(Error::Internal);
            }
        }
        out.nbrs.push(n);
    }
    Ok(out)
}
