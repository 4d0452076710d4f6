//! `nlsubdiv check IN [--json]`: reads a mesh and reports every defect class, with the
//! first elements of each named by file, line and index.
//!
//! Exit 0 when the mesh is clean, 1 when it has only warnings (the kernel accepts it, but
//! something is probably wrong), 2 when it has errors or is not a valid mesh file.

use std::path::PathBuf;

use serde_json::json;

use super::{describe, findings_json, load, print_json, Ctx, Policy};
use crate::error::{CliResult, Exit};
use crate::topology::{Finding, Severity};

/// Arguments of `check`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh file (.off, .obj, .ply).
    pub input: PathBuf,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `check`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    let quiet = Ctx {
        quiet: true,
        started: ctx.started,
    };
    let l = load(&args.input, Policy::Lenient, &quiet)?;
    let errors = l
        .findings
        .iter()
        .filter(|f| f.severity == Severity::Error)
        .count();
    let warnings = l.findings.len() - errors;
    let status = if errors > 0 {
        Exit::BadInput
    } else if warnings > 0 {
        Exit::Failed
    } else {
        Exit::Ok
    };
    if args.json {
        print_json(&json!({
            "file": args.input.display().to_string(),
            "vertices": l.mesh.num_vertices(),
            "faces": l.mesh.num_faces(),
            "edges": l.topo.edges.len(),
            "errors": errors,
            "warnings": warnings,
            "findings": findings_json(&l.findings),
        }))?;
    } else {
        println!(
            "{}: {} vertices, {} faces, {} edges",
            args.input.display(),
            l.mesh.num_vertices(),
            l.mesh.num_faces(),
            l.topo.edges.len()
        );
        for sev in [Severity::Error, Severity::Warning] {
            let of: Vec<&Finding> = l.findings.iter().filter(|f| f.severity == sev).collect();
            let tag = if sev == Severity::Error {
                "error"
            } else {
                "warning"
            };
            for line in describe(&of).lines() {
                println!("{tag}: {line}");
            }
        }
        println!(
            "{}",
            match status {
                Exit::Ok => "ok: no defects found".to_string(),
                Exit::Failed => format!("{warnings} kind(s) of warning; no errors"),
                _ => format!("{errors} kind(s) of error, {warnings} kind(s) of warning"),
            }
        );
    }
    Ok(status)
}
