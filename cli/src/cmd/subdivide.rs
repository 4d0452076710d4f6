//! `nlsubdiv subdivide --scheme NAME --levels N [--strict] [--literal] IN OUT`: `N` levels of a linear
//! or Möbius mesh scheme of the core, or of differential-space subdivision (seed 001,
//! [`crate::differential`]), file to file.
//!
//! The output is the library's, bit for bit: the same calls a host makes (one
//! `scheme::subdivide` or `scheme::mobius::subdivide` per level), and the library's vertex
//! order (see [`crate::subdiv`]). `--levels 0` copies the input after checking it.

use std::path::PathBuf;

use super::{load, Ctx, Policy};
use crate::differential::{self, DifferentialScheme};
use crate::error::{CliResult, Exit};
use crate::io::{write_mesh, Format, WriteOptions};
use crate::subdiv::{self, MeshScheme};

/// A `--scheme` value: a mesh scheme of [`crate::subdiv`] or a differential-space one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchemeArg {
    /// Linear or Möbius.
    Mesh(MeshScheme),
    /// `differential-*`.
    Differential(DifferentialScheme),
}

fn parse_scheme(name: &str) -> Result<SchemeArg, String> {
    if let Some(d) = DifferentialScheme::from_name(name) {
        return Ok(SchemeArg::Differential(d));
    }
    MeshScheme::parse(name)
        .map(SchemeArg::Mesh)
        .map_err(|e| format!("{e}, {}", DifferentialScheme::NAMES.join(", ")))
}

/// Arguments of `subdivide`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scheme: loop, catmull-clark, butterfly, kobbelt, doo-sabin, simplest, dual,
    /// vertex-insertion, dual-truncation, or any of them as mobius-<name> (canonical Möbius
    /// subdivision, seed 000); differential-loop, differential-butterfly, differential-dirmag
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
    /// differential-dirmag: the first this many levels use DirMag (the paper: 1 or 2).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub dirmag_levels: u32,
    /// differential-*: relative residual of the reconstruction's normal equations.
    #[arg(long, value_name = "T", default_value_t = 1e-10)]
    pub tolerance: f64,
    /// differential-*: iteration cap of the reconstruction.
    #[arg(long, value_name = "N", default_value_t = 100)]
    pub max_iterations: u32,
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
    let l = load(&args.input, policy, ctx)?;
    let levels = args.levels as usize;
    let scheme = match args.scheme {
        SchemeArg::Mesh(m) => m,
        SchemeArg::Differential(d) => return run_differential(args, d, &l, ctx),
    };
    let r = subdiv::run(
        &l.mesh,
        &l.source,
        scheme,
        levels,
        args.strict,
        args.literal,
        ctx,
    )?;
    {
        let _spinner = ctx.spinner("writing");
        let opts = WriteOptions {
            ply_ascii: args.ascii,
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
    let folds = crate::folds::measure(&r.mesh).describe();
    ctx.note(&format!(
        "wrote {}: {}, {} level{}: {} → {} vertices, {} → {} faces in {:.3} s{fallbacks}{guarded}; {folds}",
        args.output.display(),
        scheme.name(),
        levels,
        if levels == 1 { "" } else { "s" },
        l.mesh.num_vertices(),
        r.mesh.num_vertices(),
        l.mesh.num_faces(),
        r.mesh.num_faces(),
        r.elapsed.as_secs_f64(),
    ));
    Ok(Exit::Ok)
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
    let o = differential::RunOptions {
        dirmag_levels: args.dirmag_levels as usize,
        tolerance: args.tolerance,
        max_iterations: args.max_iterations,
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
        "wrote {}: {}, {} level{}: {} → {} vertices, {} → {} faces in {:.3} s; reconstruction: \
         {} iterations, relative residual {:.2e}, {} anchor{}",
        args.output.display(),
        d.name(),
        levels,
        if levels == 1 { "" } else { "s" },
        l.mesh.num_vertices(),
        r.mesh.num_vertices(),
        l.mesh.num_faces(),
        r.mesh.num_faces(),
        r.elapsed.as_secs_f64(),
        r.report.solve.iterations,
        r.report.solve.relative_residual,
        r.report.anchors,
        if r.report.anchors == 1 { "" } else { "s" },
    ));
    Ok(Exit::Ok)
}
