//! Large buffers: refuse, with a message, what the machine cannot hold instead of letting
//! the allocator abort or the kernel's out-of-memory killer end the process.

use crate::error::{CliError, CliResult};

/// Bytes as a short human string (`512 MiB`, `3.2 GiB`).
pub fn human_bytes(bytes: u128) -> String {
    const MIB: f64 = 1024.0 * 1024.0;
    let b = bytes as f64;
    if b >= 1024.0 * MIB {
        format!("{:.1} GiB", b / (1024.0 * MIB))
    } else {
        format!("{:.0} MiB", (b / MIB).ceil())
    }
}

/// The memory the system says is available (`MemAvailable` of `/proc/meminfo`), when known.
fn available() -> Option<u128> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses (exit 4: the command line asks for too much) when `bytes` exceed the available
/// memory; `what` says what the memory is for, `hint` what to do.
///
/// # Errors
/// Exit 4 with a message naming the size.
pub fn check(bytes: u128, what: &str, hint: &str) -> CliResult<()> {
    match available() {
        Some(avail) if bytes > avail => Err(CliError::usage(format!(
            "{what} needs about {} of memory, more than the {} available: {hint}",
            human_bytes(bytes),
            human_bytes(avail)
        ))),
        _ => Ok(()),
    }
}

/// Buffers from this size on are checked against `MemAvailable` before they are allocated.
const LARGE: u128 = 64 << 20;

/// A vector of `n` copies of `fill`, or exit 4 when the allocation fails.
///
/// # Errors
/// Exit 4 naming `what` and the size.
pub fn filled<T: Clone>(n: usize, fill: T, what: &str) -> CliResult<Vec<T>> {
    let bytes = (n as u128).saturating_mul(std::mem::size_of::<T>() as u128);
    // Large buffers are also checked against the available memory: with overcommit, an
    // allocation the machine cannot back succeeds and the out-of-memory killer strikes later.
    if bytes >= LARGE {
        check(bytes, what, "use fewer levels or a smaller input")?;
    }
    let mut v = Vec::new();
    v.try_reserve_exact(n).map_err(|_| {
        CliError::usage(format!(
            "cannot allocate {} for {what}: use fewer levels or a smaller input",
            human_bytes((n as u128).saturating_mul(std::mem::size_of::<T>() as u128))
        ))
    })?;
    v.resize(n, fill);
    Ok(v)
}
