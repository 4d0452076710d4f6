//! `nlsubdiv convert IN OUT`: reads a mesh, checks it as the subdivision commands will,
//! and writes it in the format of OUT's extension, keeping vertex, face and corner order
//! and every coordinate bit for bit.

use std::path::PathBuf;

use super::{load, Ctx, Policy, PolicyArgs};
use crate::error::{CliResult, Exit};
use crate::io::{write_mesh, Format, WriteOptions};

/// Arguments of `convert`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh file to read (.off, .obj, .ply).
    pub input: PathBuf,
    /// Mesh file to write (.off, .obj, .ply).
    pub output: PathBuf,
    /// Write PLY as ASCII instead of binary little-endian.
    #[arg(long)]
    pub ascii: bool,
    #[command(flatten)]
    pub policy: PolicyArgs,
}

/// Runs `convert`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    Format::from_path(&args.output)?;
    let l = load(&args.input, args.policy.policy(Policy::Default), ctx)?;
    let opts = WriteOptions {
        ply_ascii: args.ascii,
        ..WriteOptions::default()
    };
    write_mesh(&args.output, &l.mesh, &opts)?;
    ctx.note(&format!(
        "wrote {}: {} vertices, {} faces",
        args.output.display(),
        l.mesh.num_vertices(),
        l.mesh.num_faces()
    ));
    Ok(Exit::Ok)
}
