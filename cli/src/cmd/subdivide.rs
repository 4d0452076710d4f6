//! `nlsubdiv subdivide --scheme NAME --levels N [--strict] IN OUT`: `N` levels of a linear
//! or Möbius mesh scheme of the core, file to file.
//!
//! The output is the library's, bit for bit: the same calls a host makes (one
//! `scheme::subdivide` or `scheme::mobius::subdivide` per level), and the library's vertex
//! order (see [`crate::subdiv`]). `--levels 0` copies the input after checking it.

use std::path::PathBuf;

use super::{load, Ctx, Policy};
use crate::error::{CliResult, Exit};
use crate::io::{write_mesh, Format, WriteOptions};
use crate::subdiv::{self, MeshScheme};

/// Arguments of `subdivide`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scheme: loop, catmull-clark, butterfly, kobbelt, doo-sabin, simplest, dual,
    /// vertex-insertion, dual-truncation, or any of them as mobius-<name> (canonical Möbius
    /// subdivision, seed 000).
    #[arg(long, value_name = "NAME", value_parser = MeshScheme::parse)]
    pub scheme: MeshScheme,
    /// Number of levels (0 copies the input).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=16))]
    pub levels: u32,
    /// Refuse anything the kernel would have to work around: a Möbius element that needs
    /// its linear fallback is an error naming it (by default fallbacks are counted in the
    /// summary), and warnings on the input (unreferenced vertices, zero-area faces, open
    /// cracks) refuse it.
    #[arg(long)]
    pub strict: bool,
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
    let r = subdiv::run(&l.mesh, &l.source, args.scheme, levels, args.strict, ctx)?;
    {
        let _spinner = ctx.spinner("writing");
        let opts = WriteOptions {
            ply_ascii: args.ascii,
            ..WriteOptions::default()
        };
        write_mesh(&args.output, &r.mesh, &opts)?;
    }
    let fallbacks = if !args.scheme.mobius {
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
    ctx.note(&format!(
        "wrote {}: {}, {} level{}: {} → {} vertices, {} → {} faces in {:.3} s{fallbacks}",
        args.output.display(),
        args.scheme.name(),
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
