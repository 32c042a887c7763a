//! The seeded random numbers of every Rust test: the crate's unit tests use it as
//! `crate::test_rng`, the integration tests as `common::Rng` (tests/common/mod.rs includes this
//! file with `#[path]`), and the fuzz targets' checks need none. It uses nothing but `core`, so
//! both can compile it; helpers that return the library's types (`Vec3`, `Pose`) live beside
//! their users.
//!
//! Two streams: [`Rng`] (SplitMix64, Steele, Lea and Flood 2014), for new tests, and [`Lcg`]
//! (Knuth's MMIX linear congruential step), which the unit tests were written against and keep so
//! that their inputs stay the same. Both give the same helpers through [`Random`].
#![allow(dead_code)]

/// What every stream gives, from its 64-bit step.
pub trait Random {
    /// The next 64 random bits.
    fn next_u64(&mut self) -> u64;

    /// Uniform in [0, 1) (53 bits).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f64 {
        self.unit() * 2.0 - 1.0
    }
    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Uniform in 0..n (n > 0).
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    /// Uniform in lo..=hi.
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % ((hi - lo + 1) as u64)) as i64
    }
    /// Between lo and hi (both > 0), uniform in the logarithm.
    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.range(lo.ln(), hi.ln()).exp()
    }
    /// `10^u` for `u` uniform in [lo, hi).
    fn log10_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        10f64.powf(self.range(lo, hi))
    }
    /// Uniform in the cube [-half, half)^3.
    fn point(&mut self, half: f64) -> [f64; 3] {
        [
            self.range(-half, half),
            self.range(-half, half),
            self.range(-half, half),
        ]
    }
    /// Uniform in the ball of radius `r`.
    fn in_ball(&mut self, r: f64) -> [f64; 3] {
        loop {
            let v = self.point(1.0);
            if v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= 1.0 {
                return [v[0] * r, v[1] * r, v[2] * r];
            }
        }
    }
    /// A uniformly random unit vector.
    fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = self.point(1.0);
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 0.1 && n <= 1.0 {
                return [v[0] / n, v[1] / n, v[2] / n];
            }
        }
    }
    /// A uniformly random rotation (from a uniformly random unit quaternion), row-major.
    fn rotation(&mut self) -> [[f64; 3]; 3] {
        let (u1, u2, u3) = (self.unit(), self.unit(), self.unit());
        let tau = core::f64::consts::TAU;
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let (w, x, y, z) = (
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
            b * (tau * u3).cos(),
        );
        [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - z * w),
                2.0 * (x * z + y * w),
            ],
            [
                2.0 * (x * y + z * w),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - x * w),
            ],
            [
                2.0 * (x * z - y * w),
                2.0 * (y * z + x * w),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ]
    }
}

/// SplitMix64: small, seeded, good enough for test inputs.
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }
}

impl Random for Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// Knuth's MMIX linear congruential step; its top 53 bits are used ([`Lcg::bits`]).
#[derive(Clone, Debug)]
pub struct Lcg(pub u64);

impl Lcg {
    /// The next 53 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 11
    }
    /// Uniform in [0, 1) (here so that unit tests need not import [`Random`]).
    pub fn unit(&mut self) -> f64 {
        Random::unit(self)
    }
    /// Uniform in [-1, 1).
    pub fn signed(&mut self) -> f64 {
        Random::signed(self)
    }
}

impl Random for Lcg {
    /// The 53 bits of [`Lcg::bits`] in the top of the word, so that [`Random::unit`] gives what
    /// `bits() / 2^53` gave.
    fn next_u64(&mut self) -> u64 {
        self.bits() << 11
    }
}
