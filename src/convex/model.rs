//! `ConvexModel`: a convex polyhedron with its features (vertices, edges, faces), their neighbours
//! and their Voronoi planes, built from a point set (through our hull) or from a closed convex mesh.

use super::hull::{TriSurface, hull};
use super::predicates::{P3, area_vector, orient2d, orient3d};
use super::{Feature, FeatureKind};
use crate::error::{Error, MAX_COORDINATE};
use crate::math::Vec3;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

/// An oriented plane `n . x = d` with unit `n`; `eval` is the signed distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plane {
    pub n: Vec3,
    pub d: f64,
}

impl Plane {
    fn through(n: Vec3, p: &Vec3) -> Plane {
        Plane { n, d: n.dot(p) }
    }

    #[inline]
    pub fn eval(&self, p: &Vec3) -> f64 {
        self.n.dot(p) - self.d
    }
}

/// An edge from `tail` to `head`. `left` is the face that runs along it from tail to head in its
/// counter-clockwise order (seen from outside), `right` the other one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EdgeData {
    pub tail: u32,
    pub head: u32,
    pub left: u32,
    pub right: u32,
    /// Voronoi planes of the edge, normals pointing into its region: at the tail, at the head,
    /// along the left face, along the right face (in the order of `edge_neighbours`).
    pub planes: [Plane; 4],
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct FaceData {
    pub plane: Plane,
    /// Range of the face's vertices, edges and side planes in the `face_*` arrays.
    pub start: u32,
    pub len: u32,
}

static NEXT_UID: AtomicU64 = AtomicU64::new(1);

/// A convex polyhedron prepared for V-Clip: vertices, edges and (polygonal) faces with their
/// neighbour lists and Voronoi planes, all precomputed.
///
/// Built by [`from_points`](ConvexModel::from_points) (the convex hull of a point set) or by
/// [`from_polygons`](ConvexModel::from_polygons) / [`from_triangles`](ConvexModel::from_triangles)
/// (a closed convex mesh). Either way the stored polyhedron is canonical: coplanar faces are merged
/// into one convex polygon and every vertex is a corner (points inside a face or in the middle of an
/// edge are dropped), so `V - E + F = 2` and every face is a strictly convex polygon.
/// [`vertex_source`](ConvexModel::vertex_source) maps vertices back to the input.
///
/// Immutable once built: `Send + Sync`, shareable between threads. Per-pair query state lives in a
/// [`ConvexPairCache`](super::ConvexPairCache) that the caller owns.
#[derive(Debug, Clone)]
pub struct ConvexModel {
    uid: u64,
    verts: Vec<Vec3>,
    source: Vec<u32>,
    /// Incident edges of vertex `v`: `vert_edges[vert_start[v]..vert_start[v + 1]]`, with, at the
    /// same positions, the other end of the edge and the Voronoi plane of `v` facing that edge.
    vert_start: Vec<u32>,
    vert_edges: Vec<u32>,
    vert_others: Vec<u32>,
    vert_planes: Vec<Plane>,
    pub(crate) edges: Vec<EdgeData>,
    pub(crate) faces: Vec<FaceData>,
    /// Face `f`'s vertices counter-clockwise from outside; edge `k` of the face joins vertex `k` to
    /// vertex `k + 1`, and side plane `k` (normal into the face's Voronoi prism) contains it.
    face_verts: Vec<u32>,
    face_edges: Vec<u32>,
    face_sides: Vec<Plane>,
    centroid: Vec3,
    /// Largest distance of a vertex from the model's origin.
    radius: f64,
}

/// The most points (or vertices) a convex model is made from: 2^30, so that vertex indices and
/// feature counts stay far inside 32 bits.
pub(crate) const MAX_POINTS: usize = 1 << 30;

/// Checks coordinates and converts them.
fn import_points(points: &[[f64; 3]]) -> Result<Vec<Vec3>, Error> {
    if points.len() > MAX_POINTS {
        return Err(Error::InvalidArgument);
    }
    points
        .iter()
        .map(|p| {
            if p.iter().all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE) {
                // `+ 0.0` turns -0.0 into 0.0 so that equal points compare equal.
                Ok(Vec3::new(p[0] + 0.0, p[1] + 0.0, p[2] + 0.0))
            } else {
                Err(Error::NonFiniteCoordinate)
            }
        })
        .collect()
}

/// The points multiplied by a power of two (exact) so that the largest coordinate is at most 1,
/// where the exact predicates cannot overflow.
fn scaled(points: &[Vec3]) -> Vec<P3> {
    let m = points
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let k = if m > 0.0 { m.log2().ceil() as i32 } else { 0 };
    // Two steps keep each factor a normal double even for extreme exponents.
    let (s1, s2) = (2f64.powi(-k / 2), 2f64.powi(-(k - k / 2)));
    points
        .iter()
        .map(|p| [p.x * s1 * s2, p.y * s1 * s2, p.z * s1 * s2])
        .collect()
}

/// `v` scaled to unit length without underflow or overflow of its squared length (the squares of
/// an area vector of points scaled to at most 1 can underflow); zero stays zero.
pub(crate) fn unit(v: &Vec3) -> Vec3 {
    let m = v.amax();
    if m > 0.0 && m.is_finite() {
        let w = v / m;
        w / w.norm()
    } else {
        *v
    }
}

/// A polygon's normal direction (not normalised), accurate even for slivers.
fn newell(pts: &[P3], cycle: &[u32]) -> Vec3 {
    let a = area_vector(pts, cycle);
    Vec3::new(a[0], a[1], a[2])
}

/// The coordinate plane a planar polygon with normal `n` projects onto one-to-one, as two axes in
/// the order that keeps counter-clockwise (seen from `+n`) counter-clockwise when `n[k] > 0`.
fn projection_axes(n: &Vec3) -> (usize, usize, usize) {
    let k = (0..3)
        .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(2);
    ((k + 1) % 3, (k + 2) % 3, k)
}

struct UnionFind(Vec<u32>);

impl UnionFind {
    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let p = self.0[x as usize];
            self.0[x as usize] = self.0[p as usize];
            x = p;
        }
        x
    }
    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

/// Facets of a closed convex triangle surface: exactly coplanar neighbours merged, each facet's
/// boundary as one counter-clockwise cycle with its non-corner vertices (collinear with their two
/// neighbours) removed. Any inconsistency is an internal error: the callers guarantee a convex
/// surface.
fn facets(pts: &[P3], surf: &TriSurface) -> Result<Vec<Vec<u32>>, Error> {
    let nt = surf.tris.len();
    let mut uf = UnionFind((0..nt as u32).collect());
    for t in 0..nt {
        let v = surf.tris[t];
        for i in 0..3 {
            let u = surf.nbrs[t][i] as usize;
            if u <= t {
                continue;
            }
            let w = surf.tris[u];
            let opp = w
                .iter()
                .copied()
                .find(|&x| x != v[i] && x != v[(i + 1) % 3])
                .ok_or(Error::Internal)?;
            let p = |x: u32| &pts[x as usize];
            if orient3d(p(v[0]), p(v[1]), p(v[2]), p(opp)) == 0 {
                uf.union(t as u32, u as u32);
            }
        }
    }
    // Boundary half-edges of each group, keyed by (group, start vertex).
    let mut next: HashMap<(u32, u32), u32> = HashMap::new();
    let mut count: HashMap<u32, usize> = HashMap::new();
    let mut first: Vec<(u32, u32)> = Vec::new();
    for t in 0..nt {
        let g = uf.find(t as u32);
        let v = surf.tris[t];
        for i in 0..3 {
            if uf.find(surf.nbrs[t][i]) != g {
                if next.insert((g, v[i]), v[(i + 1) % 3]).is_some() {
                    return Err(Error::Internal);
                }
                let c = count.entry(g).or_insert(0);
                if *c == 0 {
                    first.push((g, v[i]));
                }
                *c += 1;
            }
        }
    }
    let mut out = Vec::with_capacity(first.len());
    for &(g, v0) in &first {
        let n = count[&g];
        let mut cycle = Vec::with_capacity(n);
        let mut v = v0;
        loop {
            cycle.push(v);
            v = *next.get(&(g, v)).ok_or(Error::Internal)?;
            if v == v0 || cycle.len() > n {
                break;
            }
        }
        if cycle.len() != n || n < 3 {
            return Err(Error::Internal);
        }
        let (i, j, _) = projection_axes(&newell(pts, &cycle));
        let p = |x: u32| &pts[x as usize];
        let turn = |k: usize| {
            let a = cycle[(k + n - 1) % n];
            let b = cycle[k];
            let c = cycle[(k + 1) % n];
            orient2d(p(a), p(b), p(c), i, j)
        };
        let turns: Vec<i32> = (0..n).map(turn).collect();
        let corners: Vec<u32> = (0..n)
            .filter(|&k| turns[k] != 0)
            .map(|k| cycle[k])
            .collect();
        let sign = turns.iter().copied().find(|&s| s != 0).unwrap_or(0);
        if corners.len() < 3 || turns.iter().any(|&s| s == -sign) {
            return Err(Error::Internal);
        }
        out.push(corners);
    }
    Ok(out)
}

impl ConvexModel {
    /// The convex hull of a point set.
    ///
    /// Duplicates, coplanar and nearly coplanar points are fine: every decision is an exact
    /// orientation sign on the input doubles, so the result is the exact hull of the input, with
    /// coplanar faces merged into convex polygons and only its corners as vertices (each one an
    /// input point, see [`vertex_source`](ConvexModel::vertex_source)).
    ///
    /// Errors: `NonFiniteCoordinate` for a NaN, infinite or huge (> `MAX_COORDINATE`) coordinate;
    /// `DegeneratePoints` when the points do not span a volume (fewer than four distinct points, or
    /// all collinear or coplanar, or none); `InvalidArgument` for more than 2^30 points.
    ///
    /// ```
    /// use pqp::convex::ConvexModel;
    /// let mut pts = vec![];
    /// for &x in &[0.0, 1.0] { for &y in &[0.0, 1.0] { for &z in &[0.0, 1.0] { pts.push([x, y, z]); } } }
    /// pts.push([0.5, 0.5, 0.5]); // inside
    /// pts.push([0.5, 0.5, 1.0]); // on a face
    /// let cube = ConvexModel::from_points(&pts).unwrap();
    /// assert_eq!((cube.num_vertices(), cube.num_edges(), cube.num_faces()), (8, 12, 6));
    /// ```
    pub fn from_points(points: &[[f64; 3]]) -> Result<ConvexModel, Error> {
        let pts = import_points(points)?;
        // Distinct points, each remembered by its first index.
        let mut order: Vec<u32> = (0..pts.len() as u32).collect();
        let key = |i: u32| {
            let p = &pts[i as usize];
            (p.x, p.y, p.z)
        };
        order.sort_by(|&i, &j| {
            let (a, b) = (key(i), key(j));
            a.0.total_cmp(&b.0)
                .then(a.1.total_cmp(&b.1))
                .then(a.2.total_cmp(&b.2))
                .then(i.cmp(&j))
        });
        order.dedup_by(|b, a| key(*a) == key(*b));
        let distinct: Vec<Vec3> = order.iter().map(|&i| pts[i as usize]).collect();
        let sp = scaled(&distinct);
        let surf = hull(&sp)?;
        let faces = facets(&sp, &surf)?;
        ConvexModel::assemble(&distinct, &sp, &order, faces)
    }

    /// A closed convex mesh given as polygons: `counts[f]` vertex indices per face, concatenated in
    /// `indices`, counter-clockwise seen from outside.
    ///
    /// The mesh must be closed and consistently oriented (each edge used once in each direction),
    /// use every vertex, be a topological sphere, have faces that are exactly planar and strictly
    /// convex, and be convex (every vertex on or below every face). All checks are exact; a mesh
    /// convex only up to rounding is refused (build it with [`from_points`](ConvexModel::from_points)
    /// instead). Coplanar neighbouring faces are merged and vertices that are then not corners are
    /// dropped, as in `from_points`.
    ///
    /// Errors: `NonFiniteCoordinate` for a bad coordinate; `InvalidArgument` when the arrays are
    /// malformed (an index out of range, a count below 3, counts not summing to the number of
    /// indices, more than 2^30 vertices); `InvalidConvexMesh` when they describe something other
    /// than a closed convex polyhedron (open, not an oriented sphere, a face not planar or not
    /// strictly convex, an unused vertex, a vertex above a face, flat).
    pub fn from_polygons(
        vertices: &[[f64; 3]],
        counts: &[u32],
        indices: &[u32],
    ) -> Result<ConvexModel, Error> {
        let pts = import_points(vertices)?;
        let nv = pts.len();
        // Malformed arrays first (u64: the sum of u32 counts cannot overflow).
        let total: u64 = counts.iter().map(|&c| u64::from(c)).sum();
        if total != indices.len() as u64
            || counts.iter().any(|&c| c < 3)
            || indices.iter().any(|&i| i as usize >= nv)
        {
            return Err(Error::InvalidArgument);
        }
        if nv < 4 || counts.len() < 4 {
            return Err(Error::InvalidConvexMesh);
        }
        let sp = scaled(&pts);
        let p = |x: u32| &sp[x as usize];
        // Faces: planar, strictly convex polygons.
        let mut polys: Vec<&[u32]> = Vec::with_capacity(counts.len());
        let mut at = 0usize;
        for &c in counts {
            let c = c as usize;
            let f = &indices[at..at + c];
            at += c;
            let (i, j, _) = projection_axes(&newell(&sp, f));
            let mut sign = 0;
            for k in 0..c {
                let (a, b) = (f[k], f[(k + 1) % c]);
                if a == b || f[..k].contains(&a) {
                    return Err(Error::InvalidConvexMesh);
                }
                for (m, &x) in f.iter().enumerate() {
                    if m == k || m == (k + 1) % c {
                        continue;
                    }
                    // Every other vertex strictly on one side of this edge, in the face's plane.
                    let s = orient2d(p(a), p(b), p(x), i, j);
                    if s == 0 || s == -sign || orient3d(p(f[0]), p(f[1]), p(f[2]), p(x)) != 0 {
                        return Err(Error::InvalidConvexMesh);
                    }
                    sign = s;
                }
            }
            polys.push(f);
        }
        // Closed and consistently oriented: each directed edge once, with its reverse.
        let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
        for (fi, f) in polys.iter().enumerate() {
            for k in 0..f.len() {
                if directed
                    .insert((f[k], f[(k + 1) % f.len()]), fi as u32)
                    .is_some()
                {
                    return Err(Error::InvalidConvexMesh);
                }
            }
        }
        if directed
            .keys()
            .any(|&(a, b)| !directed.contains_key(&(b, a)))
        {
            return Err(Error::InvalidConvexMesh);
        }
        let mut used = vec![false; nv];
        indices.iter().for_each(|&i| used[i as usize] = true);
        let ne = directed.len() / 2;
        if used.iter().any(|&u| !u) || nv + polys.len() != ne + 2 {
            return Err(Error::InvalidConvexMesh);
        }
        // Fan triangles (no degenerate one: faces are strictly convex) and their neighbours.
        let mut surf = TriSurface {
            tris: Vec::new(),
            nbrs: Vec::new(),
        };
        for f in &polys {
            for k in 1..f.len() - 1 {
                surf.tris.push([f[0], f[k], f[k + 1]]);
            }
        }
        let mut by_edge: HashMap<(u32, u32), u32> = HashMap::new();
        for (t, v) in surf.tris.iter().enumerate() {
            for i in 0..3 {
                by_edge.insert((v[i], v[(i + 1) % 3]), t as u32);
            }
        }
        for v in &surf.tris {
            let mut n = [0u32; 3];
            for i in 0..3 {
                n[i] = *by_edge
                    .get(&(v[(i + 1) % 3], v[i]))
                    .ok_or(Error::InvalidConvexMesh)?;
            }
            surf.nbrs.push(n);
        }
        // Connected (with Euler's count above: a sphere).
        let mut seen = vec![false; surf.tris.len()];
        let mut stack = vec![0u32];
        seen[0] = true;
        while let Some(t) = stack.pop() {
            for &u in &surf.nbrs[t as usize] {
                if !seen[u as usize] {
                    seen[u as usize] = true;
                    stack.push(u);
                }
            }
        }
        if seen.iter().any(|&s| !s) {
            return Err(Error::InvalidConvexMesh);
        }
        // Convex and outward: no vertex beyond any face, and some vertex strictly below (a volume).
        let mut solid = false;
        for v in &surf.tris {
            for x in 0..nv as u32 {
                match orient3d(p(v[0]), p(v[1]), p(v[2]), p(x)) {
                    1 => return Err(Error::InvalidConvexMesh),
                    -1 => solid = true,
                    _ => {}
                }
            }
        }
        if !solid {
            return Err(Error::InvalidConvexMesh);
        }
        let faces = facets(&sp, &surf).map_err(|_| Error::InvalidConvexMesh)?;
        let ident: Vec<u32> = (0..nv as u32).collect();
        ConvexModel::assemble(&pts, &sp, &ident, faces)
    }

    /// A closed convex triangle mesh; see [`from_polygons`](ConvexModel::from_polygons).
    pub fn from_triangles(
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
    ) -> Result<ConvexModel, Error> {
        let counts = vec![3u32; triangles.len()];
        let indices: Vec<u32> = triangles.iter().flatten().copied().collect();
        ConvexModel::from_polygons(vertices, &counts, &indices)
    }

    /// Builds features, neighbour lists and Voronoi planes from facet cycles over `pts`
    /// (`sp`: the same points scaled, `src`: their input indices).
    fn assemble(
        pts: &[Vec3],
        sp: &[P3],
        src: &[u32],
        faces: Vec<Vec<u32>>,
    ) -> Result<ConvexModel, Error> {
        // Keep only corner vertices, renumbered in input order.
        let mut new_id = vec![u32::MAX; pts.len()];
        for f in &faces {
            for &v in f {
                new_id[v as usize] = 0;
            }
        }
        let mut verts = Vec::new();
        let mut source = Vec::new();
        for (i, id) in new_id.iter_mut().enumerate() {
            if *id == 0 {
                *id = verts.len() as u32;
                verts.push(pts[i]);
                source.push(src[i]);
            }
        }
        let nv = verts.len();
        let mut face_data = Vec::with_capacity(faces.len());
        let mut face_verts = Vec::new();
        let mut face_edges = Vec::new();
        let mut edges: Vec<EdgeData> = Vec::new();
        let mut edge_of: HashMap<(u32, u32), u32> = HashMap::new();
        let dummy = Plane {
            n: Vec3::zeros(),
            d: 0.0,
        };
        for (fi, f) in faces.iter().enumerate() {
            let n = newell(sp, f);
            let n = unit(&n);
            if !n.iter().all(|v| v.is_finite()) || n == Vec3::zeros() {
                return Err(Error::Internal);
            }
            let d = f.iter().map(|&v| n.dot(&pts[v as usize])).sum::<f64>() / f.len() as f64;
            face_data.push(FaceData {
                plane: Plane { n, d },
                start: face_verts.len() as u32,
                len: f.len() as u32,
            });
            for k in 0..f.len() {
                let (a, b) = (new_id[f[k] as usize], new_id[f[(k + 1) % f.len()] as usize]);
                face_verts.push(a);
                let e = match edge_of.get(&(a.min(b), a.max(b))) {
                    None => {
                        let e = edges.len() as u32;
                        edge_of.insert((a.min(b), a.max(b)), e);
                        edges.push(EdgeData {
                            tail: a,
                            head: b,
                            left: fi as u32,
                            right: u32::MAX,
                            planes: [dummy; 4],
                        });
                        e
                    }
                    Some(&e) => {
                        let ed = &mut edges[e as usize];
                        if ed.tail != b || ed.head != a || ed.right != u32::MAX {
                            return Err(Error::Internal);
                        }
                        ed.right = fi as u32;
                        e
                    }
                };
                face_edges.push(e);
            }
        }
        if edges.iter().any(|e| e.right == u32::MAX) || nv + face_data.len() != edges.len() + 2 {
            return Err(Error::Internal);
        }
        for e in edges.iter_mut() {
            let (t, h) = (verts[e.tail as usize], verts[e.head as usize]);
            let u = unit(&(h - t));
            let nl = face_data[e.left as usize].plane.n;
            let nr = face_data[e.right as usize].plane.n;
            e.planes = [
                Plane::through(u, &t),
                Plane::through(-u, &h),
                Plane::through(unit(&u.cross(&nl)), &t),
                Plane::through(unit(&nr.cross(&u)), &t),
            ];
        }
        // A face's side plane along an edge is the edge's plane along that face, reversed, bit for
        // bit: a point is then never both over the face (for the edge) and outside the face's prism
        // through that edge (for the face), whatever the rounding.
        let mut face_sides = Vec::with_capacity(face_edges.len());
        for (fi, f) in face_data.iter().enumerate() {
            for k in f.start..f.start + f.len {
                let e = &edges[face_edges[k as usize] as usize];
                let p = if e.left == fi as u32 {
                    e.planes[2]
                } else {
                    e.planes[3]
                };
                face_sides.push(Plane { n: -p.n, d: -p.d });
            }
        }
        let mut deg = vec![0u32; nv + 1];
        for e in &edges {
            deg[e.tail as usize + 1] += 1;
            deg[e.head as usize + 1] += 1;
        }
        for i in 0..nv {
            deg[i + 1] += deg[i];
        }
        let vert_start = deg.clone();
        let m = 2 * edges.len();
        let (mut vert_edges, mut vert_others) = (vec![0u32; m], vec![0u32; m]);
        let mut vert_planes = vec![dummy; m];
        let mut fill = deg;
        for (ei, e) in edges.iter().enumerate() {
            for (v, w) in [(e.tail, e.head), (e.head, e.tail)] {
                let slot = fill[v as usize] as usize;
                fill[v as usize] += 1;
                vert_edges[slot] = ei as u32;
                vert_others[slot] = w;
                let (pv, pw) = (verts[v as usize], verts[w as usize]);
                vert_planes[slot] = Plane::through(unit(&(pv - pw)), &pv);
            }
        }
        if (0..nv).any(|v| vert_start[v + 1] - vert_start[v] < 3) {
            return Err(Error::Internal);
        }
        let centroid = verts.iter().fold(Vec3::zeros(), |s, v| s + v) / nv as f64;
        let radius = verts.iter().fold(0.0f64, |r, v| r.max(v.norm()));
        Ok(ConvexModel {
            uid: NEXT_UID.fetch_add(1, Ordering::Relaxed),
            verts,
            source,
            vert_start,
            vert_edges,
            vert_others,
            vert_planes,
            edges,
            faces: face_data,
            face_verts,
            face_edges,
            face_sides,
            centroid,
            radius,
        })
    }

    /// Identifies this model, so that a pair cache is used only with the models that filled it.
    pub(crate) fn uid(&self) -> u64 {
        self.uid
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.verts.len()
    }

    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.edges.len()
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.faces.len()
    }

    /// Number of features of a kind.
    pub fn num_features(&self, kind: FeatureKind) -> usize {
        match kind {
            FeatureKind::Vertex => self.num_vertices(),
            FeatureKind::Edge => self.num_edges(),
            FeatureKind::Face => self.num_faces(),
        }
    }

    /// Whether `f` names a feature of this model.
    pub fn has_feature(&self, f: Feature) -> bool {
        (f.index as usize) < self.num_features(f.kind)
    }

    /// Vertex `i` (panics if out of range, like slice indexing).
    pub fn vertex(&self, i: usize) -> Vec3 {
        self.verts[i]
    }

    /// All vertices.
    pub fn vertices(&self) -> &[Vec3] {
        &self.verts
    }

    /// Index, in the input of the constructor, of the point that vertex `i` is.
    pub fn vertex_source(&self, i: usize) -> usize {
        self.source[i] as usize
    }

    /// The edges incident to vertex `i`.
    pub fn vertex_edges(&self, i: usize) -> &[u32] {
        let (a, b) = (self.vert_start[i] as usize, self.vert_start[i + 1] as usize);
        &self.vert_edges[a..b]
    }

    /// Edge `i` as `(tail, head)` vertex indices.
    pub fn edge(&self, i: usize) -> (u32, u32) {
        (self.edges[i].tail, self.edges[i].head)
    }

    /// The faces of edge `i` as `(left, right)`: `left` runs along it from tail to head in its
    /// counter-clockwise order.
    pub fn edge_faces(&self, i: usize) -> (u32, u32) {
        (self.edges[i].left, self.edges[i].right)
    }

    /// Face `i`'s vertices, counter-clockwise seen from outside.
    pub fn face(&self, i: usize) -> &[u32] {
        let f = &self.faces[i];
        &self.face_verts[f.start as usize..(f.start + f.len) as usize]
    }

    /// Face `i`'s edges; edge `k` joins vertex `k` to vertex `k + 1` of [`face`](Self::face).
    pub fn face_edges(&self, i: usize) -> &[u32] {
        let f = &self.faces[i];
        &self.face_edges[f.start as usize..(f.start + f.len) as usize]
    }

    /// Face `i`'s plane as `(unit outward normal, offset)`: points `x` of the face have
    /// `normal . x == offset` up to rounding.
    pub fn face_plane(&self, i: usize) -> (Vec3, f64) {
        let p = &self.faces[i].plane;
        (p.n, p.d)
    }

    /// The mean of the vertices (a point inside).
    pub fn centroid(&self) -> Vec3 {
        self.centroid
    }

    // ---- crate-internal views used by the queries ----

    /// Voronoi planes of vertex `v` with the edge each one leads to, and that edge's other end.
    pub(crate) fn vertex_planes(&self, v: u32) -> impl Iterator<Item = (Plane, Feature, u32)> + '_ {
        let (a, b) = (
            self.vert_start[v as usize] as usize,
            self.vert_start[v as usize + 1] as usize,
        );
        (a..b).map(move |k| {
            (
                self.vert_planes[k],
                Feature::edge(self.vert_edges[k]),
                self.vert_others[k],
            )
        })
    }

    /// The other ends of the edges at vertex `v`.
    pub(crate) fn vertex_neighbours(&self, v: u32) -> &[u32] {
        let (a, b) = (
            self.vert_start[v as usize] as usize,
            self.vert_start[v as usize + 1] as usize,
        );
        &self.vert_others[a..b]
    }

    /// The neighbour each Voronoi plane of edge `e` leads to, in the order of `EdgeData::planes`.
    pub(crate) fn edge_neighbours(&self, e: u32) -> [Feature; 4] {
        let d = &self.edges[e as usize];
        [
            Feature::vertex(d.tail),
            Feature::vertex(d.head),
            Feature::face(d.left),
            Feature::face(d.right),
        ]
    }

    /// Side planes of face `f` with the edge each one leads to.
    pub(crate) fn face_side_planes(&self, f: u32) -> impl Iterator<Item = (Plane, Feature)> + '_ {
        let d = &self.faces[f as usize];
        let (a, b) = (d.start as usize, (d.start + d.len) as usize);
        (a..b).map(move |k| (self.face_sides[k], Feature::edge(self.face_edges[k])))
    }

    /// Largest distance of a vertex from the model's origin.
    pub(crate) fn radius(&self) -> f64 {
        self.radius
    }

    #[inline]
    pub(crate) fn vert(&self, v: u32) -> &Vec3 {
        &self.verts[v as usize]
    }
}
