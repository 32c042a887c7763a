//! The saved layout's checksums: Fletcher-64 (version 1) and CRC-32C (version 2), each taken
//! piece by piece, so that a load sums each piece of the buffer while it reads it, and pieces
//! summed apart (on two threads) join into the checksum of the whole ([`Piece::then`]).

use super::Version;

/// The checksum of layout version 1: Fletcher-64 of `bytes` read as little-endian 32-bit words (a partial
/// last word is padded with zeros; the layout's lengths are multiples of 4): two sums modulo
/// 2^32 - 1 from 0, `a` of the words and `b` of the successive `a`, given as `b * 2^32 + a`.
/// Any change of one word (but 0 <-> 0xffffffff), so of any one byte, and any swap of two
/// different words, changes it. Blind to a word 0 changed to 0xffffffff or back (both are 0 modulo
/// 2^32 - 1): version 2 uses [`Crc32c`] instead.
pub(crate) fn fletcher64(bytes: &[u8]) -> u64 {
    let mut sum = Fletcher64::default();
    sum.update(bytes);
    sum.finish()
}

/// [`fletcher64`] taken piece by piece, so that a load sums each piece of the buffer while it
/// reads it (one pass over the buffer, not two).
#[derive(Default)]
pub(crate) struct Fletcher64 {
    a: u64,
    b: u64,
    /// Words added since the sums were last reduced.
    words: usize,
    /// Words added in all.
    total: u64,
}

/// The two sums of [`fletcher64`] over one piece of a buffer (reduced), and the piece's length in
/// words: pieces summed apart (on two threads) are joined by [`Sums::then`] into the sums of the
/// whole.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Sums {
    a: u64,
    b: u64,
    words: u64,
}

impl Sums {
    /// The sums of this piece followed by `next`, exactly as if summed in one go. Over `next`'s
    /// `m` words, `a` grows by their sum (`next.a`), and `b`, which adds the running `a` after
    /// each word, by `next.b` plus `m` times the `a` it started from.
    pub(crate) fn then(self, next: Sums) -> Sums {
        let m = Fletcher64::MODULUS;
        // Each term is below 2^32 - 1, the product below 2^64.
        let carried = (next.words % m) * self.a % m;
        Sums {
            a: (self.a + next.a) % m,
            b: (self.b + next.b + carried) % m,
            words: self.words + next.words,
        }
    }

    /// The checksum ([`Fletcher64::finish`]).
    pub(crate) fn finish(self) -> u64 {
        (self.b << 32) | self.a
    }
}

impl Fletcher64 {
    const MODULUS: u64 = 0xffff_ffff;
    /// Words between reductions: `b` stays below 2^64 (it grows by at most `a`, itself below 2^32
    /// times this, per word).
    const BLOCK: usize = 1 << 13;

    /// Adds `bytes`: a multiple of 4 long, except in the last piece (its tail is padded).
    pub(crate) fn update(&mut self, bytes: &[u8]) {
        let (mut a, mut b) = (self.a, self.b);
        let mut rest = bytes;
        while !rest.is_empty() {
            let whole = (rest.len() / 4).min(Self::BLOCK - self.words);
            let (head, tail) = rest.split_at(4 * whole);
            // Eight words at a time: after words w0..w7, `a` has grown by their sum and `b` by
            // eight times the old `a` plus 8 w0 + 7 w1 + ... + 1 w7 (independent sums the
            // compiler vectorises).
            let octets = head.chunks_exact(32);
            let single = octets.remainder();
            for o in octets {
                // 1 KiB ahead (the processor's stream prefetch alone leaves the sum waiting on
                // memory: 27 ms for 184 MB without, 19-20 with); a hint, also past the end.
                crate::math::prefetch_line(o.as_ptr().wrapping_add(1024));
                let (mut s, mut t) = (0u64, 0u64);
                for (k, w) in o.chunks_exact(4).enumerate() {
                    let w = u64::from(u32::from_le_bytes([w[0], w[1], w[2], w[3]]));
                    s += w;
                    t += (8 - k as u64) * w;
                }
                b += 8 * a + t;
                a += s;
            }
            for w in single.chunks_exact(4) {
                a += u64::from(u32::from_le_bytes([w[0], w[1], w[2], w[3]]));
                b += a;
            }
            self.words += whole;
            self.total += whole as u64;
            rest = tail;
            if whole == 0 {
                let mut w = [0u8; 4];
                w[..rest.len()].copy_from_slice(rest);
                a += u64::from(u32::from_le_bytes(w));
                b += a;
                self.words += 1;
                self.total += 1;
                rest = &[];
            }
            if self.words == Self::BLOCK {
                (a, b, self.words) = (a % Self::MODULUS, b % Self::MODULUS, 0);
            }
        }
        (self.a, self.b) = (a, b);
    }

    /// The checksum of everything added.
    pub(crate) fn finish(&self) -> u64 {
        self.sums().finish()
    }

    /// The sums of everything added, to join with others' ([`Sums::then`]).
    pub(crate) fn sums(&self) -> Sums {
        Sums {
            a: self.a % Self::MODULUS,
            b: self.b % Self::MODULUS,
            words: self.total,
        }
    }
}

/// The checksum of layout version 2: CRC-32C (the Castagnoli polynomial, as iSCSI and ext4 use
/// it) of `bytes`. Any change confined to 32 consecutive bits (so to any one word) changes it, and
/// any change at all with probability 1 - 2^-32; it runs in hardware (SSE 4.2, ARMv8 CRC) at
/// memory speed, with a software fallback elsewhere.
pub(crate) fn crc32c(bytes: &[u8]) -> u32 {
    crc32c::crc32c(bytes)
}

/// [`crc32c`] taken piece by piece.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Crc32c {
    crc: u32,
    /// Bytes added.
    len: u64,
}

impl Crc32c {
    pub(crate) fn update(&mut self, bytes: &[u8]) {
        self.crc = crc32c::crc32c_append(self.crc, bytes);
        self.len += bytes.len() as u64;
    }

    /// These bytes followed by `next`'s, as if added in one go.
    pub(crate) fn then(self, next: Crc32c) -> Crc32c {
        Crc32c {
            // The lengths are those of pieces of one buffer in memory.
            crc: crc32c::crc32c_combine(self.crc, next.crc, next.len as usize),
            len: self.len + next.len,
        }
    }
}

/// A running checksum of either version.
pub(super) enum Running {
    Fletcher(Fletcher64),
    Crc(Crc32c),
}

/// The checksum of one piece of a buffer, of either version, to join with the others'.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Piece {
    Fletcher(Sums),
    Crc(Crc32c),
}

impl Running {
    pub(super) fn new(version: Version) -> Running {
        match version {
            Version::V1 => Running::Fletcher(Fletcher64::default()),
            Version::V2 => Running::Crc(Crc32c::default()),
        }
    }

    pub(super) fn update(&mut self, bytes: &[u8]) {
        match self {
            Running::Fletcher(f) => f.update(bytes),
            Running::Crc(c) => c.update(bytes),
        }
    }

    /// What was added, as a piece.
    pub(super) fn piece(&self) -> Piece {
        match self {
            Running::Fletcher(f) => Piece::Fletcher(f.sums()),
            Running::Crc(c) => Piece::Crc(*c),
        }
    }
}

impl Piece {
    /// An empty piece of `version`'s checksum.
    pub(super) fn empty(version: Version) -> Piece {
        Running::new(version).piece()
    }

    /// This piece followed by `next` (of the same version; a piece of the other version, which no
    /// load makes, leaves this one as it is).
    pub(super) fn then(self, next: Piece) -> Piece {
        match (self, next) {
            (Piece::Fletcher(a), Piece::Fletcher(b)) => Piece::Fletcher(a.then(b)),
            (Piece::Crc(a), Piece::Crc(b)) => Piece::Crc(a.then(b)),
            _ => self,
        }
    }

    /// The checksum as the trailer stores it (version 1: `b * 2^32 + a`; version 2: the CRC in
    /// the low 32 bits).
    pub(super) fn finish(self) -> u64 {
        match self {
            Piece::Fletcher(s) => s.finish(),
            Piece::Crc(c) => u64::from(c.crc),
        }
    }
}

/// The trailer of `body` in `version`.
pub(super) fn checksum(version: Version, body: &[u8]) -> u64 {
    match version {
        Version::V1 => fletcher64(body),
        Version::V2 => u64::from(crc32c(body)),
    }
}
