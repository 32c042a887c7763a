//! The parallel build (`Model::end_threads`, `pqp_model_end_threads`): the same model, byte for
//! byte (its saved form), and the same answers as the one-thread build whatever the thread count;
//! the errors of `pqp_model_end`.

use pqp::capi::*;
use pqp::{DistanceOptions, Model, Pose, distance};

/// A triangle as `Model::add_triangle` takes it: three vertices and an id.
type Triangle = ([f64; 3], [f64; 3], [f64; 3], i32);

/// A bumpy sphere of `2 * lat * lon` triangles.
fn bumpy(lat: usize, lon: usize, shift: f64) -> Vec<Triangle> {
    let point = |i: usize, j: usize| {
        let th = std::f64::consts::PI * i as f64 / lat as f64;
        let ph = 2.0 * std::f64::consts::PI * (j % lon) as f64 / lon as f64;
        let r = 1.0 + 0.1 * (5.0 * th).sin() * (7.0 * ph).cos();
        [
            r * th.sin() * ph.cos() + shift,
            r * th.sin() * ph.sin(),
            r * th.cos(),
        ]
    };
    let mut tris = Vec::new();
    for i in 0..lat {
        for j in 0..lon {
            let (a, b, c, d) = (
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            );
            let id = tris.len() as i32;
            tris.push((a, b, c, id));
            tris.push((a, c, d, id + 1));
        }
    }
    tris
}

fn built(tris: &[Triangle], threads: Option<usize>) -> Model {
    let mut m = Model::new();
    for &(a, b, c, id) in tris {
        m.add_triangle(a, b, c, id).unwrap();
    }
    match threads {
        None => m.end().unwrap(),
        Some(t) => m.end_threads(t).unwrap(),
    }
    m
}

#[test]
fn every_thread_count_builds_the_same_model() {
    let tris = bumpy(50, 120, 0.0);
    let other = built(&bumpy(20, 40, 2.05), None);
    let one = built(&tris, None);
    let saved = one.to_bytes().unwrap();
    let poses: Vec<Pose> = (0..20)
        .map(|k| Pose::from_translation([0.05 * k as f64 - 0.5, 0.1, 0.0]))
        .collect();
    let answers = |m: &Model| -> Vec<f64> {
        poses
            .iter()
            .map(|p| {
                distance(m, &Pose::identity(), &other, p, &DistanceOptions::exact())
                    .unwrap()
                    .distance
            })
            .collect()
    };
    let want = answers(&one);
    for threads in [0, 1, 2, 3, 16, 1000] {
        let m = built(&tris, Some(threads));
        assert_eq!(m.to_bytes().unwrap(), saved, "{threads} threads");
        assert_eq!(answers(&m), want, "{threads} threads");
    }
}

#[test]
fn c_end_threads_reports_as_end() {
    let tri = [0.0, 0.0, 0.0];
    let (x, y) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    // SAFETY: every pointer passed is NULL, a live handle or a local array.
    unsafe {
        assert_eq!(
            pqp_model_end_threads(std::ptr::null_mut(), 2),
            PQP_ERR_NULL_POINTER
        );
        let m = pqp_model_create();
        assert_eq!(pqp_model_end_threads(m, 0), PQP_ERR_BUILD_EMPTY_MODEL);
        assert_eq!(pqp_model_build_state(m), PQP_BUILD_STATE_EMPTY);
        assert_eq!(
            pqp_model_add_tri(m, tri.as_ptr(), x.as_ptr(), y.as_ptr(), 3),
            PQP_OK
        );
        assert_eq!(pqp_model_end_threads(m, u32::MAX), PQP_OK);
        assert_eq!(pqp_model_is_built(m), 1);
        assert_eq!(pqp_model_end_threads(m, 2), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        assert_eq!(pqp_model_is_built(m), 1);
        pqp_model_destroy(m);
    }
}
