//! Status codes and the error type of every fallible call.
//!
//! One enum serves the Rust API and the C ABI (`nls_status`): its discriminants are stable
//! `u32` codes, never reused. Codes 1–27 are the row numbers of their classes in the bad-input
//! catalogue (`docs/bad-input-catalogue.md`), so that a number seen in a C host's log can be
//! looked up there (a class that is accepted or reported with another class's status has no
//! code of its own); 28 and above are numbered after the catalogue's rows.
//!
//! Both [`Status`] and [`Error`] are `#[non_exhaustive]`: a later version may add a status (a
//! new code, never a changed one) or a field of the error without breaking callers, so a
//! `match` on a status outside this crate needs a wildcard arm.

use core::ffi::CStr;
use core::fmt;

/// Outcome of a call. `Ok` is 0; every other value names one class of failure.
///
/// The C ABI returns these as `uint32_t`-sized enum values (`NLS_STATUS_*`).
#[repr(u32)]
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Status {
    /// Success. Out-parameters were written.
    Ok = 0,
    /// A pointer argument was NULL while its count was non-zero (C ABI only).
    NullParameter = 1,
    /// A pointer argument was not aligned for its element type (C ABI only).
    MisalignedPointer = 2,
    /// A size computation overflowed (`count * 3`, output sizes at high levels, `u32` indices).
    SizeOverflow = 3,
    /// Input and output (or scratch) buffers overlap; in-place calls are not supported.
    AliasingBuffers = 4,
    /// Face offsets are malformed: not starting at 0, not monotonic, or not ending at the
    /// index count.
    BadOffsets = 5,
    /// A face has fewer than three vertices.
    FaceTooSmall = 6,
    /// A vertex index is not below the vertex count.
    IndexOutOfRange = 7,
    /// A face uses the same vertex twice.
    RepeatedVertex = 8,
    /// An edge is shared by more than two faces.
    NonManifoldEdge = 9,
    /// Two faces traverse their common edge in the same direction.
    InconsistentOrientation = 10,
    /// The faces around a vertex do not form one disk or one half-disk (bow-tie vertex).
    NonManifoldVertex = 11,
    /// The same face appears twice (same or opposite orientation).
    DuplicateFace = 12,
    /// An input coordinate is NaN or infinite.
    NonFiniteInput = 14,
    /// A computed value was not finite (overflow in an intermediate); nothing was reported as
    /// success.
    NumericalFailure = 15,
    /// Coincident points or another degenerate configuration for which the rule is undefined.
    DegenerateGeometry = 16,
    /// A vertex has more neighbours than `MAX_VALENCE`, or a face more corners than
    /// `MAX_FACE_SIZE` (both 128 unless the build sets them; `nls_max_valence`,
    /// `nls_max_face_size`).
    ValenceTooHigh = 18,
    /// The scheme does not accept this face type (e.g. Loop on a quad).
    UnsupportedFaceType = 19,
    /// An output or scratch buffer is too small; the needed size is reported.
    BufferTooSmall = 20,
    /// The host's floating-point environment is not the IEEE default (flush-to-zero,
    /// denormals-are-zero or a non-default rounding mode).
    FpEnvironment = 24,
    /// An iterative solve stopped at its iteration cap above its tolerance.
    NotConverged = 25,
    /// An argument is outside its domain (unknown scheme or flag value, zero count where one
    /// is required, negative tolerance …).
    InvalidArgument = 27,
    /// Fewer points than the rule needs (e.g. a curve of one point).
    TooFewPoints = 28,
    /// The `strict` option was set and an element needed the documented linear fallback.
    FallbackInStrictMode = 29,
    /// The `strict` option was set and an edit folded the surface (differential-space
    /// editing: a face turned by more than 90° from the unedited result, or a folded edge).
    FoldedSurface = 30,
    /// A crease tag names two vertices that are not joined by an edge of the mesh.
    TagNotAnEdge = 31,
    /// The same edge or vertex is tagged twice.
    RepeatedTag = 32,
    /// A tag's sharpness is NaN, negative or infinite.
    InvalidSharpness = 33,
    /// The scheme or version does not take sharp-feature tags.
    TagsNotSupported = 34,
    /// The scheme, or its Möbius form, is not compiled into this build of the library (its
    /// Cargo feature is off; `docs/firmware.md`, "Link only what you use").
    SchemeNotBuilt = 35,
}

impl Status {
    /// Every status, in code order (private so that cbindgen does not export it).
    const LIST: [Status; 30] = [
        Status::Ok,
        Status::NullParameter,
        Status::MisalignedPointer,
        Status::SizeOverflow,
        Status::AliasingBuffers,
        Status::BadOffsets,
        Status::FaceTooSmall,
        Status::IndexOutOfRange,
        Status::RepeatedVertex,
        Status::NonManifoldEdge,
        Status::InconsistentOrientation,
        Status::NonManifoldVertex,
        Status::DuplicateFace,
        Status::NonFiniteInput,
        Status::NumericalFailure,
        Status::DegenerateGeometry,
        Status::ValenceTooHigh,
        Status::UnsupportedFaceType,
        Status::BufferTooSmall,
        Status::FpEnvironment,
        Status::NotConverged,
        Status::InvalidArgument,
        Status::TooFewPoints,
        Status::FallbackInStrictMode,
        Status::FoldedSurface,
        Status::TagNotAnEdge,
        Status::RepeatedTag,
        Status::InvalidSharpness,
        Status::TagsNotSupported,
        Status::SchemeNotBuilt,
    ];

    /// Every status, in code order.
    pub const fn all() -> &'static [Status] {
        &Status::LIST
    }

    /// The stable numeric code.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The status for a numeric code, or `None` for a code that is not assigned.
    pub fn from_code(code: u32) -> Option<Status> {
        Status::all().iter().copied().find(|s| s.code() == code)
    }

    /// A static, human-readable description (the text of `nls_status_str`).
    pub fn message(self) -> &'static str {
        self.c_message().to_str().unwrap_or("")
    }

    /// [`Status::message`] as a NUL-terminated C string, for the C ABI.
    pub const fn c_message(self) -> &'static CStr {
        match self {
            Status::Ok => c"ok",
            Status::NullParameter => c"a pointer argument is NULL while its count is not zero",
            Status::MisalignedPointer => c"a pointer argument is not aligned for its element type",
            Status::SizeOverflow => c"a size computation overflowed",
            Status::AliasingBuffers => c"input and output buffers overlap",
            Status::BadOffsets => {
                c"face offsets must start at 0, never decrease and end at the index count"
            }
            Status::FaceTooSmall => c"a face has fewer than three vertices",
            Status::IndexOutOfRange => c"a vertex index is not below the vertex count",
            Status::RepeatedVertex => c"a face uses the same vertex twice",
            Status::NonManifoldEdge => c"an edge is shared by more than two faces",
            Status::InconsistentOrientation => {
                c"two faces traverse their common edge in the same direction"
            }
            Status::NonManifoldVertex => {
                c"the faces around a vertex do not form one disk or one half-disk"
            }
            Status::DuplicateFace => c"the same face appears twice",
            Status::NonFiniteInput => c"an input coordinate is NaN or infinite",
            Status::NumericalFailure => c"a computed value is not finite",
            Status::DegenerateGeometry => {
                c"coincident points or another degenerate configuration where the rule is undefined"
            }
            Status::ValenceTooHigh => c"a vertex valence or face size exceeds the fixed capacity",
            Status::UnsupportedFaceType => c"the scheme does not accept this face type",
            Status::BufferTooSmall => c"an output or scratch buffer is too small",
            Status::FpEnvironment => {
                c"the floating-point environment is not the IEEE default (FTZ/DAZ or rounding mode)"
            }
            Status::NotConverged => c"the iterative solver did not reach its tolerance",
            Status::InvalidArgument => c"an argument is outside its domain",
            Status::TooFewPoints => c"fewer points than the rule needs",
            Status::FallbackInStrictMode => {
                c"an element needed the linear fallback and the strict option is set"
            }
            Status::FoldedSurface => c"an edit folded the surface and the strict option is set",
            Status::TagNotAnEdge => {
                c"a crease tag names two vertices that are not joined by an edge"
            }
            Status::RepeatedTag => c"the same edge or vertex is tagged twice",
            Status::InvalidSharpness => c"a tag's sharpness is NaN, negative or infinite",
            Status::TagsNotSupported => c"the scheme does not take sharp-feature tags",
            Status::SchemeNotBuilt => {
                c"the scheme or version is not compiled into this build of the library"
            }
        }
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.message())
    }
}

/// Marker for "no element" in [`Error::element`].
pub const NO_ELEMENT: u32 = u32::MAX;

/// The error of a failed call: a [`Status`], the element at fault (a vertex, face, edge or
/// point index, depending on the call; [`NO_ELEMENT`] when none applies) and, for
/// [`Status::BufferTooSmall`], the size that is needed. Built with [`Error::new`],
/// [`Error::at`] or [`Error::too_small`].
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Error {
    /// What went wrong.
    pub status: Status,
    /// The index of the element at fault, or [`NO_ELEMENT`].
    pub element: u32,
    /// For [`Status::BufferTooSmall`]: the number of elements the buffer must hold. 0 otherwise.
    pub needed: usize,
}

impl Error {
    /// An error with no element attached.
    pub const fn new(status: Status) -> Error {
        Error {
            status,
            element: NO_ELEMENT,
            needed: 0,
        }
    }

    /// An error naming the element at fault.
    pub const fn at(status: Status, element: u32) -> Error {
        Error {
            status,
            element,
            needed: 0,
        }
    }

    /// [`Status::BufferTooSmall`] with the needed size.
    pub const fn too_small(needed: usize) -> Error {
        Error {
            status: Status::BufferTooSmall,
            element: NO_ELEMENT,
            needed,
        }
    }

    /// The same error, naming `element` if none was named yet.
    pub const fn with_element(self, element: u32) -> Error {
        if self.element == NO_ELEMENT {
            Error { element, ..self }
        } else {
            self
        }
    }
}

impl From<Status> for Error {
    fn from(status: Status) -> Error {
        Error::new(status)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.status.message())?;
        if self.element != NO_ELEMENT {
            write!(f, " (element {})", self.element)?;
        }
        if self.status == Status::BufferTooSmall {
            write!(f, " (needed {})", self.needed)?;
        }
        Ok(())
    }
}

impl core::error::Error for Error {}

/// Result alias of the crate.
pub type Result<T> = core::result::Result<T, Error>;

/// The error for a broken internal invariant (an index that validation guarantees in range).
/// Never expected; returned instead of panicking. Defined here, at the bottom of the layers,
/// so that every module can use it without importing a layer above its own (`crate::mesh`
/// re-exports it for the mesh code and the drivers).
pub(crate) const fn internal() -> Error {
    Error::new(Status::InvalidArgument)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_and_are_unique() {
        for (i, s) in Status::all().iter().enumerate() {
            assert_eq!(Status::from_code(s.code()), Some(*s));
            for t in &Status::all()[i + 1..] {
                assert_ne!(s.code(), t.code());
            }
            assert!(!s.message().is_empty());
        }
        assert_eq!(Status::Ok.code(), 0);
        assert_eq!(Status::from_code(13), None);
        assert_eq!(Status::from_code(9999), None);
    }
}
