//! Prints one FNV-1a hash of the bits of many kernel outputs on a fixed input set. The test
//! command builds this in several configurations (debug, release, opt-level 1,
//! `-C target-cpu=native`) and requires the same hash from all: same input, same bits.
//!
//! `cargo run --release --example det_hash`
#![allow(clippy::expect_used, clippy::indexing_slicing)] // a std program, not the core

use nlsubdiv::blend::{f4, f6};
use nlsubdiv::mobius::{CanonicalForm, MobiusMap, StarKind};
use nlsubdiv::quat::cross_ratio;

struct Fnv(u64);
impl Fnv {
    fn bits(&mut self, x: f64) {
        for b in x.to_bits().to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x100_0000_01b3);
        }
    }
    fn status(&mut self, code: u32) {
        self.bits(f64::from(code) + 0.5);
    }
}

/// SplitMix64, a fixed-seed generator.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    fn point(&mut self) -> [f64; 3] {
        [self.next(), self.next(), self.next()]
    }
}

fn main() {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    let mut rng = Rng(20181126);
    let mut ok = 0usize;
    for _ in 0..20_000 {
        let p: Vec<[f64; 3]> = (0..6).map(|_| rng.point()).collect();
        for r in [
            f4(p[0], p[1], p[2], p[3]),
            f6(p[0], p[1], p[2], p[3], p[4], p[5]),
        ] {
            match r {
                Ok(x) => {
                    ok += 1;
                    x.iter().for_each(|&c| h.bits(c));
                }
                Err(e) => h.status(e.status.code()),
            }
        }
        match cross_ratio(p[0], p[1], p[2], p[3]) {
            Ok(q) => q.to_array().iter().for_each(|&c| h.bits(c)),
            Err(e) => h.status(e.status.code()),
        }
        let m = MobiusMap::inversion(p[4], 0.5 + rng.next().abs())
            .compose(&MobiusMap::rotation([0.0, 0.6, 0.8], rng.next()));
        match m.apply(p[5]) {
            Ok(x) => x.iter().for_each(|&c| h.bits(c)),
            Err(e) => h.status(e.status.code()),
        }
        match CanonicalForm::new(p[0], &p[1..], StarKind::Interior) {
            Ok(cf) => {
                cf.c.iter().for_each(|&c| h.bits(c));
                h.bits(cf.r);
            }
            Err(e) => h.status(e.status.code()),
        }
    }
    println!("det_hash {:016x} ({ok} blends)", h.0);
}
