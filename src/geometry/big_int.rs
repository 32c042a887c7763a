//! Exact integers of any size: the last resort of the orientation predicates, for inputs whose
//! magnitudes span so many binades that the floating-point expansions would underflow (see
//! `predicates.rs`). Every finite double is an integer multiple of 2^-1074, so the predicates take
//! each coordinate as that integer and evaluate their determinants exactly. Rare and small (a few
//! dozen 64-bit limbs), so plain schoolbook arithmetic.

use std::cmp::Ordering;

/// The exponent of the least double's unit: every finite double is `n * 2^LSB` for an integer `n`.
pub(crate) const LSB: i32 = -1074;

/// A signed integer: magnitude in little-endian 64-bit limbs without leading zero limbs (zero has
/// none, and is never negative).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct BigInt {
    neg: bool,
    mag: Vec<u64>,
}

impl BigInt {
    /// `x / 2^LSB`, exactly, for a finite `x`.
    pub fn from_f64(x: f64) -> BigInt {
        debug_assert!(x.is_finite());
        let bits = x.to_bits();
        let biased = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        // x = m * 2^e.
        let (m, e) = if biased == 0 {
            (frac, LSB)
        } else {
            (frac | 1u64 << 52, biased - 1075)
        };
        let shift = (e - LSB) as usize;
        let (q, r) = (shift / 64, shift % 64);
        let mut mag = vec![0u64; q + 2];
        mag[q] = m << r;
        if r > 0 {
            mag[q + 1] = m >> (64 - r);
        }
        BigInt { neg: x < 0.0, mag }.trimmed()
    }

    fn trimmed(mut self) -> BigInt {
        while self.mag.last() == Some(&0) {
            self.mag.pop();
        }
        if self.mag.is_empty() {
            self.neg = false;
        }
        self
    }

    /// -1, 0 or 1.
    #[cfg(test)]
    pub fn signum(&self) -> i32 {
        match (self.mag.is_empty(), self.neg) {
            (true, _) => 0,
            (false, true) => -1,
            (false, false) => 1,
        }
    }

    pub fn neg(&self) -> BigInt {
        BigInt {
            neg: !self.neg && !self.mag.is_empty(),
            mag: self.mag.clone(),
        }
    }

    pub fn add(&self, o: &BigInt) -> BigInt {
        if self.neg == o.neg {
            return BigInt {
                neg: self.neg,
                mag: add_mag(&self.mag, &o.mag),
            }
            .trimmed();
        }
        match cmp_mag(&self.mag, &o.mag) {
            Ordering::Equal => BigInt {
                neg: false,
                mag: Vec::new(),
            },
            Ordering::Greater => BigInt {
                neg: self.neg,
                mag: sub_mag(&self.mag, &o.mag),
            }
            .trimmed(),
            Ordering::Less => BigInt {
                neg: o.neg,
                mag: sub_mag(&o.mag, &self.mag),
            }
            .trimmed(),
        }
    }

    pub fn sub(&self, o: &BigInt) -> BigInt {
        self.add(&o.neg())
    }

    pub fn mul(&self, o: &BigInt) -> BigInt {
        if self.mag.is_empty() || o.mag.is_empty() {
            return BigInt {
                neg: false,
                mag: Vec::new(),
            };
        }
        let mut out = vec![0u64; self.mag.len() + o.mag.len()];
        for (i, &a) in self.mag.iter().enumerate() {
            let mut carry = 0u128;
            for (j, &b) in o.mag.iter().enumerate() {
                let t = u128::from(a) * u128::from(b) + u128::from(out[i + j]) + carry;
                out[i + j] = t as u64;
                carry = t >> 64;
            }
            out[i + o.mag.len()] = carry as u64;
        }
        BigInt {
            neg: self.neg != o.neg,
            mag: out,
        }
        .trimmed()
    }

    /// The number of bits of the magnitude: `|self|` lies in `[2^(n-1), 2^n)`; 0 for zero.
    pub fn bit_len(&self) -> i64 {
        match self.mag.last() {
            None => 0,
            Some(&top) => 64 * (self.mag.len() as i64 - 1) + 64 - i64::from(top.leading_zeros()),
        }
    }

    /// `self * 2^k` rounded to a double (within an ulp or so) with the exact sign: a nonzero
    /// value beyond the doubles' range saturates at the largest finite or least normal magnitude.
    pub fn to_f64_scaled(&self, k: i32) -> f64 {
        let n = self.mag.len();
        if n == 0 {
            return 0.0;
        }
        // The top two limbs, and the exponent of the rest.
        let (mut y, below) = if n == 1 {
            (self.mag[0] as f64, 0)
        } else {
            let top = self.mag[n - 1] as f64 * 2f64.powi(64) + self.mag[n - 2] as f64;
            (top, 64 * (n as i64 - 2))
        };
        let mut e = below + i64::from(k);
        // In steps that keep each factor a normal power of two.
        while e != 0 {
            let step = e.clamp(-1000, 1000);
            y *= 2f64.powi(step as i32);
            e -= step;
        }
        let y = if y == 0.0 {
            f64::MIN_POSITIVE
        } else if y.is_infinite() {
            f64::MAX
        } else {
            y
        };
        if self.neg { -y } else { y }
    }
}

fn cmp_mag(a: &[u64], b: &[u64]) -> Ordering {
    a.len()
        .cmp(&b.len())
        .then_with(|| a.iter().rev().cmp(b.iter().rev()))
}

fn add_mag(a: &[u64], b: &[u64]) -> Vec<u64> {
    let (long, short) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    let mut out = Vec::with_capacity(long.len() + 1);
    let mut carry = false;
    for (i, &x) in long.iter().enumerate() {
        let (s, c1) = x.overflowing_add(short.get(i).copied().unwrap_or(0));
        let (s, c2) = s.overflowing_add(u64::from(carry));
        out.push(s);
        carry = c1 || c2;
    }
    out.push(u64::from(carry));
    out
}

/// `a - b` for `|a| >= |b|`.
fn sub_mag(a: &[u64], b: &[u64]) -> Vec<u64> {
    let mut out = Vec::with_capacity(a.len());
    let mut borrow = false;
    for (i, &x) in a.iter().enumerate() {
        let (d, b1) = x.overflowing_sub(b.get(i).copied().unwrap_or(0));
        let (d, b2) = d.overflowing_sub(u64::from(borrow));
        out.push(d);
        borrow = b1 || b2;
    }
    debug_assert!(!borrow);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;

    /// Small values agree with i128 arithmetic, and values convert back to their doubles.
    #[test]
    fn arithmetic_agrees_with_i128_and_round_trips() {
        let mut rng = Lcg(11);
        let lsb = 2f64.powi(LSB);
        for _ in 0..2000 {
            let a = (rng.signed() * 1e9).round() * lsb;
            let b = (rng.signed() * 1e9).round() * lsb;
            let (ia, ib) = ((a / lsb) as i128, (b / lsb) as i128);
            let (ba, bb) = (BigInt::from_f64(a), BigInt::from_f64(b));
            for (big, small) in [
                (ba.add(&bb), ia + ib),
                (ba.sub(&bb), ia - ib),
                (ba.mul(&bb), ia * ib),
            ] {
                assert_eq!(big.signum(), small.signum() as i32);
                assert_eq!(big.to_f64_scaled(0), small as f64);
            }
        }
        for x in [
            1.0,
            -3.5,
            1e150,
            -1e-300,
            5e-324,
            f64::MAX,
            -f64::MIN_POSITIVE,
        ] {
            assert_eq!(BigInt::from_f64(x).to_f64_scaled(LSB), x, "{x:e}");
        }
        // Products far beyond the doubles' range keep their sign and saturate.
        let big = BigInt::from_f64(-f64::MAX);
        assert_eq!(big.mul(&big).mul(&big).to_f64_scaled(3 * LSB), -f64::MAX);
    }
}
