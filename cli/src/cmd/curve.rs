//! `nlsubdiv curve --scheme NAME --levels N [--closed] IN OUT`: curve subdivision of a
//! polyline given as text, one point `x y z` per line.
//!
//! Input: blank lines and everything after a `#` are ignored; every other line holds exactly
//! three finite numbers separated by white space. Errors name the file and the line.
//! Output: one point per line, each coordinate the shortest decimal that parses back to the
//! same `f64`, so the points round-trip bit for bit; a `#` comment line first says what made
//! them. The output order is the core's ([`nlsubdiv::curve`]): interleaved, the vertex point
//! of input point `i` at `2i`, the edge point after it; after `k` levels of an interpolating
//! scheme input point `i` is output point `2^k i`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use nlsubdiv::curve::{self, CurveScheme};
use nlsubdiv::{Status, NO_ELEMENT};

use super::Ctx;
use crate::error::{CliError, CliResult, Exit};
use crate::io::{fmt_f64, AtomicFile};
use crate::memory;
use crate::mesh::P3;

/// Arguments of `curve`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scheme: four-point, bspline, mobius-interpolating, mobius-approximating,
    /// circle-blend, differential (= differential-four-point), differential-bspline.
    #[arg(long, value_name = "NAME", value_parser = parse_scheme)]
    pub scheme: CurveScheme,
    /// Number of levels (0 copies the input).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=40))]
    pub levels: u32,
    /// The curve is closed: the last point joins the first.
    #[arg(long)]
    pub closed: bool,
    /// Text file of points, one `x y z` per line.
    pub input: PathBuf,
    /// Text file to write, one `x y z` per line.
    pub output: PathBuf,
}

/// The command-line names, comma-separated.
fn available() -> String {
    let mut v: Vec<&str> = CurveScheme::ALL.iter().map(|s| s.name()).collect();
    v.insert(5, "differential");
    v.join(", ")
}

fn parse_scheme(name: &str) -> Result<CurveScheme, String> {
    if let Some(s) = CurveScheme::from_name(name) {
        return Ok(s);
    }
    let why = if crate::subdiv::MeshScheme::parse(name).is_ok() {
        format!("'{name}' is a mesh scheme (use `nlsubdiv subdivide`)")
    } else {
        format!("unknown curve scheme '{name}'")
    };
    Err(format!("{why}; available: {}", available()))
}

/// Points of a curve file and the line of each.
#[derive(Debug)]
pub struct Points {
    /// The points, in file order.
    pub points: Vec<P3>,
    /// The (1-based) line of each point.
    pub lines: Vec<u32>,
}

/// Reads a curve file.
///
/// # Errors
/// Exit 3 when it cannot be read, exit 2 naming the line for anything wrong in it.
pub fn read_points(path: &Path) -> CliResult<Points> {
    let bytes = std::fs::read(path).map_err(|e| CliError::io(path, "read", &e))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        CliError::bad_input(format!(
            "{}:{line}: not UTF-8 text (a curve file holds one `x y z` per line)",
            path.display()
        ))
    })?;
    let mut out = Points {
        points: Vec::new(),
        lines: Vec::new(),
    };
    // Lines end with \n, \r\n or a lone \r.
    let text = text.replace("\r\n", "\n").replace('\r', "\n");
    for (line_no, raw) in (1u32..).zip(text.split('\n')) {
        let content = raw.split('#').next().unwrap_or("");
        let toks: Vec<&str> = content.split_whitespace().collect();
        if toks.is_empty() {
            continue;
        }
        let at = format!("{}:{line_no}: point {}", path.display(), out.points.len());
        if toks.len() != 3 {
            return Err(CliError::bad_input(format!(
                "{at}: expected 3 coordinates `x y z`, found {}",
                toks.len()
            )));
        }
        let mut p = [0.0; 3];
        for (k, (c, t)) in p.iter_mut().zip(&toks).enumerate() {
            let axis = ["x", "y", "z"][k];
            let x: f64 = t.parse().map_err(|_| {
                CliError::bad_input(format!("{at}: coordinate {axis} '{t}' is not a number"))
            })?;
            if !x.is_finite() {
                return Err(CliError::bad_input(format!(
                    "{at}: coordinate {axis} is {}",
                    if x.is_nan() { "NaN" } else { "infinite" }
                )));
            }
            *c = x;
        }
        out.points.push(p);
        out.lines.push(line_no);
    }
    Ok(out)
}

/// Writes points one per line (shortest round-trip decimals) after a comment line.
fn write_points(path: &Path, header: &str, points: &[P3]) -> CliResult<()> {
    let mut file = AtomicFile::create(path)?;
    let mut buf = String::with_capacity(64 * 1024);
    let w = file.writer();
    let mut result = writeln!(w, "# {header}");
    for chunk in points.chunks(1024) {
        if result.is_err() {
            break;
        }
        buf.clear();
        for p in chunk {
            let _ = writeln!(buf, "{} {} {}", fmt_f64(p[0]), fmt_f64(p[1]), fmt_f64(p[2]));
        }
        result = w.write_all(buf.as_bytes());
    }
    result.map_err(|e| CliError::io(path, "write", &e))?;
    file.commit()
}

/// Runs `curve`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    let started = Instant::now();
    let pts = read_points(&args.input)?;
    let n = pts.points.len();
    let file = args.input.display();
    let min = curve::min_points(args.closed);
    if n < min {
        return Err(CliError::bad_input(format!(
            "{file}: {n} point{}: {} curve needs at least {min}",
            if n == 1 { "" } else { "s" },
            if args.closed { "a closed" } else { "an open" }
        )));
    }
    let too_many = || {
        CliError::usage(format!(
            "{file}: {} levels of {n} points would overflow the point count: use fewer levels",
            args.levels
        ))
    };
    let total = curve::refined_size(n, args.closed, args.levels).map_err(|_| too_many())?;
    let scratch_size =
        curve::scratch_size(args.scheme, n, args.closed, args.levels).map_err(|_| too_many())?;
    memory::check(
        (total as u128 + scratch_size as u128) * 24 + total as u128 * 60,
        &format!("{} levels ({total} points)", args.levels),
        "use fewer levels",
    )?;
    let mut out = memory::filled(total, [0.0; 3], "the output points")?;
    let mut scratch = memory::filled(scratch_size, [0.0; 3], "the intermediate levels")?;
    let spinner = ctx.spinner("subdividing");
    let result = curve::subdivide(
        args.scheme,
        &pts.points,
        args.closed,
        args.levels,
        &mut out,
        &mut scratch,
    );
    drop(spinner);
    let written = result.map_err(|e| {
        let at = match pts.lines.get(e.element as usize) {
            Some(line) if e.element != NO_ELEMENT => {
                format!("{file}:{line}: the segment from point {}", e.element)
            }
            _ => format!("{file}"),
        };
        let why = match e.status {
            Status::DegenerateGeometry => format!(
                "{} is undefined here (coincident points, or three points without a circle \
                 through them)",
                args.scheme.name()
            ),
            Status::NumericalFailure => {
                "a computed point is not finite (coordinates too large for this rule)".into()
            }
            Status::NotConverged => "the differential reconstruction did not converge".to_string(),
            s => s.message().to_string(),
        };
        CliError::bad_input(format!("{at}: {why}"))
    })?;
    let points = out.get(..written).unwrap_or(&out);
    let header = format!(
        "nlsubdiv curve --scheme {} --levels {}{}: {written} points from {n} in {}",
        args.scheme.name(),
        args.levels,
        if args.closed { " --closed" } else { "" },
        args.input.display()
    );
    write_points(&args.output, &header, points)?;
    ctx.note(&format!(
        "wrote {}: {}, {} level{}, {}: {n} → {written} points in {:.3} s",
        args.output.display(),
        args.scheme.name(),
        args.levels,
        if args.levels == 1 { "" } else { "s" },
        if args.closed { "closed" } else { "open" },
        started.elapsed().as_secs_f64()
    ));
    Ok(Exit::Ok)
}
