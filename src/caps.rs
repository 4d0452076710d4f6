//! The build-time capacities: the largest vertex valence and face size any rule accepts.
//!
//! Several rules hold one vertex star or one face in a fixed-capacity array (the canonical
//! form's tangent polygon, a face's corners for the F6 chain, the C ABI's copies of a star
//! rule's outputs), so these caps bound the kernel's stack as well as the meshes it accepts
//! (`docs/firmware.md`, "Capacities"). A firmware build that knows its meshes can lower them
//! at build time, and a host that needs larger stars can raise them:
//!
//! ```sh
//! NLSUBDIV_MAX_VALENCE=16 NLSUBDIV_MAX_FACE_SIZE=8 cargo build --release -p nlsubdiv-ffi
//! ```
//!
//! Unset, they are 128. Each must be a decimal number from 8 ([`MIN_CAP`]) to 4096 ([`MAX_CAP`]);
//! anything else stops the build with a message (a `const` assertion), never a silent
//! default. A mesh within the caps gives the same output bits whatever the caps are (no rule
//! reads them except to refuse); a vertex or face beyond them is
//! [`crate::Status::ValenceTooHigh`] naming it, from validation or from the plan when a
//! later level would exceed them, before anything is written.

/// The least cap a build accepts: the regular valences of every scheme (6 for triangle
/// schemes, 4 for quad schemes) and their face sizes fit, with room for the boundary.
pub(crate) const MIN_CAP: usize = 8;

/// The largest cap a build accepts. Valences and face sizes are counted in `u32` elsewhere;
/// this bound keeps the per-star arrays (about 24 bytes per entry each) far from any
/// stack's size.
pub(crate) const MAX_CAP: usize = 4096;

/// The default of both caps.
const DEFAULT_CAP: usize = 128;

/// `text` read as a decimal number, `default` when it is absent, and 0 (refused by the
/// assertions below) when it is empty, has a character other than a digit, or is above
/// [`MAX_CAP`].
pub(crate) const fn parse(text: Option<&str>, default: usize) -> usize {
    let bytes = match text {
        Some(t) => t.as_bytes(),
        None => return default,
    };
    if bytes.is_empty() {
        return 0;
    }
    let mut value = 0usize;
    let mut rest = bytes;
    while let [b, tail @ ..] = rest {
        if !b.is_ascii_digit() {
            return 0;
        }
        value = value * 10 + (*b - b'0') as usize;
        if value > MAX_CAP {
            return 0;
        }
        rest = tail;
    }
    value
}

/// The largest vertex valence, from `NLSUBDIV_MAX_VALENCE` at build time (default 128).
pub(crate) const MAX_VALENCE: usize = parse(option_env!("NLSUBDIV_MAX_VALENCE"), DEFAULT_CAP);

/// The largest face size, from `NLSUBDIV_MAX_FACE_SIZE` at build time (default 128).
pub(crate) const MAX_FACE_SIZE: usize = parse(option_env!("NLSUBDIV_MAX_FACE_SIZE"), DEFAULT_CAP);

const _: () = assert!(
    MAX_VALENCE >= MIN_CAP && MAX_VALENCE <= MAX_CAP,
    "NLSUBDIV_MAX_VALENCE must be a decimal number from 8 to 4096"
);
const _: () = assert!(
    MAX_FACE_SIZE >= MIN_CAP && MAX_FACE_SIZE <= MAX_CAP,
    "NLSUBDIV_MAX_FACE_SIZE must be a decimal number from 8 to 4096"
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_reads_decimal_numbers_and_refuses_the_rest() {
        assert_eq!(parse(None, 128), 128);
        assert_eq!(parse(Some("16"), 128), 16);
        assert_eq!(parse(Some("0008"), 128), 8);
        assert_eq!(parse(Some("4096"), 128), 4096);
        for bad in [
            "",
            "4097",
            "99999999999999999999999",
            "16 ",
            "-8",
            "0x10",
            "1e3",
        ] {
            assert_eq!(parse(Some(bad), 128), 0, "{bad:?}");
        }
    }
}
