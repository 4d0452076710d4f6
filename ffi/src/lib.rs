//! The C ABI of nlsubdiv (`include/nlsubdiv.h`, prefix `nls_`).
//!
//! This crate is the only place with `unsafe` code. Every export follows one contract:
//!
//! 1. every fallible call returns `nls_status` (`NLS_STATUS_OK = 0`);
//! 2. pointers are checked before use: NULL (with a non-zero count) gives
//!    `NLS_STATUS_NULL_PARAMETER`, a misaligned pointer `NLS_STATUS_MISALIGNED_POINTER`, a byte
//!    size above `isize::MAX` `NLS_STATUS_SIZE_OVERFLOW`;
//! 3. a host running with flush-to-zero / denormals-are-zero or a non-default rounding mode
//!    gets `NLS_STATUS_FP_ENVIRONMENT` (results would not be the documented bits); a host's
//!    unmasked exception traps are masked for the call and restored after it (they change
//!    no result; docs/DECISIONS.md, "Host floating-point traps");
//! 4. results are written to the trailing out-parameters only on success;
//! 5. no global state: every function is reentrant and thread-safe.
//!
//! Panics cannot cross the boundary: the core is written without panic paths, and the
//! `panic-never` feature turns any panic path that survives optimisation into a link error.
#![cfg_attr(not(any(test, feature = "std")), no_std)]
#![allow(clippy::missing_safety_doc)] // every export documents its safety contract in prose

pub mod curve;
pub mod executor;
mod guard;
pub mod mesh;
pub mod mobius;
pub mod primitives;
pub mod star;
pub mod tags;
mod weights;

pub use nlsubdiv::Status;

/// Major version of the library (also `NLS_VERSION_MAJOR` in the header).
pub const NLS_VERSION_MAJOR: u32 = 0;
/// Minor version of the library (also `NLS_VERSION_MINOR`).
pub const NLS_VERSION_MINOR: u32 = 2;
/// Patch version of the library (also `NLS_VERSION_PATCH`).
pub const NLS_VERSION_PATCH: u32 = 0;

/// The library version as `(major << 16) | (minor << 8) | patch`; compare with the
/// `NLS_VERSION_*` macros of the header the program was compiled with.
#[unsafe(no_mangle)]
pub extern "C" fn nls_version() -> u32 {
    (NLS_VERSION_MAJOR << 16) | (NLS_VERSION_MINOR << 8) | NLS_VERSION_PATCH
}

/// The largest vertex valence this build of the library accepts (`MAX_VALENCE`: 128 unless
/// the library was built with `NLSUBDIV_MAX_VALENCE`, 8 to 4096). A vertex with more
/// neighbours, in the input or in a level the plan predicts, is `NLS_STATUS_VALENCE_TOO_HIGH`.
#[unsafe(no_mangle)]
pub extern "C" fn nls_max_valence() -> u32 {
    nlsubdiv::MAX_VALENCE as u32
}

/// The largest face size (corners) this build of the library accepts (`MAX_FACE_SIZE`: 128
/// unless the library was built with `NLSUBDIV_MAX_FACE_SIZE`, 8 to 4096). A larger face is
/// `NLS_STATUS_VALENCE_TOO_HIGH`.
#[unsafe(no_mangle)]
pub extern "C" fn nls_max_face_size() -> u32 {
    nlsubdiv::MAX_FACE_SIZE as u32
}

/// A static, NUL-terminated description of a status code. Unknown codes give
/// `"unknown status"`. The pointer is valid for the life of the program; never free it.
#[unsafe(no_mangle)]
pub extern "C" fn nls_status_str(status: u32) -> *const core::ffi::c_char {
    match Status::from_code(status) {
        Some(s) => s.c_message().as_ptr(),
        None => c"unknown status".as_ptr(),
    }
}

#[cfg(not(any(test, feature = "std")))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    #[cfg(feature = "panic-never")]
    {
        unsafe extern "C" {
            // Deliberately undefined: linking fails if any panic path is reachable.
            fn nls_error_panic_path_reachable() -> !;
        }
        // SAFETY: never executed; the symbol does not exist, so this only links when the
        // optimiser removed every call to the panic handler.
        unsafe { nls_error_panic_path_reachable() }
    }
    #[cfg(not(feature = "panic-never"))]
    {
        unsafe extern "C" {
            fn abort() -> !;
        }
        // SAFETY: `abort` from the C library takes no arguments and never returns.
        unsafe { abort() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_matches_cargo_toml() {
        let v = env!("CARGO_PKG_VERSION");
        let expected = format!("{NLS_VERSION_MAJOR}.{NLS_VERSION_MINOR}.{NLS_VERSION_PATCH}");
        assert_eq!(v, expected);
        assert_eq!(nlsubdiv::VERSION, v);
        assert_eq!(
            nls_version(),
            (NLS_VERSION_MAJOR << 16) | (NLS_VERSION_MINOR << 8)
        );
    }

    #[test]
    fn header_matches_version_and_signatures() {
        let header = include_str!("../../include/nlsubdiv.h");
        for (name, value) in [
            ("NLS_VERSION_MAJOR", NLS_VERSION_MAJOR),
            ("NLS_VERSION_MINOR", NLS_VERSION_MINOR),
            ("NLS_VERSION_PATCH", NLS_VERSION_PATCH),
        ] {
            assert!(
                header.contains(&format!("#define {name} {value}")),
                "{name} in the header differs from Cargo.toml"
            );
        }
        assert!(header.contains(&format!(
            "#define NLS_VERSION_STRING \"{}\"",
            nlsubdiv::VERSION
        )));
        // The three primitive signatures the C API promises (array parameters, out last).
        for sig in [
            "nls_status nls_cross_ratio(const double a[3], const double b[3], const double c[3], const double d[3], double out_wxyz[4]);",
            "nls_status nls_f4(const double a[3], const double b[3], const double c[3], const double d[3], double out[3]);",
            "nls_status nls_f6(const double a[3], const double b[3], const double c[3], const double d[3], const double e[3], const double f[3], double out[3]);",
        ] {
            assert!(header.contains(sig), "missing exact signature:\n{sig}");
        }
    }

    /// The exported functions of the header, each as its name and parameter list.
    fn header_functions() -> Vec<(String, Vec<String>)> {
        let header = include_str!("../../include/nlsubdiv.h");
        // Declarations only (comments removed), each ending at its `;`.
        let mut code = String::new();
        let mut in_block = false;
        for line in header.lines() {
            let t = line.trim_start();
            if in_block {
                in_block = !t.contains("*/");
                continue;
            }
            if t.starts_with("/*") {
                in_block = !t.contains("*/");
                continue;
            }
            if t.starts_with('#') || t.starts_with("//") {
                continue;
            }
            code.push_str(line);
            code.push(' ');
        }
        let mut out = Vec::new();
        for decl in code.split(';') {
            // What follows a brace (`extern "C" {`, the end of a struct) starts a declaration.
            let decl = decl.rsplit(['{', '}']).next().unwrap_or("").trim();
            let Some(open) = decl.find('(') else { continue };
            let head = &decl[..open];
            let Some(name) = head.split_whitespace().last() else {
                continue;
            };
            let name = name.trim_start_matches('*');
            if !name.starts_with("nls_") || head.contains("typedef") {
                continue;
            }
            let close = decl.rfind(')').unwrap();
            let params: Vec<String> = decl[open + 1..close]
                .split(',')
                .map(|p| p.trim().to_string())
                .filter(|p| !p.is_empty() && p != "void")
                .collect();
            out.push((name.to_string(), params));
        }
        out
    }

    /// No exported function takes more than ten parameters (struct arguments instead).
    #[test]
    fn no_export_has_more_than_ten_parameters() {
        let fns = header_functions();
        assert!(fns.len() >= 40, "{} functions found", fns.len());
        assert!(fns
            .iter()
            .any(|(n, p)| n == "nls_mesh_subdivide" && p.len() == 7));
        assert!(fns.iter().any(|(n, p)| n == "nls_version" && p.is_empty()));
        for (name, params) in &fns {
            assert!(
                params.len() <= 10,
                "{name} takes {} parameters",
                params.len()
            );
            assert!(!name.ends_with("_len"), "{name}: sizes are named _size");
        }
    }

    /// The header is for C readers: no rustdoc link syntax, a Doxygen file block.
    #[test]
    fn header_has_no_rustdoc_links() {
        let header = include_str!("../../include/nlsubdiv.h");
        for (i, line) in header.lines().enumerate() {
            assert!(!line.contains("[`"), "line {}: {line}", i + 1);
            assert!(!line.contains("`]"), "line {}: {line}", i + 1);
            assert!(!line.contains("]("), "line {}: {line}", i + 1);
        }
        assert!(header.starts_with("/**\n * @file nlsubdiv.h"));
    }

    #[test]
    fn status_strings() {
        for &s in Status::all() {
            let p = nls_status_str(s.code());
            let c = unsafe { core::ffi::CStr::from_ptr(p) };
            assert_eq!(c.to_str().unwrap(), s.message());
        }
        let p = nls_status_str(77_777);
        let c = unsafe { core::ffi::CStr::from_ptr(p) };
        assert_eq!(c.to_str().unwrap(), "unknown status");
    }

    /// `Status` is `#[non_exhaustive]` and `Status::all()` is a hand-written list, so this
    /// checks the C table against the enum itself: the header's `NLS_STATUS_*` values are
    /// generated by cbindgen from the enum's variants (and the header-freshness check keeps
    /// them current). Every one must be listed, known to `from_code` and have its own message,
    /// and every other code up to 1023 must be unknown.
    #[test]
    fn status_table_covers_every_code_of_the_header() {
        let header = include_str!("../../include/nlsubdiv.h");
        let mut codes = Vec::new();
        for line in header.lines() {
            let Some(rest) = line.trim().strip_prefix("NLS_STATUS_") else {
                continue;
            };
            let Some((name, value)) = rest.split_once(" = ") else {
                continue;
            };
            let code: u32 = value.trim_end_matches(',').parse().unwrap();
            codes.push((name.to_string(), code));
        }
        assert_eq!(codes.len(), Status::all().len(), "header {codes:?}");
        let text = |code: u32| {
            let p = nls_status_str(code);
            unsafe { core::ffi::CStr::from_ptr(p) }.to_str().unwrap()
        };
        let mut messages = std::collections::BTreeSet::new();
        for (name, code) in &codes {
            let s = Status::from_code(*code).unwrap_or_else(|| panic!("NLS_STATUS_{name}"));
            assert!(Status::all().contains(&s), "NLS_STATUS_{name} not listed");
            assert_ne!(text(*code), "unknown status", "NLS_STATUS_{name}");
            assert!(
                messages.insert(text(*code)),
                "NLS_STATUS_{name}: message repeated"
            );
        }
        for code in 0..1024u32 {
            if !codes.iter().any(|(_, c)| *c == code) {
                assert_eq!(Status::from_code(code), None, "code {code}");
                assert_eq!(text(code), "unknown status", "code {code}");
            }
        }
    }
}
