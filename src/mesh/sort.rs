//! A hand-written, panic-free heapsort on `u32` ids (reliability-anchors.md §3.1, §4.4:
//! `core`'s `sort_unstable` keeps a `panic_on_ord_violation` path even for integers).
//!
//! Ids are ordered by `(key(id), id)`, a total order, so the result is unique and does not
//! depend on the initial order: the sort is deterministic although heapsort is not stable.

/// Sorts `ids` ascending by `(key(id), id)`. `O(n log n)`, in place, no allocation, no panic.
pub(crate) fn heapsort_by_key<K: Fn(u32) -> u64>(ids: &mut [u32], key: K) {
    let n = ids.len();
    let less = |a: u32, b: u32| (key(a), a) < (key(b), b);
    let mut start = n / 2;
    while start > 0 {
        start -= 1;
        sift_down(ids, start, n, &less);
    }
    let mut end = n;
    while end > 1 {
        end -= 1;
        swap(ids, 0, end);
        sift_down(ids, 0, end, &less);
    }
}

fn sift_down<L: Fn(u32, u32) -> bool>(ids: &mut [u32], mut root: usize, end: usize, less: &L) {
    loop {
        let child = root.saturating_mul(2).saturating_add(1);
        if child >= end {
            return;
        }
        let Some(&c0) = ids.get(child) else { return };
        let mut c = child;
        let mut cv = c0;
        if child + 1 < end {
            if let Some(&c1) = ids.get(child + 1) {
                if less(c0, c1) {
                    c = child + 1;
                    cv = c1;
                }
            }
        }
        let Some(&rv) = ids.get(root) else { return };
        if less(rv, cv) {
            swap(ids, root, c);
            root = c;
        } else {
            return;
        }
    }
}

fn swap(ids: &mut [u32], i: usize, j: usize) {
    if let (Some(&a), Some(&b)) = (ids.get(i), ids.get(j)) {
        if let Some(x) = ids.get_mut(i) {
            *x = b;
        }
        if let Some(y) = ids.get_mut(j) {
            *y = a;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sorts_by_key_then_id() {
        // Pseudo-random keys from a fixed LCG, many ties.
        let mut state = 12345u64;
        let keys: [u64; 257] = core::array::from_fn(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) % 17
        });
        let mut ids: [u32; 257] = core::array::from_fn(|i| (256 - i) as u32);
        heapsort_by_key(&mut ids, |i| keys[i as usize]);
        for w in ids.windows(2) {
            let (a, b) = (w[0], w[1]);
            assert!((keys[a as usize], a) < (keys[b as usize], b));
        }
        // A permutation of 0..257.
        let mut seen = [false; 257];
        for &i in &ids {
            seen[i as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn trivial_lengths() {
        let mut e: [u32; 0] = [];
        heapsort_by_key(&mut e, |i| i as u64);
        let mut one = [7u32];
        heapsort_by_key(&mut one, |i| i as u64);
        assert_eq!(one, [7]);
        let mut two = [3u32, 1];
        heapsort_by_key(&mut two, |_| 0);
        assert_eq!(two, [1, 3]);
    }
}
