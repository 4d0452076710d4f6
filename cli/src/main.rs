//! `nlsubdiv`: the command-line face of the nlsubdiv kernel.
//!
//! Every subcommand is one module of [`cmd`] with an `Args` struct and a
//! `run` function; adding one is writing the module and adding its line to [`Command`] and
//! to [`dispatch`]. See cli/README.md for the commands, the defect policy and exit statuses.
#![forbid(unsafe_code)]

mod cmd;
mod differential;
mod dome;
mod edits;
mod exit;
mod fields;
mod folds;
mod memory;
mod out;
mod progress;
mod spectrum_weights;
mod sphere;
mod subdiv;
mod tags_out;
mod topology;

// The file readers and writers live in the library part of this package (src/lib.rs).
use nlsubdiv_cli::{error, io, mesh};

use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand};

use cmd::Ctx;
use error::{CliResult, Exit};

const EXIT_HELP: &str = "\
Exit status:
  0  success
  1  the answer is no: `compare` found a difference, `check` found warnings
  2  bad input: not a valid mesh or curve file, a mesh with defects the command refuses, or
     one the scheme cannot subdivide (the message names the file, line and element)
  3  I/O error: a file cannot be read or written (also, without a message, when standard
     output is closed early by its reader, as in `nlsubdiv metrics --json x.off | head -1`)
  4  bad command line (including more levels than the kernel or the memory can hold)
  5  internal error (a bug: please report it with the input)

Meshes are read by their content (the PLY magic line, an OFF keyword), else by file
extension (or --input-format); they are written by file extension (or --output-format: a name
such as /dev/stdout has none). Curves are text, one \"x y z\" per line. Outputs are written to a
temporary file and renamed into place: a failed or interrupted command (SIGINT, SIGTERM,
SIGHUP, a file-size limit) leaves no output behind.";

const SUBDIVIDE_HELP: &str = "\
The output is the library's, bit for bit, in the library's vertex order (the C ABI's): old
vertices first at their indices, then edge points in edge order (edges sorted by their
(min, max) vertex pair), then face points in face order; the dual schemes (doo-sabin,
simplest, dual) number their points by corner, edge or face (docs/mesh-and-linear-schemes.md).
Loop and butterfly take triangles, kobbelt quads, the others any polygons (spherelike, seed
003: any polygons, interpolating, no Möbius form). differential-loop, differential-butterfly
and differential-dirmag (seed 001) take triangles and reconstruct once at the last level
(--tolerance, --max-iterations, --dirmag-levels).

Example: nlsubdiv subdivide --scheme mobius-catmull-clark --levels 3 cage.off smooth.ply";

const CURVE_HELP: &str = "\
Input: one point \"x y z\" per line; blank lines and text after # are ignored. Output: one
point per line, shortest decimals that read back to the same bits, interleaved as the
library writes them (vertex point of input point i at 2i, edge points between); after k
levels of an interpolating scheme input point i is output point 2^k i.

Example: nlsubdiv curve --scheme circle-blend --levels 4 --closed polygon.txt smooth.txt";

/// Nonlinear subdivision of curves and polygon meshes: tools around the nlsubdiv kernel.
#[derive(Parser, Debug)]
#[command(name = "nlsubdiv", version, after_help = EXIT_HELP, propagate_version = true)]
struct Cli {
    /// No progress bars, warnings or summary lines on stderr.
    #[arg(short, long, global = true)]
    quiet: bool,
    /// Read every input mesh in this format, whatever its name or content suggests.
    #[arg(long, global = true, value_enum, value_name = "FORMAT")]
    input_format: Option<io::Format>,
    /// Write every output mesh in this format, whatever its name (needed for names without
    /// a .off, .obj or .ply extension, such as /dev/stdout).
    #[arg(long, global = true, value_enum, value_name = "FORMAT")]
    output_format: Option<io::Format>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Subdivide a mesh N levels with a linear or Möbius scheme.
    #[command(after_help = SUBDIVIDE_HELP)]
    Subdivide(cmd::subdivide::Args),
    /// Subdivide a curve (text, one "x y z" per line) N levels.
    #[command(after_help = CURVE_HELP)]
    Curve(cmd::curve::Args),
    /// The main job on a bundled dome-like cage: Möbius Catmull–Clark, a mesh and a picture.
    Demo(cmd::demo::Args),
    /// Check a mesh: every defect, with the file, line and element of the first ones.
    Check(cmd::check::Args),
    /// Convert a mesh between OFF, OBJ and PLY, bit-exact, keeping the order of everything.
    Convert(cmd::convert::Args),
    /// Compare two meshes independently of vertex and face order.
    Compare(cmd::compare::Args),
    /// Measure a mesh: counts, edge lengths, Willmore energy, Möbius regularity, sphere fit.
    Metrics(cmd::metrics::Args),
    /// Draw a picture of a mesh into a PNG file.
    Render(cmd::render::Args),
}

fn dispatch(command: &Command, ctx: &Ctx) -> CliResult<Exit> {
    match command {
        Command::Subdivide(a) => cmd::subdivide::run(a, ctx),
        Command::Curve(a) => cmd::curve::run(a, ctx),
        Command::Demo(a) => cmd::demo::run(a, ctx),
        Command::Check(a) => cmd::check::run(a, ctx),
        Command::Convert(a) => cmd::convert::run(a, ctx),
        Command::Compare(a) => cmd::compare::run(a, ctx),
        Command::Metrics(a) => cmd::metrics::run(a, ctx),
        Command::Render(a) => cmd::render::run(a, ctx),
    }
}

fn main() -> ExitCode {
    let started = Instant::now();
    exit::install_handlers();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() {
                Exit::Usage as u8
            } else {
                Exit::Ok as u8
            });
        }
    };
    io::set_format_options(cli.input_format, cli.output_format);
    let ctx = Ctx {
        quiet: cli.quiet,
        started,
    };
    match dispatch(&cli.command, &ctx) {
        Ok(code) => ExitCode::from(code as u8),
        Err(e) => {
            exit::print_error(&e.message);
            ExitCode::from(e.exit as u8)
        }
    }
}
