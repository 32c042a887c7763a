//! PQP 1.3's build protocol and its return codes.

use pqp::{BuildState, Error, Model};

const A: [f64; 3] = [0.0, 0.0, 0.0];
const B: [f64; 3] = [1.0, 0.0, 0.0];
const C: [f64; 3] = [0.0, 1.0, 0.0];

#[test]
fn begin_add_end_builds_a_model() {
    let mut m = Model::new();
    assert_eq!(m.begin(8), Ok(()));
    assert_eq!(m.add_triangle(A, B, C, 3), Ok(()));
    assert_eq!(m.add_triangle(A, C, [0.0, 0.0, 1.0], 4), Ok(()));
    assert_eq!(m.num_triangles(), 2);
    assert!(!m.is_built());
    assert_eq!(m.end(), Ok(()));
    assert!(m.is_built());
    assert_eq!(m.num_triangles(), 2);
    assert!(m.memory_usage() > 0);
}

#[test]
fn out_of_sequence_calls_follow_pqp() {
    let mut m = Model::new();
    // End before begin: an empty model, as PQP 1.3's EndModel says; it stays empty.
    assert_eq!(m.end(), Err(Error::BuildEmptyModel));
    assert_eq!(m.build_state(), BuildState::Empty);
    assert_eq!(m.end(), Err(Error::BuildEmptyModel));
    // Add before begin begins implicitly.
    assert_eq!(m.add_triangle(A, B, C, 0), Ok(()));
    assert_eq!(m.end(), Ok(()));
    // Add after end is ignored.
    assert_eq!(m.add_triangle(A, B, C, 1), Err(Error::BuildOutOfSequence));
    assert_eq!(m.num_triangles(), 1);
    // End twice.
    assert_eq!(m.end(), Err(Error::BuildOutOfSequence));
    assert!(m.is_built());
    // Begin on a built model clears it, reports the misuse, and leaves it ready to build.
    assert_eq!(m.begin(4), Err(Error::BuildOutOfSequence));
    assert!(!m.is_built());
    assert_eq!(m.num_triangles(), 0);
    assert_eq!(m.add_triangle(A, B, C, 2), Ok(()));
    assert_eq!(m.end(), Ok(()));
    // Begin twice also clears.
    let mut m = Model::new();
    assert_eq!(m.begin(1), Ok(()));
    assert_eq!(m.add_triangle(A, B, C, 0), Ok(()));
    assert_eq!(m.begin(1), Err(Error::BuildOutOfSequence));
    assert_eq!(m.num_triangles(), 0);
}

#[test]
fn empty_model_cannot_be_built_or_queried() {
    let mut m = Model::new();
    assert_eq!(m.begin(0), Ok(()));
    assert_eq!(m.end(), Err(Error::BuildEmptyModel));
    assert!(!m.is_built());
    let other = Model::from_triangles([(A, B, C, 0)]).unwrap();
    let here = pqp::Pose::identity();
    assert_eq!(
        pqp::collide(&m, &here, &other, &here, pqp::ContactMode::All).unwrap_err(),
        Error::UnprocessedModel
    );
    // Still usable: add and end.
    assert_eq!(m.add_triangle(A, B, C, 0), Ok(()));
    assert_eq!(m.end(), Ok(()));
}

#[test]
fn non_finite_vertices_are_refused_and_the_model_stays_usable() {
    let mut m = Model::new();
    m.begin(4).unwrap();
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e200] {
        assert_eq!(
            m.add_triangle(A, [bad, 0.0, 0.0], C, 9),
            Err(Error::NonFiniteCoordinate)
        );
    }
    assert_eq!(m.num_triangles(), 0);
    m.add_triangle(A, B, C, 1).unwrap();
    m.end().unwrap();
    assert_eq!(m.num_triangles(), 1);
}

/// PQP 1.3's table, call by call, with the state after each: end on an empty model (fresh, begun
/// or cleared) is -5 and changes nothing; -4 only for end on a built model, add after end (ignored)
/// and begin on a model that is not fresh (cleared and begun).
#[test]
fn build_codes_and_states_follow_pqp_1_3() {
    use BuildState::{Begun, Built, Empty};
    let seq = Err(Error::BuildOutOfSequence);
    let empty = Err(Error::BuildEmptyModel);
    let mut m = Model::new();
    assert_eq!(m.build_state(), Empty);
    assert_eq!(m.end(), empty);
    assert_eq!((m.build_state(), m.num_triangles()), (Empty, 0));
    assert_eq!(m.begin(2), Ok(()));
    assert_eq!(m.build_state(), Begun);
    assert_eq!(m.end(), empty);
    assert_eq!(m.build_state(), Begun);
    assert_eq!(m.begin(2), seq);
    assert_eq!(m.build_state(), Begun);
    assert_eq!(m.add_triangle(A, B, C, 0), Ok(()));
    assert_eq!(m.end(), Ok(()));
    assert_eq!(m.build_state(), Built);
    assert_eq!(m.end(), seq);
    assert_eq!(m.add_triangle(A, B, C, 1), seq);
    assert_eq!((m.build_state(), m.num_triangles()), (Built, 1));
    assert_eq!(m.begin(0), seq);
    assert_eq!((m.build_state(), m.num_triangles()), (Begun, 0));
    assert_eq!(m.end(), empty);
    assert_eq!(m.build_state(), Begun);

    // A refused triangle on an empty model: not stored, but the implicit begin has happened.
    let mut m = Model::new();
    assert_eq!(
        m.add_triangle(A, [f64::NAN, 0.0, 0.0], C, 0),
        Err(Error::NonFiniteCoordinate)
    );
    assert_eq!((m.build_state(), m.num_triangles()), (Begun, 0));
    assert_eq!(m.end(), empty);
    assert_eq!(m.begin(1), seq);
    // On a model being built it keeps the triangles it had; on a built one the order comes first.
    m.add_triangle(A, B, C, 0).unwrap();
    assert_eq!(
        m.add_triangle(A, B, [0.0, f64::INFINITY, 0.0], 1),
        Err(Error::NonFiniteCoordinate)
    );
    assert_eq!((m.build_state(), m.num_triangles()), (Begun, 1));
    m.end().unwrap();
    assert_eq!(m.add_triangle(A, B, [f64::NAN; 3], 2), seq);
    assert_eq!((m.build_state(), m.num_triangles()), (Built, 1));
}

#[test]
fn huge_capacity_hint_is_only_a_hint() {
    let mut m = Model::new();
    assert_eq!(m.begin(usize::MAX), Ok(()));
    m.add_triangle(A, B, C, 1).unwrap();
    m.end().unwrap();
}

#[test]
fn error_codes_keep_pqp_values() {
    assert_eq!(Error::ModelOutOfMemory.code(), -1);
    assert_eq!(Error::OutOfMemory.code(), -2);
    assert_eq!(Error::UnprocessedModel.code(), -3);
    assert_eq!(Error::BuildOutOfSequence.code(), -4);
    assert_eq!(Error::BuildEmptyModel.code(), -5);
    let codes: Vec<i32> = [
        Error::NonFiniteCoordinate,
        Error::NonFinitePose,
        Error::InvalidArgument,
        Error::NullPointer,
        Error::Internal,
    ]
    .iter()
    .map(|e| e.code())
    .collect();
    assert_eq!(codes, vec![-6, -7, -8, -9, -10]);
}
