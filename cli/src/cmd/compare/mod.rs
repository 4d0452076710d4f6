//! `nlsubdiv compare A B [--tol T] [--json]`: order-independent comparison of two meshes.
//!
//! Every vertex of A is matched to its nearest vertex of B (a k-d tree of B's distinct
//! positions, [`nearest`]; among vertices at exactly the same distance the lowest-numbered
//! one not matched yet). The meshes agree
//! when they have the same numbers of vertices, faces and corners, the largest match
//! distance divided by A's bounding-box diagonal is at most `--tol`, and the faces of A,
//! renamed through the matching, are the faces of B: each face may start at any of its
//! corners (a cyclic rotation) but keeps its orientation. Exit 0 when they agree, 1 when
//! not, 2 or 3 when a file cannot be read.
//!
//! Only the files' syntax is checked, not their topology: broken meshes can be compared.
//!
//! Scale: distances are computed on both meshes scaled by one power of two (exact) that
//! brings the largest coordinate of either into [0.5, 1): squares of differences neither
//! overflow (coordinates of 1e155 and more would make the bounding-box diagonal infinite and
//! every relative distance 0, calling different meshes equal) nor underflow (coordinates
//! near 1e-160 would make distinct points coincide). Relative distances do not depend on
//! the scale; distances are reported in the files' units (infinite when they exceed the
//! largest `f64`).

mod nearest;

use std::cmp::Ordering;
use std::path::PathBuf;

use serde_json::json;

use super::{print_json, Ctx};
use crate::error::{CliError, CliResult, Exit};
use crate::io::read_mesh;
use crate::memory;
use crate::mesh::{bbox, norm, sub, Mesh, P3};
use nearest::Nearest;

/// Arguments of `compare`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The mesh of reference.
    pub a: PathBuf,
    /// The mesh compared with it.
    pub b: PathBuf,
    /// Largest accepted vertex distance, relative to A's bounding-box diagonal.
    #[arg(long, default_value_t = 1e-12)]
    pub tol: f64,
    /// Print the result as JSON.
    #[arg(long)]
    pub json: bool,
}

/// The faces of a mesh after renaming, each rotated to start at its smallest index, sorted.
struct Faces {
    offsets: Vec<usize>,
    idx: Vec<u32>,
    order: Vec<usize>,
}

impl Faces {
    fn new(m: &Mesh, map: impl Fn(u32) -> u32) -> Faces {
        let mut offsets = vec![0];
        let mut idx = Vec::with_capacity(m.indices.len());
        for face in m.faces() {
            let renamed: Vec<u32> = face.iter().map(|&v| map(v)).collect();
            let start = (0..renamed.len()).min_by_key(|&i| renamed[i]).unwrap_or(0);
            idx.extend(renamed[start..].iter().chain(&renamed[..start]));
            offsets.push(idx.len());
        }
        let mut f = Faces {
            offsets,
            idx,
            order: Vec::new(),
        };
        let mut order: Vec<usize> = (0..m.num_faces()).collect();
        order.sort_by(|&x, &y| f.cmp(x, y));
        f.order = order;
        f
    }

    fn face(&self, f: usize) -> &[u32] {
        &self.idx[self.offsets[f]..self.offsets[f + 1]]
    }

    fn cmp(&self, x: usize, y: usize) -> Ordering {
        let (a, b) = (self.face(x), self.face(y));
        a.len().cmp(&b.len()).then_with(|| a.cmp(b))
    }
}

/// Counts the faces of `a` missing from `b` (as multisets) and names the first one.
fn face_difference(a: &Faces, b: &Faces) -> (usize, Option<usize>) {
    let (mut i, mut j) = (0, 0);
    let mut missing = 0;
    let mut first: Option<usize> = None;
    while i < a.order.len() {
        let fa = a.order[i];
        if j >= b.order.len() {
            missing += 1;
            first = Some(first.map_or(fa, |f| f.min(fa)));
            i += 1;
            continue;
        }
        let (x, y) = (a.face(fa), b.face(b.order[j]));
        match x.len().cmp(&y.len()).then_with(|| x.cmp(y)) {
            Ordering::Equal => {
                i += 1;
                j += 1;
            }
            Ordering::Less => {
                missing += 1;
                first = Some(first.map_or(fa, |f| f.min(fa)));
                i += 1;
            }
            Ordering::Greater => j += 1,
        }
    }
    (missing, first)
}

/// `2^k` for `k` in the normal exponent range.
fn pow2(k: i32) -> f64 {
    f64::from_bits(((k.clamp(-1022, 1023) + 1023) as u64) << 52)
}

/// The exponent `k` such that `2^k · max|x|` is in [0.5, 1) (0 for no or zero coordinates).
fn scale_exponent(points: &[&[P3]]) -> i32 {
    let m = points
        .iter()
        .flat_map(|p| p.iter())
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return 0;
    }
    // frexp: m = f · 2^e with f in [0.5, 1).
    let bits = m.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let e = if biased == 0 {
        // Subnormal: normalise first.
        let n = (m * pow2(64)).to_bits();
        ((n >> 52) & 0x7ff) as i32 - 1022 - 64
    } else {
        biased - 1022
    };
    -e
}

/// `points` multiplied by `2^k` (two exact steps: `2^k` itself may not be a normal number).
fn scaled(points: &[P3], k: i32) -> CliResult<Vec<P3>> {
    let (k1, k2) = (k / 2, k - k / 2);
    let (s1, s2) = (pow2(k1), pow2(k2));
    let mut out = memory::filled(points.len(), [0.0; 3], "the scaled coordinates")?;
    for (o, p) in out.iter_mut().zip(points) {
        *o = p.map(|x| x * s1 * s2);
    }
    Ok(out)
}

/// Runs `compare`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    if args.tol.is_nan() || args.tol < 0.0 {
        return Err(CliError::usage(format!(
            "--tol must be a non-negative number, not {}",
            args.tol
        )));
    }
    let spinner = ctx.spinner("reading");
    let (a, _) = read_mesh(&args.a)?;
    let (b, _) = read_mesh(&args.b)?;
    let k = scale_exponent(&[&a.positions, &b.positions]);
    let (sa, sb) = (scaled(&a.positions, k)?, scaled(&b.positions, k)?);
    let mut tree = Nearest::new(&sb);
    drop(spinner);
    let same_counts = a.num_vertices() == b.num_vertices()
        && a.num_faces() == b.num_faces()
        && a.indices.len() == b.indices.len();

    // Match every vertex of A to its nearest in B.
    let mut map = memory::filled(a.num_vertices(), u32::MAX, "the matching")?;
    let mut max_d2: f64 = 0.0;
    let mut worst: Option<(usize, u32)> = None;
    let mut progress = ctx.progress(a.num_vertices(), "matching");
    for (v, p) in sa.iter().enumerate() {
        progress.inc(1);
        let Some((d2, groups)) = tree.query(*p) else {
            break;
        };
        // The lowest-numbered vertex not matched yet among all at this distance, else the
        // lowest-numbered of them.
        let unused = groups
            .iter()
            .filter_map(|&g| {
                let gr = &tree.groups[g];
                gr.members.get(gr.used).map(|&m| (m, g))
            })
            .min();
        let pick = match unused {
            Some((m, g)) => {
                tree.groups[g].used += 1;
                m
            }
            None => groups
                .iter()
                .filter_map(|&g| tree.groups[g].members.first().copied())
                .min()
                .unwrap_or(0),
        };
        map[v] = pick;
        if d2 > max_d2 || worst.is_none() {
            max_d2 = d2.max(max_d2);
            worst = Some((v, pick));
        }
    }
    progress.finish();
    let mut hits = memory::filled(b.num_vertices(), 0u32, "the matching")?;
    for &m in &map {
        if let Some(h) = hits.get_mut(m as usize) {
            *h += 1;
        }
    }
    let one_to_one = same_counts && hits.iter().all(|&h| h == 1);
    // Back to the files' units: 2^-k, in two exact steps.
    let unscale = |x: f64| x * pow2(-(k / 2)) * pow2(-(k - k / 2));
    let scaled_distance = max_d2.sqrt();
    let scaled_diagonal = bbox(&sa).map_or(0.0, |(lo, hi)| norm(sub(hi, lo)));
    let max_distance = unscale(scaled_distance);
    let diagonal = unscale(scaled_diagonal);
    let max_relative = if scaled_diagonal > 0.0 {
        scaled_distance / scaled_diagonal
    } else {
        max_distance
    };
    let (faces_identical, missing, first_missing) = if same_counts {
        let fa = Faces::new(&a, |v| map[v as usize]);
        let fb = Faces::new(&b, |v| v);
        let (missing, first) = face_difference(&fa, &fb);
        (missing == 0, missing, first)
    } else {
        (false, a.num_faces().abs_diff(b.num_faces()), None)
    };
    let within = max_relative <= args.tol;
    let equal = same_counts && within && faces_identical;

    if args.json {
        print_json(&json!({
            "a": args.a.display().to_string(),
            "b": args.b.display().to_string(),
            "vertices": [a.num_vertices(), b.num_vertices()],
            "faces": [a.num_faces(), b.num_faces()],
            "corners": [a.indices.len(), b.indices.len()],
            "same_counts": same_counts,
            "max_distance": max_distance,
            "diagonal": diagonal,
            "max_relative": max_relative,
            "worst_vertex": worst.map(|(v, w)| json!({"a": v, "b": w})),
            "tolerance": args.tol,
            "within_tolerance": within,
            "one_to_one": one_to_one,
            "faces_identical": faces_identical,
            "faces_not_matched": missing,
            "first_face_not_matched": first_missing,
            "equal": equal,
        }))?;
    } else {
        use std::fmt::Write as _;
        let mut text = String::new();
        let o = &mut text;
        let _ = writeln!(
            o,
            "A: {} ({} vertices, {} faces, {} corners)",
            args.a.display(),
            a.num_vertices(),
            a.num_faces(),
            a.indices.len()
        );
        let _ = writeln!(
            o,
            "B: {} ({} vertices, {} faces, {} corners)",
            args.b.display(),
            b.num_vertices(),
            b.num_faces(),
            b.indices.len()
        );
        if !same_counts {
            let _ = writeln!(o, "counts differ");
        }
        if let Some((v, w)) = worst {
            let _ = writeln!(
                o,
                "largest distance {max_distance:e} = {max_relative:e} of A's diagonal \
                 ({diagonal:e}), A vertex {v} -> B vertex {w}"
            );
        }
        if same_counts && !one_to_one {
            let twice = hits.iter().filter(|&&h| h > 1).count();
            let _ = writeln!(
                o,
                "matching is not one-to-one: {twice} vertices of B are nearest to several of A"
            );
        }
        if same_counts {
            let _ = match first_missing {
                None => writeln!(
            o,"faces identical after matching ({} faces)", a.num_faces()),
                Some(f) => writeln!(
            o,
                    "{missing} faces of A have no counterpart in B (first: A face {f}: {:?} -> {:?})",
                    a.face(f),
                    a.face(f).iter().map(|&v| map[v as usize]).collect::<Vec<_>>()
                ),
            };
        }
        let _ = writeln!(
            o,
            "{} (tolerance {:e})",
            if equal { "equal" } else { "DIFFERENT" },
            args.tol
        );
        crate::out::print(&text)?;
    }
    Ok(if equal { Exit::Ok } else { Exit::Failed })
}
