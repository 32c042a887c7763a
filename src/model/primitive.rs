//! Swept-sphere primitives as models: a sphere, a capsule or a box in place of a triangle mesh.
//!
//! A primitive is a solid: the set of points within a radius of a core. The sphere's core is a
//! point (the seeds' point swept sphere), the capsule's a segment (the line swept sphere), the
//! box's the solid box itself with radius 0. The queries (`query/primitive.rs`) measure from the
//! core with the exact triangle kernels, so a primitive needs no hierarchy: it is its own
//! bounding volume.

use super::{BuildState, Model, NEXT_UID};
use crate::bounding_volume::Ssv;
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::Tri;
use crate::math::{Mat3, Vec3};
use std::sync::atomic::Ordering;

/// A solid primitive a [`Model`] holds instead of triangles ([`Model::set_sphere`],
/// [`Model::set_capsule`], [`Model::set_box`]), centred on its model's origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Primitive {
    /// The points within `radius` of the origin.
    Sphere {
        /// Radius (>= 0; 0 is a point).
        radius: f64,
    },
    /// The points within `radius` of the segment from `(0, 0, -length / 2)` to
    /// `(0, 0, length / 2)`: the model's z axis, centred.
    Capsule {
        /// Radius (>= 0).
        radius: f64,
        /// Length of the segment (>= 0; 0 is a sphere).
        length: f64,
    },
    /// The solid box `[-x/2, x/2] x [-y/2, y/2] x [-z/2, z/2]`.
    Box {
        /// Side lengths along the model's x, y and z axes (each >= 0; 0 makes it flat).
        size: [f64; 3],
    },
}

/// What a primitive is swept from, in its model's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Core {
    /// A point or a segment, as a degenerate triangle (the triangle kernels take those).
    Segment(Tri),
    /// The solid box with these half sides.
    Box(Vec3),
}

impl Primitive {
    /// The primitive's core and the radius it is swept by.
    pub(crate) fn core(&self) -> (Core, f64) {
        match *self {
            Primitive::Sphere { radius } => (Core::Segment([Vec3::zeros(); 3]), radius),
            Primitive::Capsule { radius, length } => {
                let (a, b) = (
                    Vec3::new(0.0, 0.0, -0.5 * length),
                    Vec3::new(0.0, 0.0, 0.5 * length),
                );
                (Core::Segment([a, b, b]), radius)
            }
            Primitive::Box { size } => (Core::Box(Vec3::from(size) * 0.5), 0.0),
        }
    }

    /// A swept sphere volume holding the primitive (the primitive itself for a sphere and a
    /// capsule; for a box, the rectangle of its two longest sides swept by half its shortest).
    pub(crate) fn bound(&self) -> Ssv {
        let (core, radius) = self.core();
        match core {
            Core::Segment([a, b, _]) => Ssv {
                axes: Mat3::from_columns(&[Vec3::z(), Vec3::x(), Vec3::y()]),
                origin: a,
                lengths: [b.z - a.z, 0.0],
                radius,
            },
            Core::Box(h) => {
                // The shortest side across the rectangle, the other two (in cyclic order, so
                // that the frame stays right-handed) along it.
                let n = (0..3).min_by(|&i, &j| h[i].total_cmp(&h[j])).unwrap_or(2);
                let (u, v) = ((n + 1) % 3, (n + 2) % 3);
                let axis = |i: usize| Vec3::ith(i, 1.0);
                let mut origin = Vec3::zeros();
                origin[u] = -h[u];
                origin[v] = -h[v];
                Ssv {
                    axes: Mat3::from_columns(&[axis(u), axis(v), axis(n)]),
                    origin,
                    lengths: [2.0 * h[u], 2.0 * h[v]],
                    radius: h[n],
                }
            }
        }
    }

    /// `Err(InvalidArgument)` unless every size is finite, not negative and at most
    /// [`MAX_COORDINATE`]; else the primitive with `-0` made `0`.
    fn checked(self) -> Result<Primitive, Error> {
        let ok = |x: f64| {
            if (0.0..=MAX_COORDINATE).contains(&x) {
                Ok(x + 0.0)
            } else {
                Err(Error::InvalidArgument)
            }
        };
        Ok(match self {
            Primitive::Sphere { radius } => Primitive::Sphere {
                radius: ok(radius)?,
            },
            Primitive::Capsule { radius, length } => Primitive::Capsule {
                radius: ok(radius)?,
                length: ok(length)?,
            },
            Primitive::Box { size: [x, y, z] } => Primitive::Box {
                size: [ok(x)?, ok(y)?, ok(z)?],
            },
        })
    }
}

impl Model {
    /// Replaces the model's contents with the primitive `p`, built: it answers
    /// [`collide`](crate::collide), [`distance`](crate::distance), [`tolerance`](crate::tolerance),
    /// [`within_distance`](crate::within_distance) and their batch and `_into` forms, against
    /// triangle models and other primitives, exactly, as a solid (a triangle inside it collides
    /// with it and is at distance 0). In answers the primitive is one element, with id 0 and
    /// position 0 (`tri1`/`tri2`).
    ///
    /// A primitive model holds no triangles ([`num_triangles`](Model::num_triangles) is 0). Queries
    /// that need triangles or a hierarchy (closest point, signed distance, winding number, rays,
    /// self-collision, time of contact, refit, saving) return `Err(NotATriangleMesh)`;
    /// [`begin`](Model::begin) clears it into an empty mesh being built (and returns
    /// `Err(BuildOutOfSequence)` as on any built model); `add_triangle` and `end` return
    /// `Err(BuildOutOfSequence)` and change nothing.
    ///
    /// `Err(InvalidArgument)` if a size is negative, NaN, infinite or beyond [`MAX_COORDINATE`];
    /// the model is then unchanged.
    ///
    /// ```
    /// use pqp::{Model, Primitive};
    /// let mut m = Model::new();
    /// m.set_primitive(Primitive::Capsule { radius: 0.5, length: 2.0 }).unwrap();
    /// assert!(m.is_built());
    /// assert_eq!(m.primitive(), Some(Primitive::Capsule { radius: 0.5, length: 2.0 }));
    /// assert!(m.set_primitive(Primitive::Sphere { radius: -1.0 }).is_err());
    /// ```
    pub fn set_primitive(&mut self, p: Primitive) -> Result<(), Error> {
        let p = p.checked()?;
        self.pending = Vec::new();
        self.bvh = None;
        self.primitive = Some(p);
        self.state = BuildState::Built;
        self.uid = NEXT_UID.fetch_add(1, Ordering::Relaxed);
        Ok(())
    }

    /// [`set_primitive`](Model::set_primitive) with a sphere of `radius` centred on the origin.
    ///
    /// ```
    /// use pqp::{distance, DistanceOptions, Model, Pose};
    /// let mut ball = Model::new();
    /// ball.set_sphere(1.0).unwrap();
    /// let floor = Model::from_triangles([([-5.0, -5.0, 0.0], [5.0, -5.0, 0.0], [0.0, 5.0, 0.0], 3)]).unwrap();
    /// let up = Pose::from_translation([0.0, 0.0, 3.0]);
    /// let r = distance(&ball, &up, &floor, &Pose::identity(), &DistanceOptions::exact()).unwrap();
    /// assert_eq!((r.distance, r.id1, r.id2), (2.0, 0, 3));
    /// ```
    pub fn set_sphere(&mut self, radius: f64) -> Result<(), Error> {
        self.set_primitive(Primitive::Sphere { radius })
    }

    /// [`set_primitive`](Model::set_primitive) with a capsule: the points within `radius` of the
    /// segment of `length` on the model's z axis, centred on the origin.
    ///
    /// ```
    /// use pqp::{collide, ContactMode, Model, Pose};
    /// let mut rod = Model::new();
    /// rod.set_capsule(0.1, 4.0).unwrap();
    /// let tri = Model::from_triangles([([0.0, 0.0, 1.9], [1.0, 0.0, 1.9], [0.0, 1.0, 1.9], 5)]).unwrap();
    /// let hit = collide(&rod, &Pose::identity(), &tri, &Pose::identity(), ContactMode::All).unwrap();
    /// assert_eq!((hit.pairs()[0].id1, hit.pairs()[0].id2), (0, 5));
    /// ```
    pub fn set_capsule(&mut self, radius: f64, length: f64) -> Result<(), Error> {
        self.set_primitive(Primitive::Capsule { radius, length })
    }

    /// [`set_primitive`](Model::set_primitive) with the solid box of side lengths `x`, `y`, `z`
    /// along the model's axes, centred on the origin.
    ///
    /// ```
    /// use pqp::{tolerance, Model, Pose, Search};
    /// let mut crate_ = Model::new();
    /// crate_.set_box(2.0, 2.0, 2.0).unwrap();
    /// // A triangle inside the box: the solid box touches it.
    /// let inner = Model::from_triangles([([0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1], 1)]).unwrap();
    /// let here = Pose::identity();
    /// assert!(tolerance(&crate_, &here, &inner, &here, 0.0, &Search::default()).unwrap().closer_than_tolerance);
    /// ```
    pub fn set_box(&mut self, x: f64, y: f64, z: f64) -> Result<(), Error> {
        self.set_primitive(Primitive::Box { size: [x, y, z] })
    }

    /// The primitive the model holds, if it holds one rather than triangles.
    pub fn primitive(&self) -> Option<Primitive> {
        self.primitive
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_sizes_change_nothing() {
        let mut m = Model::new();
        m.set_box(1.0, 2.0, 3.0).unwrap();
        let uid = m.uid();
        for bad in [
            -1.0,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            2e150,
            -1e-300,
        ] {
            assert_eq!(m.set_sphere(bad), Err(Error::InvalidArgument));
            assert_eq!(m.set_capsule(1.0, bad), Err(Error::InvalidArgument));
            assert_eq!(m.set_capsule(bad, 1.0), Err(Error::InvalidArgument));
            assert_eq!(m.set_box(1.0, 1.0, bad), Err(Error::InvalidArgument));
            assert_eq!(m.set_box(bad, 1.0, 1.0), Err(Error::InvalidArgument));
        }
        assert_eq!(
            m.primitive(),
            Some(Primitive::Box {
                size: [1.0, 2.0, 3.0]
            })
        );
        assert_eq!(m.uid(), uid);
        // -0 is 0.
        m.set_sphere(-0.0).unwrap();
        assert_eq!(m.primitive(), Some(Primitive::Sphere { radius: 0.0 }));
    }

    #[test]
    fn the_bound_holds_the_primitive() {
        for p in [
            Primitive::Sphere { radius: 1.5 },
            Primitive::Capsule {
                radius: 0.25,
                length: 3.0,
            },
            Primitive::Box {
                size: [1.0, 4.0, 0.5],
            },
            Primitive::Box {
                size: [3.0, 0.0, 2.0],
            },
        ] {
            let (core, radius) = p.core();
            let v = p.bound();
            let corners: Vec<Vec3> = match core {
                Core::Segment(s) => {
                    let dirs = [Vec3::x(), -Vec3::x(), Vec3::y(), -Vec3::y()];
                    let mut c: Vec<Vec3> = dirs.iter().map(|d| s[0] + d * radius).collect();
                    c.extend(dirs.iter().map(|d| s[1] + d * radius));
                    c.push(s[0] - Vec3::z() * radius);
                    c.push(s[1] + Vec3::z() * radius);
                    c
                }
                Core::Box(h) => (0..8)
                    .map(|k| {
                        let s = |b: usize| if k >> b & 1 == 1 { 1.0 } else { -1.0 };
                        Vec3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
                    })
                    .collect(),
            };
            for c in corners {
                assert!(
                    crate::bounding_volume::BoundingVolume::contains(&v, &c, 1e-12),
                    "{p:?} {c}"
                );
            }
            assert!((v.axes.determinant() - 1.0).abs() < 1e-12);
        }
    }
}
