//! A hand-written, panic-free stable counting sort on `u32` ids (reliability-anchors.md
//! §3.1, §4.4: no hashing, and `core`'s `sort_unstable` keeps a `panic_on_ord_violation`
//! path even for integers).
//!
//! Ids are ordered by `key(id)`, ties kept in input order: two passes, least significant key
//! first, sort by a pair of keys; with ids fed in ascending order the result is ordered by
//! `(key, id)`, a total order, so it is unique and deterministic.

use super::internal;
use crate::error::Result;

/// Writes the ids of `ids` into `dst` ordered by `key(id)`, equal keys in input order
/// (stable). `counts` needs one entry per key value (every key below `counts.len()`); `dst`
/// at least as many entries as `ids` yields. `O(ids + keys)`, no allocation, no panic.
///
/// # Errors
/// An internal error for a key out of range or a short `dst` (never on a built topology).
pub(crate) fn counting_sort<I, K>(ids: I, dst: &mut [u32], counts: &mut [u32], key: K) -> Result<()>
where
    I: Iterator<Item = u32> + Clone,
    K: Fn(u32) -> u32,
{
    for c in counts.iter_mut() {
        *c = 0;
    }
    for id in ids.clone() {
        let c = counts.get_mut(key(id) as usize).ok_or(internal())?;
        *c = c.saturating_add(1);
    }
    let mut acc = 0u32;
    for c in counts.iter_mut() {
        let n = *c;
        *c = acc;
        acc = acc.saturating_add(n);
    }
    for id in ids {
        let c = counts.get_mut(key(id) as usize).ok_or(internal())?;
        *dst.get_mut(*c as usize).ok_or(internal())? = id;
        *c = c.saturating_add(1);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two passes sort by `(major, minor, id)`: checked against the definition of the order.
    #[test]
    fn two_passes_sort_by_key_pair_then_id() {
        // Pseudo-random keys from a fixed LCG, many ties.
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 33) % 7) as u32
        };
        let major: [u32; 257] = core::array::from_fn(|_| next());
        let minor: [u32; 257] = core::array::from_fn(|_| next());
        let mut tmp = [0u32; 257];
        let mut ids = [0u32; 257];
        let mut counts = [0u32; 7];
        counting_sort(0..257u32, &mut tmp, &mut counts, |i| minor[i as usize]).unwrap();
        counting_sort(tmp.iter().copied(), &mut ids, &mut counts, |i| {
            major[i as usize]
        })
        .unwrap();
        for w in ids.windows(2) {
            let (a, b) = (w[0] as usize, w[1] as usize);
            assert!((major[a], minor[a], a) < (major[b], minor[b], b));
        }
        // A permutation of 0..257.
        let mut seen = [false; 257];
        for &i in &ids {
            seen[i as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn trivial_lengths_and_bad_keys() {
        let mut counts = [0u32; 4];
        let mut e: [u32; 0] = [];
        counting_sort(0..0u32, &mut e, &mut counts, |i| i).unwrap();
        let mut one = [0u32; 1];
        counting_sort(7..8u32, &mut one, &mut counts, |_| 3).unwrap();
        assert_eq!(one, [7]);
        let mut two = [0u32; 2];
        counting_sort([3u32, 1].into_iter(), &mut two, &mut counts, |_| 0).unwrap();
        assert_eq!(two, [3, 1], "stable: equal keys keep their input order");
        // A key out of range and a short destination are errors, not panics.
        assert!(counting_sort(0..2u32, &mut two, &mut counts, |_| 4).is_err());
        assert!(counting_sort(0..3u32, &mut two, &mut counts, |_| 0).is_err());
    }
}
