//! Round trips through every format keep positions bit for bit and faces exactly: on
//! generated meshes with hard-to-print coordinates, and on every shared test mesh.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use std::path::Path;

/// OFF → OBJ → binary PLY → ASCII PLY → OFF through `nlsubdiv convert`; returns the mesh
/// read back from the final OFF by the tests' own reader.
fn chain(input: &Path, dir: &TempDir, stem: &str, extra: &[&str]) -> TMesh {
    let steps: [(&str, &[&str]); 4] = [
        ("obj", &[]),
        ("ply", &[]),
        ("ascii.ply", &["--ascii"]),
        ("back.off", &[]),
    ];
    let mut prev = input.to_path_buf();
    for (ext, flags) in steps {
        let out = dir.path(&format!("{stem}.{ext}"));
        let mut args: Vec<&std::ffi::OsStr> = vec!["convert".as_ref(), "-q".as_ref()];
        args.push(prev.as_os_str());
        args.push(out.as_os_str());
        args.extend(flags.iter().map(std::ffi::OsStr::new));
        args.extend(extra.iter().map(std::ffi::OsStr::new));
        let o = run(&args);
        assert_eq!(
            code(&o),
            0,
            "convert {} -> {}: {}",
            prev.display(),
            out.display(),
            stderr(&o)
        );
        prev = out;
    }
    read_off(&prev)
}

#[test]
fn generated_meshes_round_trip_bit_exactly() {
    let dir = TempDir::new("gen-roundtrip");
    let mut rng = Rng(7);
    let meshes = [
        ("torus", nasty(torus(9, 7, 2.0, 0.5), &mut rng)),
        ("grid", nasty(open_grid(6, 5), &mut rng)),
        ("sphere", icosphere(2)),
    ];
    for (name, m) in &meshes {
        let src = dir.path(&format!("{name}.off"));
        m.write_off(&src);
        let back = chain(&src, &dir, name, &[]);
        assert_eq!(back.faces, m.faces, "{name}: faces");
        assert_eq!(back.bits(), m.bits(), "{name}: positions");
    }
    // Writing is deterministic: the same mesh gives the same bytes.
    let a = dir.path("again.ply");
    let o = run(&[
        "convert",
        "-q",
        dir.path("torus.off").to_str().unwrap(),
        a.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert_eq!(
        std::fs::read(&a).unwrap(),
        std::fs::read(dir.path("torus.ply")).unwrap()
    );
    // Nothing but the outputs is left (no temporary files).
    assert!(
        dir.files().iter().all(|f| !f.ends_with(".tmp")),
        "{:?}",
        dir.files()
    );
}

#[test]
fn obj_relative_indices_groups_and_texture_corners() {
    let dir = TempDir::new("obj-features");
    let src = dir.path("in.obj");
    std::fs::write(
        &src,
        "# square pyramid\nmtllib none.mtl\no pyramid\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
         v 0.5 0.5 1 0.2 0.3 0.4\nvt 0 0\nvn 0 0 1\ng base\nusemtl m\n\
         f 1/1/1 4/1/1 3/1/1 2/1/1\ng sides\ns 1\nf -5//1 -4//1 -1//1\nf 2 3 5\nf 3 \\\n 4 5\nf 4 1 5\n",
    )
    .unwrap();
    let out = dir.path("out.off");
    let o = run(&["convert", src.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let m = read_off(&out);
    assert_eq!(m.positions.len(), 5);
    assert_eq!(
        m.faces,
        vec![
            vec![0, 3, 2, 1],
            vec![0, 1, 4],
            vec![1, 2, 4],
            vec![2, 3, 4],
            vec![3, 0, 4]
        ]
    );
    assert_eq!(m.positions[4], [0.5, 0.5, 1.0]);
}

#[test]
fn shared_meshes_round_trip_bit_exactly() {
    let Some(dir) = shared_meshes("cli::roundtrip::shared_meshes_round_trip_bit_exactly") else {
        return;
    };
    let files = off_files(&dir);
    assert!(
        files.len() >= 30,
        "only {} meshes in {}",
        files.len(),
        dir.display()
    );
    let tmp = TempDir::new("shared-roundtrip");
    // Two workers: the machine has two cores.
    let (left, right) = files.split_at(files.len() / 2);
    std::thread::scope(|s| {
        for part in [left, right] {
            let tmp = &tmp;
            s.spawn(move || {
                for f in part {
                    let stem = f.file_stem().unwrap().to_str().unwrap();
                    let want = read_off(f);
                    // --lenient: the teapot is non-manifold; the round trip is about I/O.
                    let back = chain(f, tmp, stem, &["--lenient"]);
                    assert_eq!(back.faces, want.faces, "{stem}: faces");
                    assert_eq!(back.bits(), want.bits(), "{stem}: positions");
                }
            });
        }
    });
    println!(
        "{} shared meshes round-tripped through OBJ, PLY and OFF",
        files.len()
    );
}
