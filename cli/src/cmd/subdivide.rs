//! `nlsubdiv subdivide --scheme NAME --levels N [--strict] [--literal] [--spectrum W |
//! --spectrum-weights FILE] IN OUT`: `N` levels of a linear
//! or Möbius mesh scheme of the core, or of differential-space subdivision (seed 001,
//! [`crate::differential`]), file to file.
//!
//! The output is the library's, bit for bit: the calls a host makes (`scheme::plan` and one
//! multi-level `scheme::subdivide`; on an error the levels are run again one call each so
//! that the message names the level and the element of that level's mesh), and the
//! library's vertex order (see [`crate::subdiv`]).
//! `--levels 0` copies the input after checking it.

use std::path::PathBuf;

use super::{load_for_kernel, Ctx, Policy};
use crate::differential::{self, DifferentialScheme};
use crate::error::{CliResult, Exit};
use crate::io::{write_mesh, Format, WriteOptions};
use crate::mesh::FileTags;
use crate::subdiv::{self, MeshScheme};
use nlsubdiv::scheme::CreaseMethod;

/// A `--scheme` value: a mesh scheme of [`crate::subdiv`] or a differential-space one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchemeArg {
    /// Linear or Möbius.
    Mesh(MeshScheme),
    /// `differential-*`.
    Differential(DifferentialScheme),
}

fn parse_method(name: &str) -> Result<CreaseMethod, String> {
    match name {
        "uniform" => Ok(CreaseMethod::Uniform),
        "chaikin" => Ok(CreaseMethod::Chaikin),
        _ => Err(format!(
            "unknown crease method {name:?}: uniform or chaikin"
        )),
    }
}

fn parse_weight(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(w) if (0.0..=1.0).contains(&w) => Ok(w),
        _ => Err(format!("'{s}': a weight from 0 (linear) to 1 (Möbius)")),
    }
}

fn parse_scheme(name: &str) -> Result<SchemeArg, String> {
    if let Some(d) = DifferentialScheme::from_name(name) {
        return Ok(SchemeArg::Differential(d));
    }
    // The message's list already names the differential schemes (`MeshScheme::available`).
    MeshScheme::parse(name).map(SchemeArg::Mesh)
}

/// Arguments of `subdivide`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scheme: loop, catmull-clark, butterfly, kobbelt, doo-sabin, simplest, dual,
    /// vertex-insertion, dual-truncation, or any of them as mobius-<name> (canonical Möbius
    /// subdivision, seed 000); spherelike (circle-blend interpolating subdivision, seed 003;
    /// no Möbius form); differential-loop, differential-butterfly, differential-dirmag
    /// (differential-space subdivision of triangle meshes, seed 001).
    #[arg(long, value_name = "NAME", value_parser = parse_scheme)]
    pub scheme: SchemeArg,
    /// Number of levels (0 copies the input).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=16))]
    pub levels: u32,
    /// Refuse anything the kernel would have to work around: a Möbius element that needs
    /// its linear fallback is an error naming it (by default fallbacks are counted in the
    /// summary), and warnings on the input (unreferenced vertices, zero-area faces, open
    /// cracks) refuse it.
    #[arg(long)]
    pub strict: bool,
    /// mobius-*: the paper's rules exactly, without the fold guard (by default stars with an
    /// ill-conditioned canonical form are evaluated in a form interpolated toward the
    /// linear rule, and the elements this changes are counted in the summary; docs/folds.md).
    #[arg(long)]
    pub literal: bool,
    /// mobius-*: the Möbius–linear spectrum of seed 000 §7.2, the weight W in [0, 1] of the
    /// Möbius result in each level (1, the default: Möbius; 0: the linear result, bit for
    /// bit; docs/folds.md).
    #[arg(long, value_name = "W", default_value_t = 1.0, value_parser = parse_weight)]
    pub spectrum: f64,
    /// mobius-*: per-vertex weights of the Möbius–linear spectrum from FILE, one number per
    /// input vertex and line in the mesh's vertex order (`#` starts a comment), each the
    /// weight of the Möbius result as for --spectrum, which they replace; carried to every
    /// output vertex like a vertex attribute (an edge point takes the mean of its ends, a face
    /// point the mean of its corners; docs/folds.md).
    #[arg(long, value_name = "FILE")]
    pub spectrum_weights: Option<PathBuf>,
    /// differential-dirmag: the first this many levels use DirMag (the paper: 1 or 2).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub dirmag_levels: u32,
    /// differential-*: relative residual of the reconstruction's normal equations.
    #[arg(long, value_name = "T", default_value_t = 1e-10)]
    pub tolerance: f64,
    /// differential-*: iteration cap of the reconstruction.
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub max_iterations: u32,
    /// differential-*: edits of seed 001 §4.4 from FILE, one per line: `curvature V S`
    /// (scale the mean curvature of control vertex V by S) or `normal V NX NY NZ` (the
    /// surface normal V should have in the output); `#` starts a comment. The summary counts
    /// faces the edits fold; with --strict a fold is an error.
    #[arg(long, value_name = "FILE")]
    pub edit: Option<PathBuf>,
    /// How semi-sharp creases decay from level to level: uniform (sharpness − 1 per level)
    /// or chaikin (Chaikin's rule along the crease), as OpenSubdiv.
    #[arg(long, value_name = "METHOD", default_value = "uniform", value_parser = parse_method)]
    pub crease_method: CreaseMethod,
    /// Tag every edge whose dihedral angle (between the normals of its two faces) exceeds DEG
    /// degrees as an infinitely sharp crease (loop, catmull-clark, butterfly, kobbelt),
    /// besides the OBJ file's own `t crease` / `t corner` tags.
    #[arg(long, value_name = "DEG")]
    pub crease_angle: Option<f64>,
    /// Threads of the kernel's passes (default: every core the machine offers). The output
    /// is the same bits for every count; the summary line reports the count and the
    /// kernel's subdivision time.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    /// Write PLY as ASCII instead of binary little-endian.
    #[arg(long)]
    pub ascii: bool,
    /// Mesh file to read (.off, .obj, .ply).
    pub input: PathBuf,
    /// Mesh file to write (.off, .obj, .ply).
    pub output: PathBuf,
}

/// Runs `subdivide`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    Format::from_path(&args.output)?;
    let policy = if args.strict {
        Policy::Strict
    } else {
        Policy::Default
    };
    let l = load_for_kernel(&args.input, policy, ctx)?;
    let levels = args.levels as usize;
    let mut tags = l.source.tags.clone();
    if let Some(deg) = args.crease_angle {
        if !(deg.is_finite() && (0.0..=180.0).contains(&deg)) {
            return Err(crate::error::CliError::usage(format!(
                "--crease-angle {deg}: must be a number of degrees from 0 to 180"
            )));
        }
        add_angle_creases(&l.mesh, deg, &mut tags);
    }
    if let (Some(path), SchemeArg::Mesh(_)) = (&args.edit, args.scheme) {
        return Err(crate::error::CliError::usage(format!(
            "--edit {}: edits (seed 001 §4.4) apply to the differential-* schemes",
            path.display()
        )));
    }
    let scheme = match args.scheme {
        SchemeArg::Mesh(m) => m,
        SchemeArg::Differential(_) if !tags.is_empty() => {
            return Err(crate::error::CliError::bad_input(format!(
                "{}: sharp-feature tags (t crease / t corner, --crease-angle) apply to loop, \
                 catmull-clark, butterfly and kobbelt, not to differential-space subdivision",
                args.input.display()
            )))
        }
        SchemeArg::Differential(d) => return run_differential(args, d, &l, ctx),
    };
    if args.spectrum != 1.0 && !scheme.mobius {
        return Err(crate::error::CliError::usage(format!(
            "--spectrum {}: the spectrum runs between a mobius-* scheme and its linear version; \
             {} is linear",
            args.spectrum,
            scheme.name()
        )));
    }
    let weights = match &args.spectrum_weights {
        Some(path) if !scheme.mobius => {
            return Err(crate::error::CliError::usage(format!(
                "--spectrum-weights {}: the spectrum runs between a mobius-* scheme and its \
                 linear version; {} is linear",
                path.display(),
                scheme.name()
            )))
        }
        Some(path) if args.spectrum != 1.0 => {
            return Err(crate::error::CliError::usage(format!(
                "--spectrum-weights {}: give either --spectrum or --spectrum-weights",
                path.display()
            )))
        }
        Some(path) => Some(crate::spectrum_weights::read(path, l.mesh.num_vertices())?),
        None => None,
    };
    let mode = subdiv::Mode {
        strict: args.strict,
        literal: args.literal,
        spectrum: args.spectrum,
        weights: weights.as_deref(),
        threads: args
            .threads
            .map_or_else(nlsubdiv_threads::Threads::available, |n| n as usize),
    };
    let r = if tags.is_empty() {
        subdiv::run(&l.mesh, &l.source, scheme, levels, mode, ctx)?
    } else {
        subdiv::run_tagged(
            &l.mesh,
            &l.source,
            scheme,
            levels,
            (&tags, args.crease_method),
            mode,
            ctx,
        )?
    };
    // The tags of the last level: written to an OBJ output, left out of the fold count.
    let out_tags = if tags.is_empty() {
        None
    } else {
        Some(crate::tags_out::last_level(
            &l.mesh,
            scheme.scheme,
            levels,
            &tags,
            args.crease_method,
        )?)
    };
    {
        let _spinner = ctx.spinner("writing");
        let opts = WriteOptions {
            ply_ascii: args.ascii,
            tags: out_tags.clone(),
            ..WriteOptions::default()
        };
        write_mesh(&args.output, &r.mesh, &opts)?;
    }
    let fallbacks = if !scheme.mobius {
        String::new()
    } else if let Some(first) = &r.first_fallback {
        format!(
            "; {} fallback{} to the linear rule, the first at {first}",
            r.fallbacks,
            if r.fallbacks == 1 { "" } else { "s" }
        )
    } else {
        "; 0 fallbacks".to_string()
    };
    let guarded = if !scheme.mobius {
        String::new()
    } else if let Some(first) = &r.first_guarded {
        format!(
            "; {} element{} changed by the fold guard, the first at {first}",
            r.guarded,
            if r.guarded == 1 { "" } else { "s" }
        )
    } else if args.literal {
        "; literal rules".to_string()
    } else {
        "; 0 elements changed by the fold guard".to_string()
    };
    let creases: std::collections::BTreeSet<[u32; 2]> = out_tags
        .as_ref()
        .map(|t| t.creases.iter().copied().collect())
        .unwrap_or_default();
    let mut folds = crate::folds::measure_except(&r.mesh, &creases).describe();
    if !creases.is_empty() {
        // The creases may meet at any angle by design: they are not counted.
        folds.push_str(&format!(" off the {} crease edges", creases.len()));
    }
    ctx.note(&format!(
        "wrote {}: {}, {} level{}: {} → {} vertices, {} → {} faces in {:.3} s \
         (subdivision {:.1} ms, {} thread{}){fallbacks}{guarded}; {folds}",
        args.output.display(),
        scheme.name(),
        levels,
        if levels == 1 { "" } else { "s" },
        l.mesh.num_vertices(),
        r.mesh.num_vertices(),
        l.mesh.num_faces(),
        r.mesh.num_faces(),
        r.elapsed.as_secs_f64(),
        r.kernel.as_secs_f64() * 1e3,
        r.threads,
        if r.threads == 1 { "" } else { "s" },
    ));
    Ok(Exit::Ok)
}

/// Adds an infinitely sharp crease tag (sharpness 10, OpenSubdiv's convention) for every
/// interior edge whose two faces' normals (Newell's) make an angle above `deg` degrees and
/// that the file does not tag already. Edges are visited in `(min, max)` vertex order.
fn add_angle_creases(mesh: &crate::mesh::Mesh, deg: f64, tags: &mut FileTags) {
    use std::collections::{BTreeMap, BTreeSet};
    let normal = |f: &[u32]| {
        let mut n = [0.0f64; 3];
        for (k, &a) in f.iter().enumerate() {
            let p = mesh.pos(a);
            let q = mesh.pos(f[(k + 1) % f.len()]);
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        n
    };
    let mut faces_of: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
    for (fi, f) in mesh.faces().enumerate() {
        for (k, &a) in f.iter().enumerate() {
            let b = f[(k + 1) % f.len()];
            faces_of.entry((a.min(b), a.max(b))).or_default().push(fi);
        }
    }
    let tagged: BTreeSet<(u32, u32)> = tags
        .creases
        .iter()
        .map(|&[a, b]| (a.min(b), a.max(b)))
        .collect();
    let cos_limit = deg.to_radians().cos();
    for ((a, b), fs) in faces_of {
        let [f0, f1] = fs.as_slice() else { continue };
        if tagged.contains(&(a, b)) {
            continue;
        }
        let (n0, n1) = (normal(mesh.face(*f0)), normal(mesh.face(*f1)));
        let len = |n: [f64; 3]| (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let (l0, l1) = (len(n0), len(n1));
        if l0 == 0.0 || l1 == 0.0 {
            continue;
        }
        let c = (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]) / (l0 * l1);
        if c < cos_limit {
            tags.creases.push([a, b]);
            tags.crease_sharpness.push(10.0);
        }
    }
}

/// `subdivide` with a differential-space scheme.
fn run_differential(
    args: &Args,
    d: DifferentialScheme,
    l: &super::Loaded,
    ctx: &Ctx,
) -> CliResult<Exit> {
    if !(args.tolerance.is_finite() && args.tolerance >= 0.0) {
        return Err(crate::error::CliError::usage(format!(
            "--tolerance {}: must be a finite number ≥ 0",
            args.tolerance
        )));
    }
    let levels = args.levels as usize;
    let edits = match &args.edit {
        Some(path) => Some(crate::edits::read(path, l.mesh.num_vertices())?),
        None => None,
    };
    let o = differential::RunOptions {
        dirmag_levels: args.dirmag_levels as usize,
        tolerance: args.tolerance,
        max_iterations: args.max_iterations,
        edits: edits.as_ref(),
        strict: args.strict,
        threads: args
            .threads
            .map_or_else(nlsubdiv_threads::Threads::available, |n| n as usize),
    };
    let r = differential::run(&l.mesh, &l.source, d, levels, o, ctx)?;
    {
        let _spinner = ctx.spinner("writing");
        let opts = WriteOptions {
            ply_ascii: args.ascii,
            ..WriteOptions::default()
        };
        write_mesh(&args.output, &r.mesh, &opts)?;
    }
    ctx.note(&format!(
        "wrote {}: {}, {} level{}: {} → {} vertices, {} → {} faces in {:.3} s ({} thread{}); \
         reconstruction: {} iterations, relative residual {:.2e}, {} anchor{}",
        args.output.display(),
        d.name(),
        levels,
        if levels == 1 { "" } else { "s" },
        l.mesh.num_vertices(),
        r.mesh.num_vertices(),
        l.mesh.num_faces(),
        r.mesh.num_faces(),
        r.elapsed.as_secs_f64(),
        o.threads.max(1),
        if o.threads.max(1) == 1 { "" } else { "s" },
        r.report.solve.iterations,
        r.report.solve.relative_residual,
        r.report.anchors,
        if r.report.anchors == 1 { "" } else { "s" },
    ));
    if let Some(e) = &edits {
        ctx.note(&format!(
            "edits: {} from {}; {} folded face{}, {} folded edge{}{}",
            e.count,
            args.edit
                .as_deref()
                .map_or(String::new(), |p| p.display().to_string()),
            r.report.folded_faces,
            if r.report.folded_faces == 1 { "" } else { "s" },
            r.report.folded_edges,
            if r.report.folded_edges == 1 { "" } else { "s" },
            if r.report.folded_faces > 0 || r.report.folded_edges > 0 {
                " (turned by more than 90° from the unedited result; --strict refuses them)"
            } else {
                ""
            },
        ));
    }
    Ok(Exit::Ok)
}
