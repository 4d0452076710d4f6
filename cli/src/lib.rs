//! The mesh files of the `nlsubdiv` command (OFF, OBJ, PLY readers and writers) and what
//! they need, as a library: the command (`src/main.rs`) uses it, and so does the `parsers`
//! fuzz target (`fuzz/fuzz_targets/parsers.rs`), which feeds the readers arbitrary bytes.
//! The command's documentation is `nlsubdiv --help` and cli/README.md.
#![forbid(unsafe_code)]

pub mod error;
pub mod io;
pub mod mesh;
