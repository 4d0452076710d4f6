//! Fuzz target `parsers`: the command's mesh file readers (OFF, OBJ, PLY; `cli/src/io`) on
//! arbitrary bytes.
//!
//! Input layout: the first byte picks the file name the bytes are read under (`% 4`:
//! `t.off`, `t.obj`, `t.ply`, `t.txt` — a name without a mesh extension, so that the format
//! comes from the content); the rest is the file.
//!
//! Checks, on every execution (docs/bad-input-catalogue.md, rows 28 and 31):
//! - a read mesh is well formed: offsets start at 0 and increase, every face has at least 3
//!   corners, every index is below the vertex count, every coordinate is finite;
//! - written back in each of the three formats (PLY both binary and ASCII), it reads back
//!   bit for bit: the same positions (bits), offsets and indices;
//! - a refusal is exit 2 (bad input) or 4 (format unknown), and its message is one bounded
//!   text with no control character other than the line breaks between its lines: input
//!   bytes are echoed quoted and escaped, never raw, and never in full when they are long.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use nlsubdiv_cli::error::Exit;
use nlsubdiv_cli::io::{parse_mesh, write_to, Format, WriteOptions};
use nlsubdiv_cli::mesh::Mesh;

/// The longest message accepted (bytes): the quoted excerpts are bounded, and so are the
/// fixed parts around them.
const MAX_MESSAGE: usize = 2000;

fn well_formed(m: &Mesh) {
    assert_eq!(m.offsets.first(), Some(&0), "offsets must start at 0");
    for w in m.offsets.windows(2) {
        assert!(w[1] >= w[0] + 3, "a face with fewer than 3 corners: {:?}", w);
    }
    assert_eq!(
        *m.offsets.last().unwrap_or(&0) as usize,
        m.indices.len(),
        "offsets end at the corner count"
    );
    let nv = m.positions.len();
    assert!(m.indices.iter().all(|&i| (i as usize) < nv), "index out of range");
    assert!(
        m.positions.iter().flatten().all(|x| x.is_finite()),
        "non-finite coordinate read"
    );
}

fn same_bits(a: &Mesh, b: &Mesh, what: &str) {
    assert_eq!(a.offsets, b.offsets, "{what}: offsets differ after a round trip");
    assert_eq!(a.indices, b.indices, "{what}: indices differ after a round trip");
    assert_eq!(a.positions.len(), b.positions.len(), "{what}: vertex count");
    for (p, q) in a.positions.iter().zip(&b.positions) {
        for k in 0..3 {
            assert_eq!(
                p[k].to_bits(),
                q[k].to_bits(),
                "{what}: coordinate {} became {}",
                p[k],
                q[k]
            );
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let name = ["t.off", "t.obj", "t.ply", "t.txt"][usize::from(pick % 4)];
    match parse_mesh(Path::new(name), bytes) {
        Ok((mesh, _)) => {
            well_formed(&mesh);
            for (format, ascii, file) in [
                (Format::Off, false, "r.off"),
                (Format::Obj, false, "r.obj"),
                (Format::Ply, false, "r.ply"),
                (Format::Ply, true, "r.ply"),
            ] {
                let opts = WriteOptions {
                    ply_ascii: ascii,
                    ..WriteOptions::default()
                };
                let mut out = Vec::new();
                write_to(format, &mut out, &mesh, &opts).expect("writing to memory");
                let back = parse_mesh(Path::new(file), &out)
                    .unwrap_or_else(|e| panic!("{file} (ascii {ascii}) not read back: {e}"));
                same_bits(&mesh, &back.0, file);
            }
        }
        Err(e) => {
            assert!(
                matches!(e.exit, Exit::BadInput | Exit::Usage),
                "refusal with exit {:?}: {}",
                e.exit,
                e.message
            );
            assert!(e.message.len() <= MAX_MESSAGE, "a {} byte message", e.message.len());
            assert!(
                !e.message.chars().any(|c| c.is_control() && c != '\n'),
                "a control character in the message: {:?}",
                e.message
            );
        }
    }
});
