//! The subcommands, one module each. A module has `Args` (clap) and
//! `run(&Args, &Ctx) -> CliResult<Exit>`; `main.rs` lists them once.

pub mod check;
pub mod compare;
pub mod convert;
pub mod curve;
pub mod demo;
pub mod metrics;
pub mod render;
pub mod subdivide;

use std::path::Path;
use std::time::Instant;

use crate::error::{CliError, CliResult};
use crate::io::read_mesh;
use crate::mesh::{Mesh, Source};
use crate::progress::{Progress, Spinner, Steps};
use crate::topology::{Finding, Severity, Topology};

/// What every command gets from the command line's global options.
#[derive(Debug)]
pub struct Ctx {
    /// `--quiet`: no progress bars, no warnings, no summary lines on stderr.
    pub quiet: bool,
    /// When the command started (progress bars appear after about a second).
    pub started: Instant,
}

impl Ctx {
    /// A spinner for a step without a count (dropped: gone).
    pub fn spinner(&self, message: &'static str) -> Spinner {
        Spinner::start(!self.quiet, self.started, message)
    }

    /// A progress bar over `total` steps.
    pub fn progress(&self, total: usize, message: &'static str) -> Progress {
        Progress::new(!self.quiet, self.started, total as u64, message)
    }

    /// A bar over `steps` long steps of `total` weight (see [`Steps`]).
    pub fn steps(&self, total: usize, steps: usize, message: &'static str) -> Steps {
        Steps::start(
            !self.quiet,
            self.started,
            total as u64,
            steps as u64,
            message,
        )
    }

    /// A note on stderr unless `--quiet`.
    pub fn note(&self, msg: &str) {
        if !self.quiet {
            eprintln!("{msg}");
        }
    }
}

/// What a command does with the defects `nlsubdiv check` reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Policy {
    /// Errors and warnings both refuse the mesh (`--strict`).
    Strict,
    /// Errors refuse the mesh; warnings are printed (the default of most commands).
    Default,
    /// Errors and warnings are printed and the command goes on (`--lenient`).
    Lenient,
}

/// The flags that choose a [`Policy`].
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct PolicyArgs {
    /// Go on despite topological errors (non-manifold edges or vertices, inconsistent
    /// orientation, duplicate faces, …), printing them as warnings. Files that cannot be
    /// read as a mesh (syntax, NaN, bad indices) are refused all the same.
    #[arg(long, conflicts_with = "strict")]
    pub lenient: bool,
    /// Refuse the mesh on warnings too (unreferenced vertices, zero-area faces, open
    /// cracks, sizes above the kernel's limits).
    #[arg(long)]
    pub strict: bool,
}

impl PolicyArgs {
    /// The policy, `default` when neither flag is given.
    pub fn policy(&self, default: Policy) -> Policy {
        if self.strict {
            Policy::Strict
        } else if self.lenient {
            Policy::Lenient
        } else {
            default
        }
    }
}

/// A mesh read and checked.
#[derive(Debug)]
pub struct Loaded {
    /// The mesh.
    pub mesh: Mesh,
    /// Its connectivity.
    pub topo: Topology,
    /// The defects found.
    pub findings: Vec<Finding>,
    /// Where each element came from (file, lines), for messages.
    pub source: Source,
}

/// Reads `path`, builds its topology and applies `policy` to its defects. For commands that
/// take `--lenient` (a refusal message offers it).
///
/// # Errors
/// Those of [`read_mesh`]; exit 2 when the policy refuses the mesh.
pub fn load(path: &Path, policy: Policy, ctx: &Ctx) -> CliResult<Loaded> {
    load_with(path, policy, true, ctx)
}

/// [`load`] for commands that hand the mesh to the kernel, which needs a manifold,
/// consistently oriented mesh and has no `--lenient`: a refusal says to repair the mesh.
///
/// # Errors
/// Those of [`load`].
pub fn load_for_kernel(path: &Path, policy: Policy, ctx: &Ctx) -> CliResult<Loaded> {
    load_with(path, policy, false, ctx)
}

fn load_with(path: &Path, policy: Policy, lenient_flag: bool, ctx: &Ctx) -> CliResult<Loaded> {
    let spinner = ctx.spinner("reading");
    let (mesh, source) = read_mesh(path)?;
    let topo = Topology::build(&mesh);
    let findings = topo.findings(&mesh, &source);
    drop(spinner);
    let refused = |f: &Finding| match policy {
        Policy::Strict => true,
        Policy::Default => f.severity == Severity::Error,
        Policy::Lenient => false,
    };
    let bad: Vec<&Finding> = findings.iter().filter(|f| refused(f)).collect();
    if !bad.is_empty() {
        let mut msg = describe(&bad);
        let hint = if bad.iter().any(|f| f.severity == Severity::Error) {
            if lenient_flag {
                "--lenient goes on anyway"
            } else {
                "subdivision needs a manifold, consistently oriented mesh: repair these first"
            }
        } else {
            "these are warnings: drop --strict to go on"
        };
        msg.push_str(&format!(
            "\n{}: refused ({hint}; `nlsubdiv check` lists the defects)",
            path.display()
        ));
        return Err(CliError::bad_input(msg));
    }
    if !ctx.quiet {
        let shown: Vec<&Finding> = findings.iter().collect();
        for line in describe(&shown).lines() {
            eprintln!("warning: {line}");
        }
    }
    Ok(Loaded {
        mesh,
        topo,
        findings,
        source,
    })
}

/// The findings as message lines: each example, then how many more there are.
pub fn describe(findings: &[&Finding]) -> String {
    let mut out = Vec::new();
    for f in findings {
        for e in &f.examples {
            out.push(format!("{e} [{}]", f.kind));
        }
        if f.count > f.examples.len() {
            out.push(format!(
                "… and {} more of the same kind [{}]",
                f.count - f.examples.len(),
                f.kind
            ));
        }
        if let Some(h) = &f.hint {
            out.push(format!("{h} [{}]", f.kind));
        }
    }
    out.join("\n")
}

/// Findings as JSON.
pub fn findings_json(findings: &[Finding]) -> serde_json::Value {
    serde_json::Value::Array(
        findings
            .iter()
            .map(|f| {
                serde_json::json!({
                    "severity": match f.severity { Severity::Error => "error", Severity::Warning => "warning" },
                    "kind": f.kind,
                    "count": f.count,
                    "examples": f.examples,
                    "hint": f.hint,
                })
            })
            .collect(),
    )
}

/// Prints a JSON value on stdout.
pub fn print_json(v: &serde_json::Value) -> CliResult<()> {
    let s = serde_json::to_string_pretty(v)
        .map_err(|e| CliError::internal(format!("JSON output: {e}")))?;
    crate::out::print(&format!("{s}\n"))
}
