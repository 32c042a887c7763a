//! The fuzz targets' bodies: each takes the fuzzer's bytes, decodes them into calls of the C ABI
//! (through `pqp::capi`, exactly the functions C programs call) and checks what the header
//! promises, panicking on the first broken promise. `fuzz_targets/*.rs` hand libFuzzer's input to
//! these; `tests/fuzz_regressions.rs` (in the main crate, on stable) replays every committed input
//! of `corpus/` and `regressions/` through the same functions.
//!
//! - [`build_protocol`]: the build protocol on a few model slots with hostile numbers (NaN,
//!   infinities, subnormals, values around the 1e150 limit, huge hints) and calls in any order
//!   (create, begin, add, end, clone, destroy, volume choices, the PQP 1.3 views), against a shadow
//!   of what each model must hold.
//! - [`queries`]: two small models and a random pose pair through every query (collide with both
//!   flags, distance with random error bounds and search options, tolerance), checked against each
//!   other and against a brute-force minimum over triangle pairs by `pqp_triangle_distance`.
//! - [`convex`]: convex models from points and from triangles (valid and broken meshes), then
//!   distance, intersect and penetration, checked against each other and against the triangle-mesh
//!   queries on the hulls' faces.
//! - [`deserialize`]: bytes given to `pqp_model_deserialize` (as they are, or with their checksum,
//!   of either version, recomputed so that the checks of the contents are reached), into a fresh
//!   and into a built model: refused with `PQP_ERR_INVALID_DATA` and the model unchanged, or loaded
//!   as a model that saves to exactly those bytes (version 1 ones as version 2) and that every
//!   query and view runs on.
//! - [`more_queries`]: what PQP 1.3 lacks, on two small models whose triangles share vertices:
//!   closest point and signed distance (against a brute-force minimum and winding number), rays
//!   and their batch form (against crossings well inside a triangle), pairs within a distance,
//!   self-collision (against collide of the model with itself), refit (against a rebuilt model)
//!   and time of contact (against the distance sampled along the same motion).
//!
//! A broken promise is a panic with a message saying which; `PQP_ERR_INTERNAL` (a caught panic
//! inside the library) counts as one.
#![allow(clippy::missing_safety_doc, clippy::manual_is_multiple_of)]

use pqp::capi::*;
use std::ffi::c_int;
use std::ptr::{null, null_mut};

/// Reads the fuzzer's bytes; past their end it yields zeros, so every input decodes.
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, pos: 0 }
    }
    pub fn done(&self) -> bool {
        self.pos >= self.data.len()
    }
    pub fn u8(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }
    pub fn u64(&mut self) -> u64 {
        (self.u32() as u64) | ((self.u32() as u64) << 32)
    }
    /// An int, often one of the interesting ones.
    pub fn int(&mut self) -> c_int {
        const SPECIAL: [c_int; 8] = [0, 1, 2, 3, -1, c_int::MIN, c_int::MAX, 1 << 30];
        let sel = self.u8();
        if sel < 128 {
            SPECIAL[(sel % 8) as usize]
        } else {
            self.u32() as c_int
        }
    }
    /// A small coordinate on a grid of quarters in [-4, 4], so that exact contacts happen.
    pub fn grid(&mut self) -> f64 {
        (self.u8() as i32 - 128) as f64 / 32.0
    }
    /// A number that may be anything: special values, values at and past the 1e150 limit,
    /// subnormals, raw bits, or a grid value.
    pub fn hostile(&mut self) -> f64 {
        const SPECIAL: [f64; 16] = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e150,
            -1e150,
            1.0000000000000002e150,
            1e151,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            1e-310,
            0.0,
            -0.0,
            1e-150,
            1e100,
        ];
        let sel = self.u8();
        match sel % 4 {
            0 => SPECIAL[(sel / 4 % 16) as usize],
            1 => f64::from_bits(self.u64()),
            _ => self.grid(),
        }
    }
    /// A valid coordinate: a grid value, or now and then one scaled far up or down (still within
    /// the 1e150 limit).
    pub fn coord(&mut self) -> f64 {
        let sel = self.u8();
        let g = self.grid();
        match sel % 16 {
            0 => g * 1e-140,
            1 => g * 1e140,
            2 => g * 1e-6,
            3 => g + self.grid() * 1e-9,
            _ => g,
        }
    }
    /// A rotation: the identity, a signed axis permutation, or one from a (normalised) random
    /// quaternion.
    pub fn rotation(&mut self) -> [f64; 9] {
        let sel = self.u8();
        match sel % 4 {
            0 => [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
            1 => {
                let perm = [[0, 1, 2], [1, 2, 0], [2, 0, 1]][(sel / 4 % 3) as usize];
                let mut r = [0.0; 9];
                for (i, &j) in perm.iter().enumerate() {
                    // An even permutation keeps det +1; flip two signs at most.
                    let s = if i < 2 && sel & 0x40 != 0 { -1.0 } else { 1.0 };
                    r[3 * i + j] = s;
                }
                r
            }
            _ => {
                let q = [self.grid(), self.grid(), self.grid(), self.grid()];
                let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
                if n == 0.0 {
                    return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
                }
                let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
                [
                    1.0 - 2.0 * (y * y + z * z),
                    2.0 * (x * y - z * w),
                    2.0 * (x * z + y * w),
                    2.0 * (x * y + z * w),
                    1.0 - 2.0 * (x * x + z * z),
                    2.0 * (y * z - x * w),
                    2.0 * (x * z - y * w),
                    2.0 * (y * z + x * w),
                    1.0 - 2.0 * (x * x + y * y),
                ]
            }
        }
    }
    /// A pose: a rotation and a translation of grid values (hostile entries now and then).
    pub fn pose(&mut self) -> ([f64; 9], [f64; 3]) {
        let mut r = self.rotation();
        let mut t = [self.grid(), self.grid(), self.grid()];
        if self.u8() == 0xff {
            let k = self.u8() as usize;
            let v = self.hostile();
            // A pose the library accepts must be a rotation (the header's contract, not checked):
            // an accepted value goes into the translation.
            if k % 2 == 0 && !acceptable(v) {
                r[k / 2 % 9] = v;
            } else {
                t[k / 2 % 3] = v;
            }
        }
        (r, t)
    }
}

/// Whether the library accepts a coordinate or pose entry: finite and at most 1e150 in magnitude.
pub fn acceptable(x: f64) -> bool {
    x.is_finite() && x.abs() <= 1e150
}

fn assert_code(what: &str, rc: c_int, allowed: &[c_int]) {
    assert!(
        allowed.contains(&rc),
        "{what} returned {rc} ({}), expected one of {allowed:?}",
        unsafe { std::ffi::CStr::from_ptr(pqp_error_string(rc)) }.to_string_lossy()
    );
}

// ---------------------------------------------------------------------------------------------
// Build protocol.

#[derive(Clone, PartialEq, Debug)]
enum State {
    Empty,
    Begun,
    Built,
}

/// What a model must hold: its state and its accepted triangles.
#[derive(Clone)]
struct Shadow {
    state: State,
    tris: Vec<([f64; 9], c_int)>,
}

struct Slot {
    handle: *mut pqp_model,
    shadow: Shadow,
}

const SLOTS: usize = 3;

/// Checks a model against its shadow through every getter and both views.
unsafe fn check_model(m: *mut pqp_model, s: &Shadow, views: bool) {
    let state = match s.state {
        State::Empty => PQP_BUILD_STATE_EMPTY,
        State::Begun => PQP_BUILD_STATE_BEGUN,
        State::Built => PQP_BUILD_STATE_PROCESSED,
    };
    assert_eq!(
        pqp_model_build_state(m),
        state,
        "build state, shadow {:?}",
        s.state
    );
    assert_eq!(pqp_model_is_built(m), (s.state == State::Built) as c_int);
    assert_eq!(pqp_model_num_tris(m) as usize, s.tris.len(), "num_tris");
    if !views {
        return;
    }
    let mut tris: *const pqp_tri = null();
    let mut n: c_int = -1;
    assert_code(
        "pqp_model_tris",
        pqp_model_tris(m, &mut tris, &mut n),
        &[PQP_OK],
    );
    assert_eq!(n as usize, s.tris.len(), "pqp_model_tris count");
    for (k, (v, id)) in s.tris.iter().enumerate() {
        let t = &*tris.add(k);
        let got = [t.p1, t.p2, t.p3].concat();
        assert!(
            got.iter().zip(v).all(|(a, b)| a.to_bits() == b.to_bits()),
            "triangle {k} of the view differs from what was added"
        );
        assert_eq!(t.id, *id, "triangle {k}'s id");
    }
    let mut tf: *const pqp_tri_float = null();
    let mut nf: c_int = -1;
    assert_code(
        "pqp_model_tris_float",
        pqp_model_tris_float(m, &mut tf, &mut nf),
        &[PQP_OK],
    );
    assert_eq!(nf, n);
    let mut bvs: *const pqp_bv = null();
    let mut nb: c_int = -1;
    let rc = pqp_model_bvs(m, &mut bvs, &mut nb);
    let mut bf: *const pqp_bv_float = null();
    let mut nbf: c_int = -1;
    let rcf = pqp_model_bvs_float(m, &mut bf, &mut nbf);
    assert_eq!(rc, rcf, "pqp_model_bvs and _float disagree");
    if s.state != State::Built {
        assert_code("pqp_model_bvs (unbuilt)", rc, &[PQP_ERR_UNPROCESSED_MODEL]);
        assert!(bvs.is_null() && nb == 0, "bvs on error");
        return;
    }
    assert_code("pqp_model_bvs", rc, &[PQP_OK]);
    let nt = s.tris.len() as c_int;
    assert_eq!(nb, 2 * nt - 1, "2 n - 1 volumes");
    assert_eq!(nbf, nb);
    // Every volume is reached once from the root; every triangle is in exactly one leaf.
    let mut reached = vec![false; nb as usize];
    let mut leaf_of = vec![false; nt as usize];
    let mut stack = vec![0usize];
    while let Some(k) = stack.pop() {
        assert!(!reached[k], "volume {k} reached twice");
        reached[k] = true;
        let b = &*bvs.add(k);
        assert!(b.r >= 0.0 && !b.r.is_nan(), "volume {k}'s radius {}", b.r);
        if b.first_child >= 0 {
            let c = b.first_child as usize;
            assert!(c > k && c + 1 < nb as usize, "volume {k}'s children at {c}");
            stack.push(c);
            stack.push(c + 1);
        } else {
            let t = (-(b.first_child as i64) - 1) as usize;
            assert!(t < nt as usize, "leaf {k} holds triangle {t} of {nt}");
            assert!(!leaf_of[t], "triangle {t} in two leaves");
            leaf_of[t] = true;
        }
    }
    assert!(
        reached.iter().all(|&r| r),
        "a volume is not reachable from the root"
    );
    assert!(leaf_of.iter().all(|&l| l), "a triangle is in no leaf");
}

/// The build protocol, driven by `data` (see the crate documentation).
pub fn build_protocol(data: &[u8]) {
    let mut input = Bytes::new(data);
    let mut slots: Vec<Option<Slot>> = (0..SLOTS).map(|_| None).collect();
    let mut ops = 0;
    unsafe {
        while !input.done() && ops < 200 {
            ops += 1;
            let op = input.u8();
            let k = (input.u8() as usize) % SLOTS;
            match op % 12 {
                0 => {
                    if let Some(s) = slots[k].take() {
                        pqp_model_destroy(s.handle);
                    }
                    let h = pqp_model_create();
                    assert!(!h.is_null());
                    slots[k] = Some(Slot {
                        handle: h,
                        shadow: Shadow {
                            state: State::Empty,
                            tris: Vec::new(),
                        },
                    });
                }
                1 => {
                    if let Some(s) = slots[k].take() {
                        pqp_model_destroy(s.handle);
                    }
                }
                2 => {
                    let hint = input.int();
                    if let Some(s) = slots[k].as_mut() {
                        let rc = pqp_model_begin(s.handle, hint);
                        let expect = if s.shadow.state == State::Empty {
                            PQP_OK
                        } else {
                            PQP_ERR_BUILD_OUT_OF_SEQUENCE
                        };
                        // A negative hint may be refused as an invalid argument.
                        if rc == PQP_ERR_INVALID_ARGUMENT && hint < 0 {
                            continue;
                        }
                        assert_code("pqp_model_begin", rc, &[expect]);
                        s.shadow = Shadow {
                            state: State::Begun,
                            tris: Vec::new(),
                        };
                    } else {
                        assert_code(
                            "begin(NULL)",
                            pqp_model_begin(null_mut(), hint),
                            &[PQP_ERR_NULL_POINTER],
                        );
                    }
                }
                3..=5 => {
                    let hostile = op % 12 == 3;
                    let mut v = [0.0; 9];
                    for x in v.iter_mut() {
                        *x = if hostile {
                            input.hostile()
                        } else {
                            input.coord()
                        };
                    }
                    let id = input.int();
                    let Some(s) = slots[k].as_mut() else {
                        continue;
                    };
                    let rc = pqp_model_add_tri(
                        s.handle,
                        v[0..3].as_ptr(),
                        v[3..6].as_ptr(),
                        v[6..9].as_ptr(),
                        id,
                    );
                    let ok = v.iter().all(|&x| acceptable(x));
                    match s.shadow.state {
                        State::Built => {
                            if ok {
                                assert_code(
                                    "add_tri after end",
                                    rc,
                                    &[PQP_ERR_BUILD_OUT_OF_SEQUENCE],
                                );
                            } else {
                                assert_code(
                                    "add_tri (bad) after end",
                                    rc,
                                    &[PQP_ERR_BUILD_OUT_OF_SEQUENCE, PQP_ERR_NONFINITE_COORDINATE],
                                );
                            }
                        }
                        _ => {
                            s.shadow.state = State::Begun;
                            if ok {
                                assert_code("add_tri", rc, &[PQP_OK]);
                                s.shadow.tris.push((v, id));
                            } else {
                                assert_code("add_tri (bad)", rc, &[PQP_ERR_NONFINITE_COORDINATE]);
                            }
                        }
                    }
                }
                6 => {
                    let Some(s) = slots[k].as_mut() else {
                        assert_code(
                            "end(NULL)",
                            pqp_model_end(null_mut()),
                            &[PQP_ERR_NULL_POINTER],
                        );
                        continue;
                    };
                    let rc = pqp_model_end(s.handle);
                    if s.shadow.state == State::Built {
                        assert_code("end on a built model", rc, &[PQP_ERR_BUILD_OUT_OF_SEQUENCE]);
                    } else if s.shadow.tris.is_empty() {
                        assert_code("end on an empty model", rc, &[PQP_ERR_BUILD_EMPTY_MODEL]);
                    } else {
                        assert_code("end", rc, &[PQP_OK]);
                        s.shadow.state = State::Built;
                    }
                }
                7 => {
                    let to = (input.u8() as usize) % SLOTS;
                    let Some(s) = slots[k].as_ref() else {
                        let mut out: *mut pqp_model = std::ptr::NonNull::dangling().as_ptr();
                        assert_code(
                            "clone(NULL)",
                            pqp_model_clone(&mut out, null()),
                            &[PQP_ERR_NULL_POINTER],
                        );
                        assert!(out.is_null(), "clone(NULL) left a handle");
                        continue;
                    };
                    let mut out: *mut pqp_model = null_mut();
                    assert_code("clone", pqp_model_clone(&mut out, s.handle), &[PQP_OK]);
                    assert!(!out.is_null());
                    let shadow = s.shadow.clone();
                    check_model(out, &shadow, false);
                    if let Some(old) = slots[to].take() {
                        pqp_model_destroy(old.handle);
                    }
                    slots[to] = Some(Slot {
                        handle: out,
                        shadow,
                    });
                }
                8 => {
                    if let Some(s) = slots[k].as_ref() {
                        check_model(s.handle, &s.shadow, true);
                    }
                }
                9 => {
                    let kind = input.int();
                    let coll = input.int();
                    if let Some(s) = slots[k].as_ref() {
                        let rc = pqp_model_set_volume(s.handle, kind);
                        let valid = (0..=3).contains(&kind);
                        assert_code(
                            "set_volume",
                            rc,
                            if valid {
                                &[PQP_OK, PQP_ERR_BUILD_OUT_OF_SEQUENCE]
                            } else {
                                &[PQP_ERR_INVALID_ARGUMENT, PQP_ERR_BUILD_OUT_OF_SEQUENCE]
                            },
                        );
                        let rc = pqp_model_set_collision_volume(s.handle, coll);
                        let valid = (0..=1).contains(&coll);
                        assert_code(
                            "set_collision_volume",
                            rc,
                            if valid {
                                &[PQP_OK, PQP_ERR_BUILD_OUT_OF_SEQUENCE]
                            } else {
                                &[PQP_ERR_INVALID_ARGUMENT, PQP_ERR_BUILD_OUT_OF_SEQUENCE]
                            },
                        );
                    }
                }
                10 => {
                    // A query on whatever the slots hold: codes only, and self-consistency.
                    let j = (input.u8() as usize) % SLOTS;
                    let (Some(a), Some(b)) = (slots[k].as_ref(), slots[j].as_ref()) else {
                        continue;
                    };
                    let (r1, t1) = input.pose();
                    let (r2, t2) = input.pose();
                    let built = a.shadow.state == State::Built && b.shadow.state == State::Built;
                    let pose_ok = r1
                        .iter()
                        .chain(&t1)
                        .chain(&r2)
                        .chain(&t2)
                        .all(|&x| acceptable(x));
                    let d = pqp_distance_result_create();
                    let rc = pqp_distance(
                        d,
                        r1.as_ptr(),
                        t1.as_ptr(),
                        a.handle,
                        r2.as_ptr(),
                        t2.as_ptr(),
                        b.handle,
                        0.0,
                        0.0,
                        2,
                    );
                    if !built {
                        assert_code(
                            "distance (unbuilt)",
                            rc,
                            &[PQP_ERR_UNPROCESSED_MODEL, PQP_ERR_NONFINITE_POSE],
                        );
                    } else if !pose_ok {
                        assert_code("distance (bad pose)", rc, &[PQP_ERR_NONFINITE_POSE]);
                    } else {
                        assert_code("distance", rc, &[PQP_OK]);
                        let dist = pqp_distance_result_distance(d);
                        assert!(dist >= 0.0, "distance {dist}");
                    }
                    pqp_distance_result_destroy(d);
                }
                _ => {
                    if let Some(s) = slots[k].as_ref() {
                        let _ = pqp_model_memory_usage(s.handle);
                        check_model(s.handle, &s.shadow, false);
                    }
                }
            }
        }
        for s in slots.into_iter().flatten() {
            check_model(s.handle, &s.shadow, true);
            pqp_model_destroy(s.handle);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Queries.

type Tri = [f64; 9];

fn apply(r: &[f64; 9], t: &[f64; 3], p: &[f64]) -> [f64; 3] {
    [
        r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0],
        r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1],
        r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2],
    ]
}

fn world(r: &[f64; 9], t: &[f64; 3], tri: &Tri) -> Tri {
    let (a, b, c) = (
        apply(r, t, &tri[0..3]),
        apply(r, t, &tri[3..6]),
        apply(r, t, &tri[6..9]),
    );
    [a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]
}

fn tri_distance(s: &Tri, t: &Tri) -> f64 {
    let (mut d, mut p, mut q) = (0.0, [0.0; 3], [0.0; 3]);
    let rc = unsafe {
        pqp_triangle_distance(
            &mut d,
            p.as_mut_ptr(),
            q.as_mut_ptr(),
            s.as_ptr(),
            t.as_ptr(),
        )
    };
    assert_code("pqp_triangle_distance", rc, &[PQP_OK]);
    d
}

unsafe fn build(tris: &[Tri], first_id: c_int, volume: c_int, coll: c_int) -> *mut pqp_model {
    let m = pqp_model_create();
    assert_code("set_volume", pqp_model_set_volume(m, volume), &[PQP_OK]);
    assert_code(
        "set_collision_volume",
        pqp_model_set_collision_volume(m, coll),
        &[PQP_OK],
    );
    assert_code("begin", pqp_model_begin(m, tris.len() as c_int), &[PQP_OK]);
    for (i, t) in tris.iter().enumerate() {
        let rc = pqp_model_add_tri(
            m,
            t[0..3].as_ptr(),
            t[3..6].as_ptr(),
            t[6..9].as_ptr(),
            first_id + i as c_int,
        );
        assert_code("add_tri", rc, &[PQP_OK]);
    }
    assert_code("end", pqp_model_end(m), &[PQP_OK]);
    m
}

fn dist3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Every query on two small models at one pose pair (see the crate documentation).
pub fn queries(data: &[u8]) {
    let mut input = Bytes::new(data);
    let n1 = 1 + (input.u8() % 6) as usize;
    let n2 = 1 + (input.u8() % 6) as usize;
    let tris = |n: usize, input: &mut Bytes| -> Vec<Tri> {
        (0..n)
            .map(|_| {
                let mut t = [0.0; 9];
                for x in t.iter_mut() {
                    *x = input.coord();
                }
                t
            })
            .collect()
    };
    let a = tris(n1, &mut input);
    let b = tris(n2, &mut input);
    let (va, ca) = ((input.u8() % 4) as c_int, (input.u8() % 2) as c_int);
    let (vb, cb) = ((input.u8() % 4) as c_int, (input.u8() % 2) as c_int);
    let (r1, t1) = input.pose();
    let (r2, t2) = input.pose();
    let pose_ok = r1
        .iter()
        .chain(&t1)
        .chain(&r2)
        .chain(&t2)
        .all(|&x| acceptable(x));
    const ID1: c_int = 1000;
    const ID2: c_int = -50;

    // Brute force in the world frame; `scale` bounds the scene's coordinates, for the allowance.
    let wa: Vec<Tri> = a.iter().map(|t| world(&r1, &t1, t)).collect();
    let wb: Vec<Tri> = b.iter().map(|t| world(&r2, &t2, t)).collect();
    let scale = wa
        .iter()
        .chain(&wb)
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let eps = 1e-9 * scale;
    let mut brute = f64::INFINITY;
    // Without a brute force (a pose moves a coordinate past the 1e150 that pqp_triangle_distance
    // accepts; the library works in model 1's frame and still answers), every pair counts as
    // touching, which no check below can fail on.
    let mut pair_d = vec![vec![0.0; n2]; n1];
    let brute_ok = pose_ok && wa.iter().chain(&wb).flatten().all(|&x| acceptable(x));
    if brute_ok {
        for i in 0..n1 {
            for j in 0..n2 {
                pair_d[i][j] = tri_distance(&wa[i], &wb[j]);
                brute = brute.min(pair_d[i][j]);
            }
        }
    }

    unsafe {
        let m1 = build(&a, ID1, va, ca);
        let m2 = build(&b, ID2, vb, cb);
        let (r1p, t1p, r2p, t2p) = (r1.as_ptr(), t1.as_ptr(), r2.as_ptr(), t2.as_ptr());

        // Collision, both flags.
        let c = pqp_collide_result_create();
        let rc = pqp_collide(c, r1p, t1p, m1, r2p, t2p, m2, PQP_ALL_CONTACTS);
        if !pose_ok {
            assert_code("collide (bad pose)", rc, &[PQP_ERR_NONFINITE_POSE]);
            pqp_collide_result_destroy(c);
            pqp_model_destroy(m1);
            pqp_model_destroy(m2);
            return;
        }
        assert_code("collide", rc, &[PQP_OK]);
        let np = pqp_collide_result_num_pairs(c);
        let colliding = pqp_collide_result_colliding(c) != 0;
        assert_eq!(colliding, np > 0, "colliding flag vs pair count");
        let mut all = Vec::new();
        for k in 0..np {
            let (i1, i2) = (pqp_collide_result_id1(c, k), pqp_collide_result_id2(c, k));
            let (i, j) = ((i1 - ID1) as usize, (i2 - ID2) as usize);
            assert!(i < n1 && j < n2, "pair {k}: ids {i1}, {i2} out of range");
            assert!(
                pair_d[i][j] <= eps,
                "pair ({i}, {j}) reported colliding at distance {}",
                pair_d[i][j]
            );
            all.push((i, j));
        }
        let len = all.len();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), len, "a pair reported twice");
        for (i, row) in pair_d.iter().enumerate() {
            for (j, &d) in row.iter().enumerate() {
                // A pair robustly apart (or robustly crossing) must be classified so.
                if d > eps {
                    assert!(!all.contains(&(i, j)));
                }
            }
        }
        let rc = pqp_collide(c, r1p, t1p, m1, r2p, t2p, m2, PQP_FIRST_CONTACT);
        assert_code("collide first", rc, &[PQP_OK]);
        let nf = pqp_collide_result_num_pairs(c);
        assert_eq!(nf > 0, colliding, "first contact vs all contacts");
        assert!(nf <= np);
        for k in 0..nf {
            let p = (
                (pqp_collide_result_id1(c, k) - ID1) as usize,
                (pqp_collide_result_id2(c, k) - ID2) as usize,
            );
            assert!(
                all.contains(&p),
                "first-contact pair {p:?} not among all pairs"
            );
        }
        let bad_flag = input.int();
        if bad_flag != PQP_ALL_CONTACTS && bad_flag != PQP_FIRST_CONTACT {
            let rc = pqp_collide(c, r1p, t1p, m1, r2p, t2p, m2, bad_flag);
            assert_code("collide (bad flag)", rc, &[PQP_ERR_INVALID_ARGUMENT]);
        }
        pqp_collide_result_destroy(c);

        // Exact distance, default search.
        let d = pqp_distance_result_create();
        let rc = pqp_distance(d, r1p, t1p, m1, r2p, t2p, m2, 0.0, 0.0, 2);
        assert_code("distance", rc, &[PQP_OK]);
        let exact = pqp_distance_result_distance(d);
        assert!(exact >= 0.0, "distance {exact}");
        assert!(
            !brute_ok || (exact - brute).abs() <= eps,
            "distance {exact}, brute force {brute}"
        );
        assert_eq!(
            exact == 0.0,
            colliding,
            "distance {exact} but colliding {colliding}"
        );
        assert_eq!(
            pqp_distance_result_overlap(d) != 0,
            exact == 0.0,
            "overlap flag"
        );
        check_distance_result(d, &r1, &t1, &r2, &t2, &pair_d, ID1, ID2, exact, eps);

        // Random error bounds and search options, on a reused result (cache, front) or a fresh one.
        for _ in 0..3 {
            let rel = if input.u8() % 2 == 0 {
                input.hostile().abs()
            } else {
                input.hostile()
            };
            let abs = if input.u8() % 2 == 0 {
                input.hostile().abs()
            } else {
                input.hostile()
            };
            let opts = pqp_search_options {
                strategy: if input.u8() < 240 {
                    (input.u8() % 4) as c_int
                } else {
                    input.int()
                },
                qsize: if input.u8() < 240 {
                    (input.u8() % 5) as c_int
                } else {
                    input.int()
                },
                triangle_cache: if input.u8() < 240 {
                    (input.u8() % 2) as c_int
                } else {
                    input.int()
                },
            };
            let valid_opts = (0..=3).contains(&opts.strategy)
                && opts.qsize >= 0
                && (0..=1).contains(&opts.triangle_cache);
            let fresh = input.u8() % 2 == 0;
            let r = if fresh {
                pqp_distance_result_create()
            } else {
                d
            };
            let use_opts = input.u8() % 4 != 0;
            let rc = pqp_distance_search(
                r,
                r1p,
                t1p,
                m1,
                r2p,
                t2p,
                m2,
                rel,
                abs,
                if use_opts { &opts } else { null() },
            );
            if rel.is_nan() || abs.is_nan() || rel < 0.0 || abs < 0.0 || (use_opts && !valid_opts) {
                assert_code(
                    "distance_search (bad arguments)",
                    rc,
                    &[PQP_ERR_INVALID_ARGUMENT],
                );
            } else {
                assert_code("distance_search", rc, &[PQP_OK]);
                let got = pqp_distance_result_distance(r);
                let bound = if abs == 0.0 {
                    exact
                } else {
                    (exact * (1.0 + rel)).min(exact + abs)
                };
                assert!(
                    got >= exact - eps && got <= bound + eps,
                    "distance {got} with rel_err {rel}, abs_err {abs}: exact {exact}"
                );
                if exact == 0.0 {
                    assert_eq!(got, 0.0, "overlapping models at a non-zero distance");
                }
                check_distance_result(r, &r1, &t1, &r2, &t2, &pair_d, ID1, ID2, got, eps);
            }
            if fresh {
                pqp_distance_result_destroy(r);
            }
        }
        pqp_distance_result_destroy(d);

        // Tolerance: a tolerance near the distance, or anything.
        let tr = pqp_tolerance_result_create();
        for _ in 0..2 {
            let sel = input.u8();
            let tol = match sel % 4 {
                0 => input.hostile(),
                1 => exact,
                _ => exact * (1.0 + input.grid() / 8.0) + input.grid() * 1e-3,
            };
            let use_opts = sel & 0x80 != 0;
            let opts = pqp_search_options {
                strategy: (input.u8() % 4) as c_int,
                qsize: (input.u8() % 3) as c_int,
                triangle_cache: (input.u8() % 2) as c_int,
            };
            let rc = if use_opts {
                pqp_tolerance_search(tr, r1p, t1p, m1, r2p, t2p, m2, tol, &opts)
            } else {
                pqp_tolerance(tr, r1p, t1p, m1, r2p, t2p, m2, tol, 2)
            };
            if tol.is_nan() || tol < 0.0 {
                assert_code("tolerance (bad)", rc, &[PQP_ERR_INVALID_ARGUMENT]);
                continue;
            }
            assert_code("tolerance", rc, &[PQP_OK]);
            let closer = pqp_tolerance_result_closer_than_tolerance(tr) != 0;
            let td = pqp_tolerance_result_distance(tr);
            if exact < tol - eps {
                assert!(closer, "distance {exact} < tolerance {tol} but not closer");
            }
            if exact > tol + eps {
                assert!(!closer, "distance {exact} > tolerance {tol} but closer");
            }
            if closer {
                assert!(
                    td <= tol,
                    "closer, yet reported distance {td} > tolerance {tol}"
                );
            } else {
                assert!(
                    td > tol,
                    "not closer: lower bound {td} must exceed tolerance {tol}"
                );
                assert!(
                    td <= exact + eps,
                    "lower bound {td} above the distance {exact}"
                );
            }
        }
        pqp_tolerance_result_destroy(tr);
        pqp_model_destroy(m1);
        pqp_model_destroy(m2);
    }
}

/// The closest points, ids and triangles of a distance result against the brute force.
#[allow(clippy::too_many_arguments)]
unsafe fn check_distance_result(
    d: *const pqp_distance_result,
    r1: &[f64; 9],
    t1: &[f64; 3],
    r2: &[f64; 9],
    t2: &[f64; 3],
    pair_d: &[Vec<f64>],
    id1: c_int,
    id2: c_int,
    dist: f64,
    eps: f64,
) {
    let (i, j) = (
        (pqp_distance_result_id1(d) - id1) as usize,
        (pqp_distance_result_id2(d) - id2) as usize,
    );
    assert!(
        i < pair_d.len() && j < pair_d[0].len(),
        "distance ids out of range"
    );
    let (mut ti, mut tj) = (-2, -2);
    assert_code(
        "distance_result_triangles",
        pqp_distance_result_triangles(d, &mut ti, &mut tj),
        &[PQP_OK],
    );
    assert_eq!((ti as usize, tj as usize), (i, j), "triangles vs ids");
    assert!(
        pair_d[i][j] <= dist + eps,
        "the reported pair is {} apart, distance {dist}",
        pair_d[i][j]
    );
    let p1 = std::slice::from_raw_parts(pqp_distance_result_p1(d), 3);
    let p2 = std::slice::from_raw_parts(pqp_distance_result_p2(d), 3);
    let (w1, w2) = (apply(r1, t1, p1), apply(r2, t2, p2));
    let gap = dist3(&w1, &w2);
    assert!(
        (gap - dist).abs() <= eps.max(1e-300) * 4.0 + dist * 1e-9,
        "closest points {gap} apart, distance {dist}"
    );
}

// ---------------------------------------------------------------------------------------------
// Convex models.

/// A convex model's faces, fan-triangulated, as triangles in its frame.
unsafe fn hull_triangles(m: *const pqp_convex_model) -> Vec<Tri> {
    let nf = pqp_convex_model_num_faces(m);
    let mut out = Vec::new();
    for f in 0..nf {
        let k = pqp_convex_model_face_num_vertices(m, f);
        assert!(k >= 3, "face {f} has {k} vertices");
        let mut idx = vec![0 as c_int; k as usize];
        assert_code(
            "convex_model_face",
            pqp_convex_model_face(m, f, idx.as_mut_ptr()),
            &[PQP_OK],
        );
        let mut v = Vec::new();
        for &i in &idx {
            let mut p = [0.0; 3];
            assert_code(
                "convex_model_vertex",
                pqp_convex_model_vertex(m, i, p.as_mut_ptr()),
                &[PQP_OK],
            );
            v.push(p);
        }
        for q in 1..v.len() - 1 {
            out.push([v[0], v[q], v[q + 1]].concat().try_into().unwrap());
        }
    }
    out
}

/// Checks a convex model's accessors: counts, Euler's formula, indices in range.
unsafe fn check_convex_model(m: *const pqp_convex_model) {
    let (v, e, f) = (
        pqp_convex_model_num_vertices(m),
        pqp_convex_model_num_edges(m),
        pqp_convex_model_num_faces(m),
    );
    assert!(
        v >= 4 && f >= 4 && e >= 6,
        "convex model with {v} vertices, {e} edges, {f} faces"
    );
    assert_eq!(v - e + f, 2, "Euler's formula");
    for i in 0..e {
        let (mut a, mut b) = (-1, -1);
        assert_code(
            "convex_model_edge",
            pqp_convex_model_edge(m, i, &mut a, &mut b),
            &[PQP_OK],
        );
        assert!(
            (0..v).contains(&a) && (0..v).contains(&b) && a != b,
            "edge {i}: {a}-{b}"
        );
    }
    let mut p = [0.0; 3];
    assert_code(
        "vertex out of range",
        pqp_convex_model_vertex(m, v, p.as_mut_ptr()),
        &[PQP_ERR_INVALID_ARGUMENT],
    );
    assert_code(
        "vertex -1",
        pqp_convex_model_vertex(m, -1, p.as_mut_ptr()),
        &[PQP_ERR_INVALID_ARGUMENT],
    );
}

/// Convex models and their queries (see the crate documentation).
pub fn convex(data: &[u8]) {
    let mut input = Bytes::new(data);
    let mut models: Vec<*mut pqp_convex_model> = Vec::new();
    unsafe {
        for _ in 0..2 {
            let sel = input.u8();
            let mut out: *mut pqp_convex_model = null_mut();
            if sel % 4 != 3 {
                // From points (hostile ones now and then).
                let n = (input.u8() % 16) as usize;
                let hostile = sel % 8 == 1;
                let pts: Vec<f64> = (0..3 * n)
                    .map(|_| {
                        if hostile {
                            input.hostile()
                        } else {
                            input.coord()
                        }
                    })
                    .collect();
                let rc = pqp_convex_model_from_points(&mut out, pts.as_ptr(), n as c_int);
                if !pts.iter().all(|&x| acceptable(x)) {
                    assert_code("from_points (bad)", rc, &[PQP_ERR_NONFINITE_COORDINATE]);
                } else if n < 4 {
                    assert_code("from_points (< 4)", rc, &[PQP_ERR_DEGENERATE_POINTS]);
                } else {
                    assert_code("from_points", rc, &[PQP_OK, PQP_ERR_DEGENERATE_POINTS]);
                }
            } else {
                // From triangles: a hull's own faces (valid), perhaps broken by one change.
                let n = 4 + (input.u8() % 8) as usize;
                let pts: Vec<f64> = (0..3 * n).map(|_| input.coord()).collect();
                let mut hull = null_mut();
                if pqp_convex_model_from_points(&mut hull, pts.as_ptr(), n as c_int) != PQP_OK {
                    continue;
                }
                let nv = pqp_convex_model_num_vertices(hull);
                let mut xyz = vec![0.0; 3 * nv as usize];
                for i in 0..nv {
                    pqp_convex_model_vertex(hull, i, xyz[3 * i as usize..].as_mut_ptr());
                }
                // Fan triangles of the faces, as vertex indices.
                let mut idx: Vec<c_int> = Vec::new();
                for f in 0..pqp_convex_model_num_faces(hull) {
                    let k = pqp_convex_model_face_num_vertices(hull, f);
                    let mut fv = vec![0 as c_int; k as usize];
                    pqp_convex_model_face(hull, f, fv.as_mut_ptr());
                    for q in 1..fv.len() - 1 {
                        idx.extend([fv[0], fv[q], fv[q + 1]]);
                    }
                }
                pqp_convex_model_destroy(hull);
                let broken = input.u8();
                let mut expect: &[c_int] = &[PQP_OK];
                match broken % 4 {
                    0 => {
                        let k = input.u8() as usize % idx.len();
                        idx[k] = input.int();
                        expect = if (0..nv).contains(&idx[k]) {
                            &[PQP_OK, PQP_ERR_INVALID_CONVEX_MESH]
                        } else {
                            &[PQP_ERR_INVALID_ARGUMENT]
                        };
                    }
                    1 => {
                        idx.swap(0, 1);
                        expect = &[PQP_ERR_INVALID_CONVEX_MESH];
                    }
                    2 => {
                        let k = input.u8() as usize % xyz.len();
                        xyz[k] = input.hostile();
                        expect = if acceptable(xyz[k]) {
                            &[PQP_OK, PQP_ERR_INVALID_CONVEX_MESH]
                        } else {
                            &[PQP_ERR_NONFINITE_COORDINATE]
                        };
                    }
                    _ => {}
                }
                let rc = pqp_convex_model_from_triangles(
                    &mut out,
                    xyz.as_ptr(),
                    nv,
                    idx.as_ptr(),
                    (idx.len() / 3) as c_int,
                );
                assert_code("from_triangles", rc, expect);
            }
            if !out.is_null() {
                check_convex_model(out);
                models.push(out);
            }
        }
        if models.is_empty() {
            return;
        }
        let (a, b) = (models[0], models[models.len() - 1]);
        let cache = pqp_convex_cache_create();
        let res = pqp_convex_result_create();
        let ta = hull_triangles(a);
        let tb = hull_triangles(b);
        let ma = build(&ta, 0, PQP_BV_RSS, PQP_COLLIDE_OBB);
        let mb = build(&tb, 0, PQP_BV_RSS, PQP_COLLIDE_OBB);
        let dres = pqp_distance_result_create();
        for _ in 0..3 {
            let (r1, t1) = input.pose();
            let (r2, t2) = input.pose();
            let pose_ok = r1
                .iter()
                .chain(&t1)
                .chain(&r2)
                .chain(&t2)
                .all(|&x| acceptable(x));
            let c = if input.u8() % 3 == 0 {
                null_mut()
            } else {
                cache
            };
            let (r1p, t1p, r2p, t2p) = (r1.as_ptr(), t1.as_ptr(), r2.as_ptr(), t2.as_ptr());
            let rc = pqp_convex_distance(res, r1p, t1p, a, r2p, t2p, b, c);
            let mut hit: c_int = -1;
            let rci = pqp_convex_intersect(&mut hit, r1p, t1p, a, r2p, t2p, b, c);
            if !pose_ok {
                assert_code("convex_distance (bad pose)", rc, &[PQP_ERR_NONFINITE_POSE]);
                assert_code(
                    "convex_intersect (bad pose)",
                    rci,
                    &[PQP_ERR_NONFINITE_POSE],
                );
                continue;
            }
            assert_code("convex_distance", rc, &[PQP_OK]);
            assert_code("convex_intersect", rci, &[PQP_OK]);
            let d = pqp_convex_result_distance(res);
            let inter = pqp_convex_result_intersecting(res) != 0;
            assert!(d >= 0.0, "convex distance {d}");
            assert_eq!(
                d == 0.0,
                inter,
                "convex distance {d} vs intersecting {inter}"
            );
            assert_eq!(hit != 0, inter, "convex_intersect vs convex_distance");
            // Against the triangle meshes of the two hulls.
            let wa: Vec<Tri> = ta.iter().map(|t| world(&r1, &t1, t)).collect();
            let wb: Vec<Tri> = tb.iter().map(|t| world(&r2, &t2, t)).collect();
            let scale = wa
                .iter()
                .chain(&wb)
                .flatten()
                .fold(0.0f64, |m, x| m.max(x.abs()));
            let eps = 1e-9 * scale;
            assert_code(
                "distance (hull meshes)",
                pqp_distance(dres, r1p, t1p, ma, r2p, t2p, mb, 0.0, 0.0, 2),
                &[PQP_OK],
            );
            let md = pqp_distance_result_distance(dres);
            if d > eps {
                assert!(
                    (md - d).abs() <= eps,
                    "convex distance {d}, hull meshes {md}"
                );
            }
            if md > eps {
                assert!(!inter || d == 0.0, "meshes apart yet intersecting");
            }
            if md == 0.0 {
                assert!(d <= eps, "hull meshes touch, convex distance {d}");
            }
            let p1 = std::slice::from_raw_parts(pqp_convex_result_p1(res), 3);
            let p2 = std::slice::from_raw_parts(pqp_convex_result_p2(res), 3);
            let gap = dist3(&apply(&r1, &t1, p1), &apply(&r2, &t2, p2));
            assert!(
                (gap - d).abs() <= 4.0 * eps + 1e-300,
                "convex closest points {gap} apart, distance {d}"
            );
            // Penetration.
            let rc = pqp_convex_penetration(res, r1p, t1p, a, r2p, t2p, b, c);
            assert_code("convex_penetration", rc, &[PQP_OK]);
            let depth = pqp_convex_result_depth(res);
            assert!(depth.is_finite() && depth >= 0.0, "depth {depth}");
            if !inter {
                assert_eq!(depth, 0.0, "apart, depth {depth}");
            }
            let n = std::slice::from_raw_parts(pqp_convex_result_normal(res), 3);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!(
                (len - 1.0).abs() < 1e-6 || (d == 0.0 && depth == 0.0),
                "normal of length {len}"
            );
        }
        pqp_distance_result_destroy(dres);
        pqp_model_destroy(ma);
        pqp_model_destroy(mb);
        pqp_convex_result_destroy(res);
        pqp_convex_cache_destroy(cache);
        for m in models {
            pqp_convex_model_destroy(m);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Saved models.

/// Fletcher-64 of the saved-model layout (docs/saved-model-format.md, version 1), from its
/// definition.
fn fletcher64(bytes: &[u8]) -> u64 {
    let m = 0xffff_ffffu64;
    let (mut a, mut b) = (0u64, 0u64);
    for w in bytes.chunks(4) {
        let mut x = [0u8; 4];
        x[..w.len()].copy_from_slice(w);
        a = (a + u32::from_le_bytes(x) as u64) % m;
        b = (b + a) % m;
    }
    (b << 32) | a
}

/// CRC-32C of the saved-model layout (version 2), from its definition, a bit at a time.
fn crc32c(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 == 1 {
                (c >> 1) ^ 0x82f6_3b78
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// The version word of saved bytes (0 if too short).
fn version_of(bytes: &[u8]) -> u32 {
    bytes
        .get(8..12)
        .map_or(0, |w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
}

/// A model's saved bytes (it must be built).
unsafe fn saved_bytes(m: *const pqp_model) -> Vec<u8> {
    let mut size = 0usize;
    assert_code(
        "pqp_model_serialize (size)",
        pqp_model_serialize(m, null_mut(), 0, &mut size),
        &[PQP_ERR_BUFFER_TOO_SMALL],
    );
    let mut buf = vec![0u8; size];
    let mut written = 0usize;
    assert_code(
        "pqp_model_serialize",
        pqp_model_serialize(m, buf.as_mut_ptr().cast(), size, &mut written),
        &[PQP_OK],
    );
    assert_eq!(written, size);
    buf
}

/// Bytes as a saved model. The first byte chooses: bit 0, recompute the checksum (the last 8
/// bytes: Fletcher-64 if the version word is 1, else CRC-32C) so that the checks of the contents
/// are reached; the rest are the bytes.
pub fn deserialize(data: &[u8]) {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let mut bytes = rest.to_vec();
    if mode & 1 == 1 && bytes.len() >= 8 {
        let body = bytes.len() - 8;
        let sum = if version_of(&bytes) == 1 {
            fletcher64(&bytes[..body])
        } else {
            u64::from(crc32c(&bytes[..body]))
        };
        bytes[body..].copy_from_slice(&sum.to_le_bytes());
    }
    unsafe {
        // A built model to load into: on failure it must stay as it was.
        let other = pqp_model_create();
        let (p, q, r) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.5]);
        assert_eq!(
            pqp_model_add_tri(other, p.as_ptr(), q.as_ptr(), r.as_ptr(), 9),
            PQP_OK
        );
        assert_eq!(
            pqp_model_add_tri(other, q.as_ptr(), r.as_ptr(), p.as_ptr(), 8),
            PQP_OK
        );
        assert_eq!(pqp_model_end(other), PQP_OK);
        let other_bytes = saved_bytes(other);

        let fresh = pqp_model_create();
        let rc = pqp_model_deserialize(fresh, bytes.as_ptr().cast(), bytes.len());
        assert_code(
            "pqp_model_deserialize",
            rc,
            &[PQP_OK, PQP_ERR_INVALID_DATA, PQP_ERR_MODEL_OUT_OF_MEMORY],
        );
        let into_built = pqp_model_deserialize(other, bytes.as_ptr().cast(), bytes.len());
        assert_eq!(into_built, rc, "the same bytes, another answer");
        if rc != PQP_OK {
            assert_eq!(pqp_model_build_state(fresh), PQP_BUILD_STATE_EMPTY);
            assert!(
                saved_bytes(other) == other_bytes,
                "a failed load changed the model"
            );
        } else {
            // Loaded: exactly what it saves (version 2; a version 1 buffer but for its version
            // word and checksum), and every query and view runs on it.
            let mut want = bytes.clone();
            if version_of(&bytes) == 1 {
                want[8..12].copy_from_slice(&2u32.to_le_bytes());
                let body = want.len() - 8;
                let sum = u64::from(crc32c(&want[..body]));
                want[body..].copy_from_slice(&sum.to_le_bytes());
            }
            assert!(
                saved_bytes(fresh) == want,
                "a loaded model saves other bytes"
            );
            assert!(
                saved_bytes(other) == want,
                "a loaded model saves other bytes"
            );
            let n = pqp_model_num_tris(fresh);
            assert!(n >= 1);
            let (mut bvs, mut nb) = (null(), 0);
            assert_code(
                "pqp_model_bvs",
                pqp_model_bvs(fresh, &mut bvs, &mut nb),
                &[PQP_OK],
            );
            assert_eq!(nb, 2 * n - 1);
            let (mut tris, mut nt) = (null(), 0);
            assert_code(
                "pqp_model_tris",
                pqp_model_tris(fresh, &mut tris, &mut nt),
                &[PQP_OK],
            );
            assert_eq!(nt, n);
            let id = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
            let t = [0.25, -0.5, 0.125];
            let z = [0.0; 3];
            let c = pqp_collide_result_create();
            let d = pqp_distance_result_create();
            let tol = pqp_tolerance_result_create();
            for (a, b) in [(fresh, other), (other, fresh), (fresh, fresh)] {
                for flag in [PQP_ALL_CONTACTS, PQP_FIRST_CONTACT] {
                    let rc = pqp_collide(
                        c,
                        id.as_ptr(),
                        z.as_ptr(),
                        a,
                        id.as_ptr(),
                        t.as_ptr(),
                        b,
                        flag,
                    );
                    assert_code("pqp_collide", rc, &[PQP_OK]);
                }
                for (rel, abs) in [(0.0, 0.0), (0.5, 0.1)] {
                    let rc = pqp_distance(
                        d,
                        id.as_ptr(),
                        z.as_ptr(),
                        a,
                        id.as_ptr(),
                        t.as_ptr(),
                        b,
                        rel,
                        abs,
                        2,
                    );
                    assert_code("pqp_distance", rc, &[PQP_OK]);
                    assert!(pqp_distance_result_distance(d) >= 0.0);
                }
                let rc = pqp_tolerance(
                    tol,
                    id.as_ptr(),
                    z.as_ptr(),
                    a,
                    id.as_ptr(),
                    t.as_ptr(),
                    b,
                    0.1,
                    2,
                );
                assert_code("pqp_tolerance", rc, &[PQP_OK]);
            }
            pqp_tolerance_result_destroy(tol);
            pqp_distance_result_destroy(d);
            pqp_collide_result_destroy(c);
        }
        pqp_model_destroy(fresh);
        pqp_model_destroy(other);
    }
}

// ---------------------------------------------------------------------------------------------
// The queries PQP never had: points, rays, pairs within a distance, self-collision, refit and
// time of contact.

fn sub3(a: &[f64], b: &[f64]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross3(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v` over its largest magnitude (no overflow or underflow at any scale), or None for zero.
fn rescaled(v: [f64; 3]) -> Option<[f64; 3]> {
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    (m > 0.0).then(|| [v[0] / m, v[1] / m, v[2] / m])
}

fn unit3(v: [f64; 3]) -> Option<[f64; 3]> {
    let v = rescaled(v)?;
    let n = dot3(&v, &v).sqrt();
    Some([v[0] / n, v[1] / n, v[2] / n])
}

/// Distance from a point to a triangle, by the exact triangle distance with the point as a
/// degenerate triangle.
fn point_tri_distance(p: &[f64; 3], t: &Tri) -> f64 {
    tri_distance(&[p[0], p[1], p[2], p[0], p[1], p[2], p[0], p[1], p[2]], t)
}

/// The generalized winding number of `tris` about `p`: the solid angles (Van Oosterom and
/// Strackee's formula on unit vectors, so any scale works) summed plainly over 4 pi; None when
/// `p` is a vertex.
fn brute_winding(tris: &[Tri], p: &[f64; 3]) -> Option<f64> {
    let mut sum = 0.0;
    for t in tris {
        let a = unit3(sub3(&t[0..3], p))?;
        let b = unit3(sub3(&t[3..6], p))?;
        let c = unit3(sub3(&t[6..9], p))?;
        let det = dot3(&a, &cross3(&b, &c));
        let den = 1.0 + dot3(&a, &b) + dot3(&b, &c) + dot3(&c, &a);
        sum += 2.0 * det.atan2(den);
    }
    Some(sum / (4.0 * std::f64::consts::PI))
}

/// The ray parameter where `o + t d` crosses triangle `t` well inside it (every barycentric
/// coordinate above 1e-6, the ray at more than about 1e-3 radians to its plane), by Moller and Trumbore's
/// plain formula; None for a crossing near an edge, a grazing ray or no crossing.
fn robust_crossing(o: &[f64; 3], d: &[f64; 3], t: &Tri) -> Option<f64> {
    // Everything is rescaled by the triangle's extent so that no product overflows.
    let e1 = sub3(&t[3..6], &t[0..3]);
    let e2 = sub3(&t[6..9], &t[0..3]);
    let s = e1.iter().chain(&e2).fold(0.0f64, |m, x| m.max(x.abs()));
    if s == 0.0 {
        return None;
    }
    let (e1, e2) = (
        [e1[0] / s, e1[1] / s, e1[2] / s],
        [e2[0] / s, e2[1] / s, e2[2] / s],
    );
    let du = unit3(*d)?;
    let w = sub3(o, &t[0..3]);
    let w = [w[0] / s, w[1] / s, w[2] / s];
    let p = cross3(&du, &e2);
    let det = dot3(&e1, &p);
    let area = dot3(&cross3(&e1, &e2), &cross3(&e1, &e2)).sqrt();
    if det.abs() <= 1e-3 * area || det.is_nan() || !w.iter().all(|x| x.is_finite()) {
        return None;
    }
    let u = dot3(&w, &p) / det;
    let q = cross3(&w, &e1);
    let v = dot3(&du, &q) / det;
    let along = dot3(&e2, &q) / det; // distance along the unit direction, over s
    if u > 1e-6 && v > 1e-6 && 1.0 - u - v > 1e-6 && along.is_finite() {
        let dn = dot3(d, d).sqrt();
        Some(along * s / dn)
    } else {
        None
    }
}

/// A rotation matrix's unit quaternion (w, x, y, z), by the largest of its four candidates.
fn quaternion(r: &[f64; 9]) -> [f64; 4] {
    let tr = r[0] + r[4] + r[8];
    let q = if tr > r[0].max(r[4]).max(r[8]) {
        let s = (1.0 + tr).sqrt() * 2.0;
        [
            s / 4.0,
            (r[7] - r[5]) / s,
            (r[2] - r[6]) / s,
            (r[3] - r[1]) / s,
        ]
    } else if r[0] >= r[4] && r[0] >= r[8] {
        let s = (1.0 + r[0] - r[4] - r[8]).sqrt() * 2.0;
        [
            (r[7] - r[5]) / s,
            s / 4.0,
            (r[1] + r[3]) / s,
            (r[2] + r[6]) / s,
        ]
    } else if r[4] >= r[8] {
        let s = (1.0 + r[4] - r[0] - r[8]).sqrt() * 2.0;
        [
            (r[2] - r[6]) / s,
            (r[1] + r[3]) / s,
            s / 4.0,
            (r[5] + r[7]) / s,
        ]
    } else {
        let s = (1.0 + r[8] - r[0] - r[4]).sqrt() * 2.0;
        [
            (r[3] - r[1]) / s,
            (r[2] + r[6]) / s,
            (r[5] + r[7]) / s,
            s / 4.0,
        ]
    };
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    [q[0] / n, q[1] / n, q[2] / n, q[3] / n]
}

fn qmul(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

fn rotation_of(q: &[f64; 4]) -> [f64; 9] {
    let [w, x, y, z] = *q;
    [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - z * w),
        2.0 * (x * z + y * w),
        2.0 * (x * y + z * w),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - x * w),
        2.0 * (x * z - y * w),
        2.0 * (y * z + x * w),
        1.0 - 2.0 * (x * x + y * y),
    ]
}

/// The header's motion, independently: R(t) = Ra exp(t log(Ra^T Rb)) the shorter way (a
/// quaternion slerp from the identity to Ra^T Rb), T(t) linear. None for a relative turn within
/// 1e-6 of pi, which the header lets go either way.
struct Motion {
    qa: [f64; 4],
    axis: [f64; 3],
    angle: f64,
    ta: [f64; 3],
    tb: [f64; 3],
}

impl Motion {
    fn new(ra: &[f64; 9], ta: [f64; 3], rb: &[f64; 9], tb: [f64; 3]) -> Option<Motion> {
        let qa = quaternion(ra);
        let qb = quaternion(rb);
        let mut rel = qmul(&[qa[0], -qa[1], -qa[2], -qa[3]], &qb);
        if rel[0] < 0.0 {
            rel = rel.map(|x| -x);
        }
        if rel[0] < 1e-6 {
            return None;
        }
        let s = (rel[1] * rel[1] + rel[2] * rel[2] + rel[3] * rel[3]).sqrt();
        let angle = 2.0 * s.atan2(rel[0]);
        let axis = if s > 0.0 {
            [rel[1] / s, rel[2] / s, rel[3] / s]
        } else {
            [1.0, 0.0, 0.0]
        };
        Some(Motion {
            qa,
            axis,
            angle,
            ta,
            tb,
        })
    }

    fn at(&self, t: f64) -> ([f64; 9], [f64; 3]) {
        let h = 0.5 * self.angle * t;
        let step = [
            h.cos(),
            self.axis[0] * h.sin(),
            self.axis[1] * h.sin(),
            self.axis[2] * h.sin(),
        ];
        let r = rotation_of(&qmul(&self.qa, &step));
        let tr = [0, 1, 2].map(|i| self.ta[i] + t * (self.tb[i] - self.ta[i]));
        (r, tr)
    }
}

/// The exact distance of two posed models (fresh result each time).
unsafe fn model_distance(
    p1: &([f64; 9], [f64; 3]),
    m1: *const pqp_model,
    p2: &([f64; 9], [f64; 3]),
    m2: *const pqp_model,
) -> f64 {
    let d = pqp_distance_result_create();
    let rc = pqp_distance(
        d,
        p1.0.as_ptr(),
        p1.1.as_ptr(),
        m1,
        p2.0.as_ptr(),
        p2.1.as_ptr(),
        m2,
        0.0,
        0.0,
        2,
    );
    assert_code("distance", rc, &[PQP_OK]);
    let v = pqp_distance_result_distance(d);
    pqp_distance_result_destroy(d);
    v
}

/// The pairs of a collision result, as indices from the given first ids.
unsafe fn pairs_of(c: *const pqp_collide_result, id1: c_int, id2: c_int) -> Vec<(usize, usize)> {
    let n = pqp_collide_result_num_pairs(c);
    (0..n)
        .map(|k| {
            (
                (pqp_collide_result_id1(c, k) - id1) as usize,
                (pqp_collide_result_id2(c, k) - id2) as usize,
            )
        })
        .collect()
}

/// Every query PQP 1.3 lacks, on small models at random poses, against brute force (see the
/// crate documentation).
pub fn more_queries(data: &[u8]) {
    let mut input = Bytes::new(data);
    let n1 = 1 + (input.u8() % 6) as usize;
    let n2 = 1 + (input.u8() % 6) as usize;
    // Vertices from a small pool, so that triangles share vertices and edges (self-collision's
    // exclusion) and closed fans occur. The pool has one scale (mostly 1, as `coord` scales), so
    // that most inputs stay on the predicates' fast path; vertices outside it mix scales.
    let pool_scale = [1.0, 1.0, 1.0, 1.0, 1.0, 1e-140, 1e140, 1e-6][(input.u8() % 8) as usize];
    let pool: Vec<[f64; 3]> = (0..6)
        .map(|_| [input.grid(), input.grid(), input.grid()].map(|x| x * pool_scale))
        .collect();
    let tri = |input: &mut Bytes| -> Tri {
        let mut t = [0.0; 9];
        for k in 0..3 {
            let sel = input.u8();
            let v = if sel < 192 {
                pool[(sel % 6) as usize]
            } else {
                [input.coord(), input.coord(), input.coord()]
            };
            t[3 * k..3 * k + 3].copy_from_slice(&v);
        }
        t
    };
    let a: Vec<Tri> = (0..n1).map(|_| tri(&mut input)).collect();
    let b: Vec<Tri> = (0..n2).map(|_| tri(&mut input)).collect();
    let (va, ca) = ((input.u8() % 4) as c_int, (input.u8() % 2) as c_int);
    let (vb, cb) = ((input.u8() % 4) as c_int, (input.u8() % 2) as c_int);
    let r1 = input.rotation();
    let t1 = [input.grid(), input.grid(), input.grid()];
    let r2 = input.rotation();
    let t2 = [input.grid(), input.grid(), input.grid()];
    const ID1: c_int = 7;
    const ID2: c_int = -3;

    let wa: Vec<Tri> = a.iter().map(|t| world(&r1, &t1, t)).collect();
    let wb: Vec<Tri> = b.iter().map(|t| world(&r2, &t2, t)).collect();
    let scale = wa
        .iter()
        .chain(&wb)
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let eps = 1e-9 * scale.max(1e-300);
    let pair_d: Vec<Vec<f64>> = wa
        .iter()
        .map(|s| wb.iter().map(|t| tri_distance(s, t)).collect())
        .collect();

    unsafe {
        let m1 = build(&a, ID1, va, ca);
        let m2 = build(&b, ID2, vb, cb);
        let (r1p, t1p, r2p, t2p) = (r1.as_ptr(), t1.as_ptr(), r2.as_ptr(), t2.as_ptr());

        // Closest point and signed distance of a point near the scene.
        let p = [
            input.coord() + t1[0],
            input.coord() + t1[1],
            input.coord() + t1[2],
        ];
        let brute = wa
            .iter()
            .map(|t| point_tri_distance(&p, t))
            .fold(f64::INFINITY, f64::min);
        let eps_p = eps.max(1e-9 * p.iter().fold(0.0f64, |m, x| m.max(x.abs())));
        let max_d = match input.u8() % 4 {
            0 => f64::INFINITY,
            1 => brute,
            _ => input.grid().abs(),
        };
        let mut out = pqp_point_result {
            distance: -1.0,
            point: [0.0; 3],
            triangle: -2,
        };
        let rc = pqp_closest_point(&mut out, r1p, t1p, m1, p.as_ptr(), max_d);
        assert_code("closest_point", rc, &[PQP_OK]);
        if out.triangle == -1 {
            assert!(out.distance == f64::INFINITY && out.point.iter().all(|x| x.is_nan()));
            assert!(
                brute > max_d - eps_p,
                "closest point: nothing within {max_d}, brute force {brute}"
            );
        } else {
            let i = (out.triangle - ID1) as usize;
            assert!(
                i < n1,
                "closest point: triangle id {} out of range",
                out.triangle
            );
            assert!(
                (out.distance - brute).abs() <= eps_p,
                "closest point: {} vs brute force {brute}",
                out.distance
            );
            assert!(out.distance <= max_d, "closest point beyond max_distance");
            assert!(
                (dist3(&out.point, &p) - out.distance).abs() <= eps_p,
                "closest point: point not that far"
            );
            assert!(
                point_tri_distance(&out.point, &wa[i]) <= eps_p,
                "closest point: not on its triangle"
            );
        }
        let mut sd = f64::NAN;
        let rc = pqp_signed_distance(&mut sd, r1p, t1p, m1, p.as_ptr());
        assert_code("signed_distance", rc, &[PQP_OK]);
        assert!(
            (sd.abs() - brute).abs() <= eps_p,
            "signed distance {sd} vs brute force {brute}"
        );
        if let (true, Some(w)) = (brute > eps_p, brute_winding(&wa, &p)) {
            if w.abs() >= 0.5 + 1e-4 {
                assert!(
                    sd < 0.0,
                    "winding number {w}: inside, but signed distance {sd}"
                );
            } else if w.abs() <= 0.5 - 1e-4 {
                assert!(
                    sd > 0.0,
                    "winding number {w}: outside, but signed distance {sd}"
                );
            }
        }

        // Rays: the nearest hit against the triangles crossed well inside, and the batch form.
        let mut origins = [0.0; 9];
        let mut dirs = [0.0; 9];
        for k in 0..3 {
            for j in 0..3 {
                origins[3 * k + j] = input.coord() + t1[j];
                dirs[3 * k + j] = input.grid();
            }
            if dirs[3 * k..3 * k + 3].iter().all(|&x| x == 0.0) {
                dirs[3 * k + 2] = 1.0;
            }
        }
        let max_t = match input.u8() % 4 {
            0 => f64::INFINITY,
            1 => 0.0,
            _ => input.grid().abs() * 4.0,
        };
        let no_hit = pqp_ray_hit {
            t: -1.0,
            point: [0.0; 3],
            normal: [0.0; 3],
            triangle: -2,
        };
        let mut singles = [no_hit; 3];
        for k in 0..3 {
            let (o, d) = (&origins[3 * k..3 * k + 3], &dirs[3 * k..3 * k + 3]);
            let rc = pqp_ray_cast(&mut singles[k], r1p, t1p, m1, o.as_ptr(), d.as_ptr(), max_t);
            assert_code("ray_cast", rc, &[PQP_OK]);
            let h = singles[k];
            let (o, d) = ([o[0], o[1], o[2]], [d[0], d[1], d[2]]);
            let dn = dot3(&d, &d).sqrt();
            let nearest = wa
                .iter()
                .filter_map(|t| robust_crossing(&o, &d, t))
                .filter(|&t| t >= 0.0 && t <= max_t)
                .fold(f64::INFINITY, f64::min);
            // Rounding, and the crossings' error along the ray (up to 1e3 times that at the
            // angles robust_crossing keeps).
            let reach = dot3(&o, &o).sqrt() + if h.t.is_finite() { h.t * dn } else { 0.0 };
            let slack = 1e3 * eps.max(1e-9 * reach);
            if h.triangle == -1 {
                assert!(h.t == f64::INFINITY);
                assert!(
                    nearest == f64::INFINITY || nearest * dn > max_t * dn - slack,
                    "ray {k}: no hit, but a triangle is crossed at t = {nearest}"
                );
            } else {
                let i = (h.triangle - ID1) as usize;
                assert!(i < n1, "ray {k}: triangle id out of range");
                assert!(
                    h.t >= 0.0 && h.t <= max_t,
                    "ray {k}: t = {} outside [0, {max_t}]",
                    h.t
                );
                assert!(
                    h.t * dn <= nearest * dn + slack,
                    "ray {k}: hit at {} after a crossing at {nearest}",
                    h.t
                );
                let at = [0, 1, 2].map(|j| o[j] + h.t * d[j]);
                assert!(
                    dist3(&at, &h.point) <= slack,
                    "ray {k}: point is not origin + t direction"
                );
                // Off the triangle by the error along the ray, which grows as the ray grazes it.
                let sin = dot3(&h.normal, &unit3(d).unwrap()).abs();
                if sin > 1e-3 {
                    assert!(
                        point_tri_distance(&h.point, &wa[i]) <= slack,
                        "ray {k}: point off its triangle"
                    );
                }
                let t = &wa[i];
                if let Some(m) = unit3(cross3(&sub3(&t[3..6], &t[0..3]), &sub3(&t[6..9], &t[0..3])))
                {
                    assert!(
                        dot3(&m, &h.normal) > 1.0 - 1e-6,
                        "ray {k}: normal {:?} vs {m:?}",
                        h.normal
                    );
                }
            }
        }
        let mut batch = [no_hit; 3];
        let threads = (input.u8() % 4) as u32;
        let rc = pqp_ray_cast_batch(
            batch.as_mut_ptr(),
            3,
            r1p,
            t1p,
            m1,
            origins.as_ptr(),
            dirs.as_ptr(),
            max_t,
            threads,
        );
        assert_code("ray_cast_batch", rc, &[PQP_OK]);
        for k in 0..3 {
            assert_eq!(batch[k].triangle, singles[k].triangle, "batch ray {k}");
            assert_eq!(
                batch[k].t.to_bits(),
                singles[k].t.to_bits(),
                "batch ray {k}"
            );
        }

        // Pairs within a distance, against the brute force and (at 0) against collide.
        let c = pqp_collide_result_create();
        let rc = pqp_collide(c, r1p, t1p, m1, r2p, t2p, m2, PQP_ALL_CONTACTS);
        assert_code("collide", rc, &[PQP_OK]);
        let mut contacts = pairs_of(c, ID1, ID2);
        contacts.sort();
        let tol = match input.u8() % 4 {
            0 => 0.0,
            1 => f64::INFINITY,
            _ => input.grid().abs() * scale.max(1e-300),
        };
        let rc = pqp_within_distance(c, r1p, t1p, m1, r2p, t2p, m2, tol);
        assert_code("within_distance", rc, &[PQP_OK]);
        let mut within = pairs_of(c, ID1, ID2);
        let len = within.len();
        within.sort();
        within.dedup();
        assert_eq!(within.len(), len, "within_distance: a pair listed twice");
        if tol == 0.0 {
            assert_eq!(within, contacts, "within_distance at 0 vs collide");
        }
        for (i, row) in pair_d.iter().enumerate() {
            for (j, &d) in row.iter().enumerate() {
                let listed = within.binary_search(&(i, j)).is_ok();
                if d < tol - eps || tol == f64::INFINITY {
                    assert!(
                        listed,
                        "within_distance: pair ({i}, {j}) at {d} <= {tol} missing"
                    );
                }
                if d > tol + eps {
                    assert!(
                        !listed,
                        "within_distance: pair ({i}, {j}) at {d} > {tol} listed"
                    );
                }
            }
        }

        // Self-collision of model 1 against collide of model 1 with itself, for the pairs that
        // share no vertex (exact both ways), and the brute force for every pair.
        let rc = pqp_self_collide(c, m1, PQP_ALL_CONTACTS);
        assert_code("self_collide", rc, &[PQP_OK]);
        let selfs = pairs_of(c, ID1, ID1);
        let mut sorted = selfs.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(
            sorted.len(),
            selfs.len(),
            "self_collide: a pair reported twice"
        );
        let id = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let zero = [0.0; 3];
        let rc = pqp_collide(
            c,
            id.as_ptr(),
            zero.as_ptr(),
            m1,
            id.as_ptr(),
            zero.as_ptr(),
            m1,
            PQP_ALL_CONTACTS,
        );
        assert_code("collide with itself", rc, &[PQP_OK]);
        let itself = pairs_of(c, ID1, ID1);
        let vertex = |t: &Tri, k: usize| [t[3 * k], t[3 * k + 1], t[3 * k + 2]];
        for i in 0..n1 {
            for j in i + 1..n1 {
                let reported = sorted.binary_search(&(i, j)).is_ok();
                let shares = (0..3).any(|k| (0..3).any(|l| vertex(&a[i], k) == vertex(&a[j], l)));
                if !shares {
                    assert_eq!(
                        reported,
                        itself.contains(&(i, j)),
                        "self_collide vs collide, pair ({i}, {j})"
                    );
                }
                if reported {
                    assert!(
                        tri_distance(&a[i], &a[j]) == 0.0,
                        "self_collide: ({i}, {j}) apart"
                    );
                }
            }
        }
        assert!(
            selfs.iter().all(|&(i, j)| i < j),
            "self_collide: id1 not the earlier triangle"
        );
        let rc = pqp_self_collide(c, m1, PQP_FIRST_CONTACT);
        assert_code("self_collide first", rc, &[PQP_OK]);
        assert_eq!(
            pqp_collide_result_num_pairs(c) > 0,
            !selfs.is_empty(),
            "self_collide first vs all"
        );

        // Refit model 1 to moved triangles: the same answers as a model built on them; a wrong
        // count or a bad coordinate changes nothing.
        let moved: Vec<Tri> = a
            .iter()
            .map(|t| {
                let mut t = *t;
                for x in t.iter_mut() {
                    if input.u8() % 3 == 0 {
                        *x += input.grid();
                    }
                }
                t
            })
            .collect();
        let flat: Vec<f64> = moved.iter().flatten().copied().collect();
        let before = model_distance(&(r1, t1), m1, &(r2, t2), m2);
        let rc = pqp_model_refit(m1, flat.as_ptr(), n1 + 1);
        assert_code("refit (wrong count)", rc, &[PQP_ERR_INVALID_ARGUMENT]);
        let mut bad = flat.clone();
        let k = input.u8() as usize % bad.len();
        bad[k] = f64::NAN;
        let rc = pqp_model_refit(m1, bad.as_ptr(), n1);
        assert_code("refit (NaN)", rc, &[PQP_ERR_NONFINITE_COORDINATE]);
        assert_eq!(
            model_distance(&(r1, t1), m1, &(r2, t2), m2).to_bits(),
            before.to_bits(),
            "failed refit changed the model"
        );
        let rc = pqp_model_refit(m1, flat.as_ptr(), n1);
        assert_code("refit", rc, &[PQP_OK]);
        let fresh = build(&moved, ID1, va, ca);
        let moved_scale = moved
            .iter()
            .map(|t| world(&r1, &t1, t))
            .chain(wb.iter().copied())
            .flatten();
        let meps = 1e-9 * moved_scale.fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
        let refit_d = model_distance(&(r1, t1), m1, &(r2, t2), m2);
        let fresh_d = model_distance(&(r1, t1), fresh, &(r2, t2), m2);
        assert!(
            (refit_d - fresh_d).abs() <= meps,
            "refit: distance {refit_d} vs rebuilt {fresh_d}"
        );
        let rc = pqp_collide(c, r1p, t1p, m1, r2p, t2p, m2, PQP_ALL_CONTACTS);
        assert_code("collide after refit", rc, &[PQP_OK]);
        let mut after = pairs_of(c, ID1, ID2);
        let rc = pqp_collide(c, r1p, t1p, fresh, r2p, t2p, m2, PQP_ALL_CONTACTS);
        assert_code("collide rebuilt", rc, &[PQP_OK]);
        let mut rebuilt = pairs_of(c, ID1, ID2);
        after.sort();
        rebuilt.sort();
        assert_eq!(after, rebuilt, "refit: pairs differ from a rebuilt model's");
        pqp_model_destroy(fresh);
        pqp_collide_result_destroy(c);

        // Time of contact: model 1 (refit) and model 2 each move to a second pose.
        let r1b = input.rotation();
        let t1b = [input.grid(), input.grid(), input.grid()];
        let r2b = input.rotation();
        let t2b = [input.grid(), input.grid(), input.grid()];
        let wm: Vec<Tri> = moved.iter().map(|t| world(&r1, &t1, t)).collect();
        let span = wm
            .iter()
            .chain(&wb)
            .flatten()
            .chain(&t1b)
            .chain(&t2b)
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let span = span.max(
            moved
                .iter()
                .chain(&b)
                .flatten()
                .fold(0.0f64, |m, x| m.max(x.abs())),
        );
        let ceps = 1e-8 * span.max(1e-300);
        let tol = span.max(1e-300) * (1 + input.u8() % 64) as f64 / 64.0;
        let blank = pqp_contact_time {
            contact: 7,
            toc: -1.0,
            id1: 0,
            id2: 0,
            point1: [0.0; 3],
            point2: [0.0; 3],
        };
        let mut ct = blank;
        let toc = |ct: &mut pqp_contact_time, tol: f64| {
            pqp_time_of_contact(
                ct,
                r1p,
                t1p,
                r1b.as_ptr(),
                t1b.as_ptr(),
                m1,
                r2p,
                t2p,
                r2b.as_ptr(),
                t2b.as_ptr(),
                m2,
                tol,
            )
        };
        for bad_tol in [0.0, -tol, f64::NAN] {
            let rc = toc(&mut ct, bad_tol);
            assert_code(
                "time_of_contact (bad tolerance)",
                rc,
                &[PQP_ERR_INVALID_ARGUMENT],
            );
            assert_eq!(ct.contact, 7, "time_of_contact wrote on an error");
        }
        let rc = toc(&mut ct, tol);
        assert_code("time_of_contact", rc, &[PQP_OK]);
        let motions = (
            Motion::new(&r1, t1, &r1b, t1b),
            Motion::new(&r2, t2, &r2b, t2b),
        );
        let d0 = model_distance(&(r1, t1), m1, &(r2, t2), m2);
        if d0 < tol - ceps {
            assert!(
                ct.contact == 1 && ct.toc == 0.0,
                "within tolerance at t = 0, toc {}",
                ct.toc
            );
        }
        if ct.contact == 1 {
            assert!(
                (0.0..=1.0).contains(&ct.toc),
                "toc {} outside [0, 1]",
                ct.toc
            );
            assert!(
                dist3(&ct.point1, &ct.point2) <= tol + ceps,
                "toc: closest points farther than tolerance"
            );
        } else {
            assert!(ct.contact == 0 && ct.toc == f64::INFINITY && ct.id1 == -1 && ct.id2 == -1);
        }
        if let (Some(ma), Some(mb)) = motions {
            let end = if ct.contact == 1 { ct.toc } else { 1.0 };
            if ct.contact == 1 {
                let d = model_distance(&ma.at(end), m1, &mb.at(end), m2);
                assert!(
                    d <= tol + ceps,
                    "distance {d} at toc {end} above tolerance {tol}"
                );
            }
            for k in 0..=16 {
                let t = end * k as f64 / 16.0;
                if ct.contact == 1 && t >= end {
                    break;
                }
                let d = model_distance(&ma.at(t), m1, &mb.at(t), m2);
                let floor = if ct.contact == 1 { 0.999 * tol } else { tol };
                assert!(
                    d > floor - ceps,
                    "distance {d} at t = {t} before toc {} (tolerance {tol})",
                    ct.toc
                );
            }
        }

        pqp_model_destroy(m1);
        pqp_model_destroy(m2);
    }
}
