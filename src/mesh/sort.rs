//! A hand-written, panic-free stable counting sort on `u32` ids, for numbering the edges of a
//! topology: no hashing (its order would be the hasher's, and the numbering must not depend
//! on it), and not `core`'s `sort_unstable`, which keeps a `panic_on_ord_violation` path even
//! for integers (the core has no panic paths).
//!
//! Ids are ordered by `key(id)`, ties kept in input order: two passes, least significant key
//! first, sort by a pair of keys; with ids fed in ascending order the result is ordered by
//! `(key, id)`, a total order, so it is unique and deterministic.

use super::internal;
use crate::error::Result;

/// Writes the ids of `items` (`(id, key)` pairs) into `dst` ordered by key, equal keys in
/// input order (stable). `counts` needs one entry per key value (every key below
/// `counts.len()`); `dst` at least as many entries as `items` yields. `O(items + keys)`, no
/// allocation, no panic. `items` is walked twice (count, then place).
///
/// # Errors
/// An internal error for a key out of range or a short `dst` (never on a built topology).
pub(crate) fn counting_sort<I>(items: I, dst: &mut [u32], counts: &mut [u32]) -> Result<()>
where
    I: Iterator<Item = (u32, u32)> + Clone,
{
    for c in counts.iter_mut() {
        *c = 0;
    }
    for (_, key) in items.clone() {
        let c = counts.get_mut(key as usize).ok_or(internal())?;
        *c = c.saturating_add(1);
    }
    let mut acc = 0u32;
    for c in counts.iter_mut() {
        let n = *c;
        *c = acc;
        acc = acc.saturating_add(n);
    }
    for (id, key) in items {
        let c = counts.get_mut(key as usize).ok_or(internal())?;
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
        let by_minor = (0..257u32).map(|i| (i, minor[i as usize]));
        counting_sort(by_minor, &mut tmp, &mut counts).unwrap();
        let by_major = tmp.iter().map(|&i| (i, major[i as usize]));
        counting_sort(by_major, &mut ids, &mut counts).unwrap();
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
        counting_sort(core::iter::empty(), &mut e, &mut counts).unwrap();
        let mut one = [0u32; 1];
        counting_sort([(7u32, 3u32)].into_iter(), &mut one, &mut counts).unwrap();
        assert_eq!(one, [7]);
        let mut two = [0u32; 2];
        counting_sort([(3u32, 0u32), (1, 0)].into_iter(), &mut two, &mut counts).unwrap();
        assert_eq!(two, [3, 1], "stable: equal keys keep their input order");
        // A key out of range and a short destination are errors, not panics.
        let bad_key = (0..2u32).map(|i| (i, 4));
        assert!(counting_sort(bad_key, &mut two, &mut counts).is_err());
        let too_many = (0..3u32).map(|i| (i, 0));
        assert!(counting_sort(too_many, &mut two, &mut counts).is_err());
    }
}
