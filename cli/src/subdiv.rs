//! Several levels of one of the core's mesh schemes, linear or Möbius, on the command's
//! [`Mesh`]: sizes planned before anything is computed, one core call per level (exactly
//! the calls a C or Rust host makes, so the output is the library's bit for bit), progress,
//! and errors that name the file, the level and the element at fault.
//!
//! Output vertex order is the library's ([`nlsubdiv::mesh::refine`]): primal schemes keep
//! the old vertices first at their indices, then edge points in edge order (edges sorted by
//! their `(min, max)` vertex pair), then face points in face order; the dual schemes number
//! their points by corner, edge or face as that table says.

use std::time::{Duration, Instant};

use nlsubdiv::mesh::refine::Pattern;
use nlsubdiv::mesh::{Mesh as CoreMesh, MeshOut, MeshSizes, Topology as CoreTopology};
use nlsubdiv::scheme::{self, Options, Scheme, Scratch, ScratchSizes, MAX_LEVELS};
use nlsubdiv::{Error, Status, MAX_FACE_SIZE, MAX_VALENCE, NO_ELEMENT};

use crate::cmd::Ctx;
use crate::error::{CliError, CliResult};
use crate::memory;
use crate::mesh::{Mesh, Source};

/// A mesh scheme of the command line: one of the core's [`Scheme`]s, linear or in its
/// canonical Möbius form (seed 000 §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshScheme {
    /// The underlying scheme.
    pub scheme: Scheme,
    /// The Möbius driver (`mobius-<name>`) instead of the linear one.
    pub mobius: bool,
}

/// The differential-space names (seed 001), run by `cli/src/differential.rs`, not by
/// [`MeshScheme`]; listed so that every "available" message names them.
const DIFFERENTIAL: [&str; 3] = crate::differential::DifferentialScheme::NAMES;

impl MeshScheme {
    /// The command-line name: the core's name, with `mobius-` in front for the Möbius form.
    pub fn name(self) -> String {
        if self.mobius {
            format!("mobius-{}", self.scheme.name())
        } else {
            self.scheme.name().to_string()
        }
    }

    /// Every scheme: the linear ones (and `spherelike`) in code order, then the Möbius forms
    /// of those that have one ([`Scheme::has_mobius_form`]).
    pub fn all() -> impl Iterator<Item = MeshScheme> {
        [false, true].into_iter().flat_map(|mobius| {
            Scheme::ALL
                .iter()
                .filter(move |s| !mobius || s.has_mobius_form())
                .map(move |&scheme| MeshScheme { scheme, mobius })
        })
    }

    /// The names of [`MeshScheme::all`], comma-separated.
    pub fn available() -> String {
        MeshScheme::all()
            .map(MeshScheme::name)
            .chain(DIFFERENTIAL.iter().map(|s| s.to_string()))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Parses a command-line name; the message of an error lists the available names.
    ///
    /// # Errors
    /// A message for unknown names and for the names this version does not implement.
    pub fn parse(name: &str) -> Result<MeshScheme, String> {
        let (base, mobius) = match name.strip_prefix("mobius-") {
            Some(rest) => (rest, true),
            None => (name, false),
        };
        let why = match Scheme::from_name(base) {
            Some(scheme) if !mobius || scheme.has_mobius_form() => {
                return Ok(MeshScheme { scheme, mobius });
            }
            Some(_) => {
                format!("'{base}' has no Möbius form (its circle rules keep circles already)")
            }
            None => String::new(),
        };
        let why = if !why.is_empty() {
            why
        } else if nlsubdiv::curve::CurveScheme::from_name(name).is_some() {
            format!("'{name}' is a curve scheme (use `nlsubdiv curve`)")
        } else {
            format!("unknown mesh scheme '{name}'")
        };
        Err(format!("{why}; available: {}", MeshScheme::available()))
    }
}

/// The result of [`run`].
#[derive(Debug)]
pub struct Outcome {
    /// The last level.
    pub mesh: Mesh,
    /// Elements that took their linear rule, over all levels (Möbius schemes).
    pub fallbacks: u64,
    /// The first fallback: a description naming the level and the element.
    pub first_fallback: Option<String>,
    /// Elements the fold guard changed, over all levels (Möbius schemes without
    /// `--literal`; `docs/folds.md`).
    pub guarded: u64,
    /// The first of them: a description naming the level and the element.
    pub first_guarded: Option<String>,
    /// Time spent in the core (planning and every level).
    pub elapsed: Duration,
    /// Time of the kernel's subdivision call alone (every level; no planning, allocation or
    /// file I/O).
    pub kernel: Duration,
    /// The threads that call ran on.
    pub threads: usize,
}

/// Names the elements of the input of one step: the file's (level 0, with lines) or an
/// intermediate level's.
struct Namer<'a> {
    src: &'a Source,
    level: usize,
}

impl Namer<'_> {
    fn file(&self) -> String {
        self.src.path.display().to_string()
    }

    fn line(l: Option<u32>) -> String {
        l.map(|l| format!(" (line {l})")).unwrap_or_default()
    }

    /// `vertex 3 (line 7)` or `vertex 3 of level 2`.
    fn vertex(&self, v: u32) -> String {
        if self.level == 0 {
            format!("vertex {v}{}", Self::line(self.src.vertex_line(v as usize)))
        } else {
            format!("vertex {v} of level {}", self.level)
        }
    }

    /// `face 3 (line 12)` or `face 3 of level 2`.
    fn face(&self, f: u32) -> String {
        if self.level == 0 {
            format!("face {f}{}", Self::line(self.src.face_line(f as usize)))
        } else {
            format!("face {f} of level {}", self.level)
        }
    }

    /// `path:line: face f` for level 0, `path: level 2: face f` otherwise.
    fn at_face(&self, f: u32) -> String {
        if self.level == 0 {
            self.src.at_face(f as usize)
        } else {
            format!("{}: {}", self.file(), self.face(f))
        }
    }

    fn at_vertex(&self, v: u32) -> String {
        if self.level == 0 {
            self.src.at_vertex(v as usize)
        } else {
            format!("{}: {}", self.file(), self.vertex(v))
        }
    }
}

/// The `k`-th vertex (in index order) among those where `pick` holds.
fn nth_vertex(topo: &CoreTopology<'_, '_>, k: usize, pick: impl Fn(u32) -> bool) -> Option<u32> {
    (0..topo.num_vertices() as u32).filter(|&v| pick(v)).nth(k)
}

/// What output vertex `i` of one step of `pattern` on `topo` is, in words (the numbering of
/// [`nlsubdiv::mesh::refine`]).
fn describe_output_vertex(
    pattern: Pattern,
    topo: &CoreTopology<'_, '_>,
    i: u32,
    n: &Namer<'_>,
) -> String {
    let (nv, ne, nf, nh) = (
        topo.num_vertices(),
        topo.num_edges(),
        topo.num_faces(),
        topo.num_half_edges(),
    );
    let i = i as usize;
    let edge = |e: usize| match topo.edge_vertices(e as u32) {
        Ok((a, b)) => format!(
            "the edge point of the edge between {} and {}",
            n.vertex(a),
            n.vertex(b)
        ),
        Err(_) => format!("the edge point of edge {e}"),
    };
    let face = |f: usize| format!("the face point of {}", n.face(f as u32));
    let old = |v: usize| format!("the new position of {}", n.vertex(v as u32));
    let isolated = |k: usize| match nth_vertex(topo, k, |v| topo.is_isolated(v) == Ok(true)) {
        Some(v) => format!("{} (unreferenced, carried through)", n.vertex(v)),
        None => "an unreferenced vertex".to_string(),
    };
    let boundary = |k: usize| nth_vertex(topo, k, |v| topo.is_boundary_vertex(v) == Ok(true));
    let nb = topo.num_boundary_vertices();
    match pattern {
        Pattern::Split1To4 if i < nv => old(i),
        Pattern::Split1To4 => edge(i - nv),
        Pattern::Quads if i < nv => old(i),
        Pattern::Quads if i < nv + ne => edge(i - nv),
        Pattern::Quads => face(i - nv - ne),
        Pattern::VertexInsertion | Pattern::DualTruncation if i < nv => old(i),
        Pattern::VertexInsertion | Pattern::DualTruncation => face(i - nv),
        Pattern::CornerCut if i < nh => match (topo.origin(i as u32), topo.face(i as u32)) {
            (Ok(v), Ok(f)) => format!("the corner point of {} in {}", n.vertex(v), n.face(f)),
            _ => format!("the corner point of corner {i}"),
        },
        Pattern::CornerCut => isolated(i - nh),
        Pattern::MidEdge if i < ne => edge(i),
        Pattern::MidEdge if i < ne + nb => match boundary(i - ne) {
            Some(v) => format!("the boundary point of {}", n.vertex(v)),
            None => format!("boundary point {}", i - ne),
        },
        Pattern::MidEdge => isolated(i - ne - nb),
        Pattern::Dual if i < nf => face(i),
        Pattern::Dual if i < nf + nb => match boundary(i - nf) {
            Some(v) => format!("the midpoint of the boundary edge leaving {}", n.vertex(v)),
            None => format!("boundary edge point {}", i - nf),
        },
        Pattern::Dual if i < nf + 2 * nb => match boundary(i - nf - nb) {
            Some(v) => format!("the boundary point of {}", n.vertex(v)),
            None => format!("boundary point {}", i - nf - nb),
        },
        Pattern::Dual => isolated(i - nf - 2 * nb),
        // A pattern of a later core version.
        _ => format!("output vertex {i}"),
    }
}

/// The hint for a face the scheme does not take.
const ANY_POLYGONS: &str = "catmull-clark, doo-sabin, simplest, dual, vertex-insertion and \
     dual-truncation take any polygons";

/// Where a core call failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    /// Validation and topology ([`CoreTopology::build`]).
    Build,
    /// The step itself (sizes, connectivity, positions).
    Step,
}

/// The message and exit status of a core error in step `level + 1` (input: level `level`).
fn core_error(
    e: Error,
    stage: Stage,
    ms: MeshScheme,
    topo: Option<&CoreTopology<'_, '_>>,
    mesh: &CoreMesh<'_>,
    n: &Namer<'_>,
) -> CliError {
    let el = e.element;
    let step = n.level + 1;
    let bad = |msg: String| CliError::bad_input(msg);
    let face_size = |f: u32| mesh.face(f as usize).map_or(0, <[u32]>::len);
    match (stage, e.status) {
        (Stage::Step, Status::UnsupportedFaceType) if el != NO_ELEMENT => {
            let size = face_size(el);
            let why = match ms.scheme {
                Scheme::Loop | Scheme::ModifiedButterfly => format!(
                    "has {size} corners; {} needs triangles ({ANY_POLYGONS})",
                    ms.name()
                ),
                Scheme::Kobbelt => format!(
                    "has {size} corners; {} needs quads ({ANY_POLYGONS})",
                    ms.name()
                ),
                _ => format!(
                    "shares two edges with one neighbouring face; {} would make a double edge",
                    ms.name()
                ),
            };
            bad(format!("{}: {why}", n.at_face(el)))
        }
        (Stage::Step, Status::FaceTooSmall) if el != NO_ELEMENT => bad(format!(
            "{}: an interior vertex of valence 2: its face in {} would be a 2-gon",
            n.at_vertex(el),
            ms.name()
        )),
        (_, Status::ValenceTooHigh) if el != NO_ELEMENT => {
            let is_face = (stage == Stage::Build && face_size(el) > MAX_FACE_SIZE)
                || (stage == Stage::Step
                    && ms.scheme == Scheme::DualTruncation
                    && el as usize >= mesh.num_vertices());
            let at = if is_face {
                n.at_face(el)
            } else {
                n.at_vertex(el)
            };
            if stage == Stage::Build {
                let what = if is_face { "corners" } else { "neighbours" };
                bad(format!(
                    "{at}: more {what} than the kernel's limit of {MAX_VALENCE}"
                ))
            } else {
                bad(format!(
                    "{at}: step {step} of {} would need a vertex of valence (or a face of \
                     size) above the kernel's {MAX_VALENCE}",
                    ms.name()
                ))
            }
        }
        (
            Stage::Step,
            Status::FallbackInStrictMode | Status::NumericalFailure | Status::DegenerateGeometry,
        ) => {
            let what = match topo {
                Some(t) if el != NO_ELEMENT => {
                    describe_output_vertex(ms.scheme.pattern(), t, el, n)
                }
                _ => "an element".to_string(),
            };
            let why = if e.status == Status::FallbackInStrictMode {
                "needed the linear fallback (a degenerate neighbourhood: coincident points, a \
                 star without a canonical form, a blend at infinity, or a face whose corners \
                 are all ears, boundary vertices of one face), or the fold guard changed it (a \
                 star with an ill-conditioned canonical form; --literal runs the paper's \
                 rules), and --strict is set"
                    .to_string()
            } else if e.status == Status::DegenerateGeometry {
                "has no circle through its points (coincident vertices or a spike; the \
                 spherelike rule has no fallback)"
                    .to_string()
            } else {
                "is not finite (the coordinates are too large for this rule)".to_string()
            };
            bad(format!(
                "{}: step {step} of {}, output vertex {el} ({what}) {why}",
                n.file(),
                ms.name()
            ))
        }
        (Stage::Build, s) if el != NO_ELEMENT => {
            let at = match s {
                Status::NonManifoldVertex | Status::NonFiniteInput => n.at_vertex(el),
                _ => n.at_face(el),
            };
            bad(format!("{at}: {}", s.message()))
        }
        (_, Status::SizeOverflow) => CliError::usage(format!(
            "{}: step {step} of {} would exceed the kernel's 32-bit indices: use fewer levels",
            n.file(),
            ms.name()
        )),
        (_, Status::BufferTooSmall | Status::InvalidArgument) => CliError::internal(format!(
            "{}: step {step} of {}: the kernel reported '{e}' (a bug: please report it with the \
             input)",
            n.file(),
            ms.name()
        )),
        (_, s) => bad(format!(
            "{}: step {step} of {}: {}",
            n.file(),
            ms.name(),
            if el == NO_ELEMENT {
                s.message().to_string()
            } else {
                format!("{} (element {el})", s.message())
            }
        )),
    }
}

/// [`describe_output_vertex`] for output vertex `i` of one step of `ms` on `mesh` (a
/// fallback or an element the fold guard changed), with `mesh`'s topology built here.
fn describe_fallback(ms: MeshScheme, mesh: CoreMesh<'_>, i: u32, n: &Namer<'_>) -> String {
    let topology = scheme::plan_scratch_size(&mesh)
        .ok()
        .and_then(|len| memory::filled(len, 0u32, "the topology").ok());
    match topology {
        Some(mut scratch) => match CoreTopology::build(mesh, &mut scratch) {
            Ok(topo) => describe_output_vertex(ms.scheme.pattern(), &topo, i, n),
            Err(_) => "an element".to_string(),
        },
        None => "an element".to_string(),
    }
}

/// The message of a failed core call (`plan` or `subdivide`) on `mesh`, the input of step
/// `n.level + 1`: a validation error names the element of `mesh`; any other error is the
/// step's, described with `mesh`'s topology (built here, on the error path only).
/// The output vertex `i` of step `level` of a multi-level call, for a report: elements of
/// level 1 are described by the input's elements (file lines), later ones by their index.
fn describe_step_vertex(
    ms: MeshScheme,
    mesh0: CoreMesh<'_>,
    n0: &Namer<'_>,
    level: u32,
    i: u32,
) -> String {
    let what = if level == 1 {
        describe_fallback(ms, mesh0, i, n0)
    } else {
        format!("an element of level {}", level - 1)
    };
    format!("step {level}, output vertex {i} ({what})")
}

fn call_error(e: Error, ms: MeshScheme, mesh: CoreMesh<'_>, n: &Namer<'_>) -> CliError {
    let Some(mut scratch) = scheme::plan_scratch_size(&mesh)
        .ok()
        .and_then(|len| memory::filled(len, 0u32, "the topology").ok())
    else {
        return core_error(e, Stage::Build, ms, None, &mesh, n);
    };
    match CoreTopology::build(mesh, &mut scratch) {
        Err(_) => core_error(e, Stage::Build, ms, None, &mesh, n),
        Ok(topo) => core_error(e, Stage::Step, ms, Some(&topo), &mesh, n),
    }
}

/// The sizes of every level, with a message naming the first level that cannot be made.
fn plan_sizes(
    ms: MeshScheme,
    mesh: CoreMesh<'_>,
    levels: usize,
    n: &Namer<'_>,
) -> CliResult<(Vec<MeshSizes>, ScratchSizes)> {
    let mut scratch = memory::filled(
        scheme::plan_scratch_size(&mesh).unwrap_or(0),
        0u32,
        "the topology",
    )?;
    let opts = |levels: usize| Options::new(ms.scheme).mobius(ms.mobius).levels(levels);
    match scheme::plan(mesh, &opts(levels), &mut scratch) {
        Ok(p) => Ok((
            p.sizes
                .get(..=levels)
                .map(<[MeshSizes]>::to_vec)
                .unwrap_or_default(),
            p.scratch,
        )),
        Err(e)
            if e.element == NO_ELEMENT
                && matches!(e.status, Status::ValenceTooHigh | Status::SizeOverflow) =>
        {
            // Find the first level that fails (each plan is cheap: counts only).
            let first = (1..=levels)
                .find(|&k| scheme::plan(mesh, &opts(k), &mut scratch).is_err())
                .unwrap_or(levels);
            let why = if e.status == Status::ValenceTooHigh {
                format!("would have a vertex of valence (or a face of size) above the kernel's {MAX_VALENCE}")
            } else {
                "would exceed the kernel's 32-bit indices".to_string()
            };
            Err(CliError::usage(format!(
                "{}: level {first} of {} {why}: use at most {} levels",
                n.file(),
                ms.name(),
                first - 1
            )))
        }
        Err(e) => Err(CliError::internal(format!(
            "{}: planning {} levels of {}: {e}",
            n.file(),
            levels,
            ms.name()
        ))),
    }
}

/// An output mesh of `sizes` (zeroed), its allocations checked.
fn output_mesh(sizes: MeshSizes) -> CliResult<Mesh> {
    Ok(Mesh {
        positions: memory::filled(sizes.vertices, [0.0; 3], "the output positions")?,
        offsets: memory::filled(sizes.faces + 1, 0u32, "the output faces")?,
        indices: memory::filled(sizes.indices, 0u32, "the output faces")?,
    })
}

/// How `run` treats the Möbius schemes' special elements.
#[derive(Clone, Copy, Debug)]
pub struct Mode<'a> {
    /// A Möbius fallback or an element the fold guard changes is an error naming it.
    pub strict: bool,
    /// The paper's Möbius rules without the fold guard (`Options::literal`).
    pub literal: bool,
    /// The weight of the Möbius result in the Möbius–linear spectrum (`Options::spectrum`).
    pub spectrum: f64,
    /// Per input vertex, the weight of the Möbius result (`VertexWeights::Mobius`, replacing
    /// `spectrum`); `None` for the global weight.
    pub weights: Option<&'a [f64]>,
    /// Threads of the kernel's passes (`nlsubdiv_threads`; the output is the same bits for
    /// every count).
    pub threads: usize,
}

impl Mode<'_> {
    /// Not strict, the fold guard on, the Möbius result, one thread.
    pub const DEFAULT: Mode<'static> = Mode {
        strict: false,
        literal: false,
        spectrum: 1.0,
        weights: None,
        threads: 1,
    };
}

/// Runs `levels` steps of `ms` on `input` (read from `src`). `mode.strict`: a Möbius fallback (or
/// an element the fold guard changes) is an error naming the element. `mode.literal`: the paper's
/// Möbius rules without the fold guard (`Options::literal`). `mode.spectrum`: the weight of the
/// Möbius result in the Möbius–linear spectrum (`Options::spectrum`; 1 for the Möbius
/// result); `mode.weights`: per-vertex weights replacing it (`scheme::subdivide_weighted`,
/// one multi-level call that carries them). Level 0 returns a copy.
///
/// # Errors
/// Exit 2 for meshes the scheme refuses (naming the file, the level and the element), exit 4
/// when the levels ask for more than the kernel or the machine can hold, exit 5 for a bug.
pub fn run(
    input: &Mesh,
    src: &Source,
    ms: MeshScheme,
    levels: usize,
    mode: Mode<'_>,
    ctx: &Ctx,
) -> CliResult<Outcome> {
    let Mode {
        strict,
        literal,
        spectrum,
        weights,
        threads,
    } = mode;
    let started = Instant::now();
    if levels > MAX_LEVELS {
        return Err(CliError::usage(format!(
            "--levels {levels}: at most {MAX_LEVELS}"
        )));
    }
    let mesh0 = CoreMesh::new(&input.positions, &input.offsets, &input.indices);
    let n0 = Namer { src, level: 0 };
    // Validation and the first step's requirements, with the file's elements named.
    {
        let len = scheme::plan_scratch_size(&mesh0)
            .map_err(|e| core_error(e, Stage::Build, ms, None, &mesh0, &n0))?;
        let mut scratch = memory::filled(len, 0u32, "the topology")?;
        let first = Options::new(ms.scheme).levels(levels.min(1));
        scheme::plan(mesh0, &first, &mut scratch).map_err(|e| call_error(e, ms, mesh0, &n0))?;
    }
    let (sizes, scratch_sizes) = plan_sizes(ms, mesh0, levels, &n0)?;
    // Peak memory, from the library's own plan: the input, the output and the scratch of the
    // multi-level call (its topologies, intermediate levels and Möbius candidates). The
    // level-by-level run below holds two levels and one level's scratch at a time, which
    // that scratch covers.
    let mesh_bytes = |s: MeshSizes| 24 * s.vertices as u128 + 4 * (s.faces + 1 + s.indices) as u128;
    let peak = mesh_bytes(sizes.first().copied().unwrap_or_default())
        + mesh_bytes(sizes.last().copied().unwrap_or_default())
        + 4 * scratch_sizes.u32s as u128
        + 24 * scratch_sizes.points as u128;
    memory::check(
        peak,
        &format!("{levels} levels of {}", ms.name()),
        "use fewer levels",
    )?;

    let opts = Options::new(ms.scheme)
        .mobius(ms.mobius)
        .strict(strict)
        .literal(literal)
        .spectrum(spectrum);
    // One multi-level call of the library, as a host makes it: the child topologies are
    // derived level to level, the intermediate levels live in the scratch. An error is
    // diagnosed afterwards by running the levels one call each, so that the message names
    // the level and the element of that level's mesh (the error path only).
    let all = opts.levels(levels);
    let no_tags = scheme::Tags::new();
    let weights = weights.map(scheme::VertexWeights::Mobius);
    let plan = {
        let len = scheme::plan_scratch_size(&mesh0)
            .map_err(|e| core_error(e, Stage::Build, ms, None, &mesh0, &n0))?;
        let mut scratch = memory::filled(len, 0u32, "the topology")?;
        scheme::plan_weighted(mesh0, &all, &no_tags, weights, &mut scratch)
            .map_err(|e| call_error(e, ms, mesh0, &n0))?
    };
    let out_sizes = plan.output();
    let mut u32s = memory::filled(plan.scratch.u32s, 0u32, "the topologies")?;
    let mut points = memory::filled(plan.scratch.points, [0.0; 3], "the intermediate levels")?;
    let mut next = output_mesh(out_sizes)?;
    let spinner = ctx.spinner("subdividing");
    let kernel_started = Instant::now();
    let result = {
        let mut out = MeshOut::new(&mut next.positions, &mut next.offsets, &mut next.indices);
        let scratch = Scratch::new(&mut u32s, &mut points);
        match weights {
            None => nlsubdiv_threads::subdivide(mesh0, &all, scratch, &mut out, threads),
            Some(_) => {
                let exec = nlsubdiv_threads::Threads::new(threads);
                scheme::subdivide_weighted(mesh0, &all, &no_tags, weights, scratch, &mut out, &exec)
            }
        }
    };
    let kernel = kernel_started.elapsed();
    drop(spinner);
    drop((u32s, points));
    let report = match result {
        Ok(report) => report,
        Err(e) if weights.is_some() && levels > 1 => {
            // The weights of the later levels live inside the call: its levels cannot be
            // run one call each. The error names an element of the level it gives.
            return Err(CliError::bad_input(format!(
                "{}: {} levels of {} with spectrum weights: {e}",
                n0.file(),
                levels,
                ms.name()
            )));
        }
        Err(e) if weights.is_some() => return Err(call_error(e, ms, mesh0, &n0)),
        Err(e) => {
            drop(next);
            let by_levels = run_by_levels(input, src, ms, &sizes, opts, ctx);
            return Err(match by_levels {
                Err(diagnosed) => diagnosed,
                // Not reproduced one level at a time: report the call's own error.
                Ok(_) => call_error(e, ms, mesh0, &n0),
            });
        }
    };
    if report.sizes != out_sizes {
        return Err(CliError::internal(format!(
            "{} levels of {}: wrote {:?}, planned {out_sizes:?}",
            levels,
            ms.name(),
            report.sizes
        )));
    }
    // Elements of level 1 are described by the input's elements (file lines); later levels
    // by their index.
    let describe = |level: u32, i: u32| describe_step_vertex(ms, mesh0, &n0, level, i);
    Ok(Outcome {
        mesh: next,
        fallbacks: u64::from(report.fallbacks),
        first_fallback: (report.fallbacks > 0)
            .then(|| describe(report.first_fallback_level, report.first_fallback)),
        guarded: u64::from(report.guarded),
        first_guarded: (report.guarded > 0)
            .then(|| describe(report.first_guarded_level, report.first_guarded)),
        elapsed: started.elapsed(),
        kernel,
        threads: threads.max(1),
    })
}

/// The levels one call each, for diagnosing an error of the multi-level call: the failing
/// level's error names the element of that level's mesh. Returns the result as `run` would
/// have (`Ok` when no level fails).
fn run_by_levels(
    input: &Mesh,
    src: &Source,
    ms: MeshScheme,
    sizes: &[MeshSizes],
    opts: Options,
    ctx: &Ctx,
) -> CliResult<Mesh> {
    let levels = sizes.len().saturating_sub(1);
    let total: usize = sizes.iter().skip(1).map(|s| s.vertices).sum();
    let progress = ctx.steps(total, levels, "level");
    let mut current = input.clone();
    for level in 0..levels {
        let out_sizes = sizes.get(level + 1).copied().unwrap_or_default();
        let namer = Namer { src, level };
        let mesh = CoreMesh::new(&current.positions, &current.offsets, &current.indices);
        let len = scheme::plan_scratch_size(&mesh)
            .map_err(|e| core_error(e, Stage::Build, ms, None, &mesh, &namer))?;
        let mut scratch = memory::filled(len, 0u32, "the topology")?;
        let plan =
            scheme::plan(mesh, &opts, &mut scratch).map_err(|e| call_error(e, ms, mesh, &namer))?;
        let mut scratch = memory::filled(plan.scratch.u32s, 0u32, "the topology")?;
        let mut points = memory::filled(plan.scratch.points, [0.0; 3], "the Möbius candidates")?;
        let mut next = output_mesh(out_sizes)?;
        let mut out = MeshOut::new(&mut next.positions, &mut next.offsets, &mut next.indices);
        let report = scheme::subdivide(
            mesh,
            &opts,
            Scratch::new(&mut scratch, &mut points),
            &mut out,
        )
        .map_err(|e| call_error(e, ms, mesh, &namer))?;
        let written = report.sizes;
        if written != out_sizes {
            return Err(CliError::internal(format!(
                "step {} of {}: wrote {written:?}, planned {out_sizes:?}",
                level + 1,
                ms.name()
            )));
        }
        progress.step_done(out_sizes.vertices as u64);
        current = next;
    }
    drop(progress);
    Ok(current)
}

/// [`run`] for a mesh with sharp-feature tags: every level in one core call
/// (`scheme::subdivide_tagged`), which carries the tags to the child edges and vertices from
/// level to level (one call per level would lose them). Loop, Catmull–Clark, Modified
/// Butterfly and Kobbelt, linear or Möbius (with `mode`'s strict, literal and spectrum; the
/// tagged call runs on the calling thread); the kernel refuses the others with a status
/// this names.
///
/// # Errors
/// Those of [`run`]; exit 2 for a tag the kernel refuses, naming the file and the line of the
/// tag (`src.tags` holds the lines; tags added by `--crease-angle` have none).
pub fn run_tagged(
    input: &Mesh,
    src: &Source,
    ms: MeshScheme,
    levels: usize,
    (tags, method): (&crate::mesh::FileTags, scheme::CreaseMethod),
    mode: Mode<'_>,
    ctx: &Ctx,
) -> CliResult<Outcome> {
    let started = Instant::now();
    if levels > MAX_LEVELS {
        return Err(CliError::usage(format!(
            "--levels {levels}: at most {MAX_LEVELS}"
        )));
    }
    let mesh0 = CoreMesh::new(&input.positions, &input.offsets, &input.indices);
    let n0 = Namer { src, level: 0 };
    let core_tags = scheme::Tags::new()
        .creases(&tags.creases, &tags.crease_sharpness)
        .corners(&tags.corners, &tags.corner_sharpness)
        .method(method);
    let tag_error = |e: Error| -> Option<CliError> {
        let why = match e.status {
            Status::TagNotAnEdge => "the two vertices are not joined by an edge",
            Status::RepeatedTag => "this edge or vertex is already tagged",
            Status::InvalidSharpness => "the sharpness must be a finite number ≥ 0",
            Status::IndexOutOfRange => "a vertex index is not below the vertex count",
            Status::TagsNotSupported => {
                return Some(CliError::bad_input(format!(
                    "{}: sharp-feature tags: {} does not take them (loop, catmull-clark, \
                     butterfly and kobbelt do, linear and Möbius)",
                    n0.file(),
                    ms.name()
                )))
            }
            _ => return None,
        };
        let e_idx = e.element as usize;
        let what = if e_idx < tags.creases.len() {
            let [a, b] = tags.creases.get(e_idx).copied().unwrap_or_default();
            format!("crease tag {a} {b}")
        } else {
            let v = tags
                .corners
                .get(e_idx - tags.creases.len())
                .copied()
                .unwrap_or_default();
            format!("corner tag {v}")
        };
        let at = match tags.line_of(e_idx) {
            Some(l) => format!("{}:{l}", n0.file()),
            None => format!("{} (--crease-angle)", n0.file()),
        };
        Some(CliError::bad_input(format!("{at}: {what}: {why}")))
    };
    let opts = Options::new(ms.scheme)
        .mobius(ms.mobius)
        .strict(mode.strict)
        .literal(mode.literal)
        .spectrum(mode.spectrum)
        .levels(levels);
    // Validation (naming the file's elements) and the sizes of every level, as `run`.
    {
        let len = scheme::plan_scratch_size(&mesh0)
            .map_err(|e| core_error(e, Stage::Build, ms, None, &mesh0, &n0))?;
        let mut scratch = memory::filled(len, 0u32, "the topology")?;
        let first = Options::new(ms.scheme).levels(levels.min(1));
        scheme::plan(mesh0, &first, &mut scratch).map_err(|e| call_error(e, ms, mesh0, &n0))?;
    }
    let (sizes, _) = plan_sizes(ms, mesh0, levels, &n0)?;
    let len = scheme::plan_scratch_size_tagged(&mesh0, &core_tags)
        .map_err(|e| core_error(e, Stage::Build, ms, None, &mesh0, &n0))?;
    let mut scratch = memory::filled(len, 0u32, "the topology")?;
    let weights = mode.weights.map(scheme::VertexWeights::Mobius);
    let plan = scheme::plan_weighted(mesh0, &opts, &core_tags, weights, &mut scratch)
        .map_err(|e| tag_error(e).unwrap_or_else(|| call_error(e, ms, mesh0, &n0)))?;
    let out_sizes = plan.output();
    if sizes.last().copied().unwrap_or_default() != out_sizes {
        return Err(CliError::internal(
            "tagged plan sizes differ from the untagged plan",
        ));
    }
    let bytes = 4 * plan.scratch.u32s as u128
        + 24 * plan.scratch.points as u128
        + 24 * out_sizes.vertices as u128
        + 4 * (out_sizes.faces as u128 + 1 + out_sizes.indices as u128);
    memory::check(
        bytes,
        &format!("{levels} levels of {}", ms.name()),
        "use fewer levels",
    )?;
    let mut scratch = memory::filled(plan.scratch.u32s, 0u32, "the topology")?;
    let mut points = memory::filled(plan.scratch.points, [0.0; 3], "the levels")?;
    let mut next = output_mesh(out_sizes)?;
    let _spinner = ctx.spinner("subdividing");
    let mut out = MeshOut::new(&mut next.positions, &mut next.offsets, &mut next.indices);
    let kernel_started = Instant::now();
    let report = scheme::subdivide_weighted(
        mesh0,
        &opts,
        &core_tags,
        weights,
        Scratch::new(&mut scratch, &mut points),
        &mut out,
        &nlsubdiv::exec::Serial,
    )
    .map_err(|e| {
        tag_error(e).unwrap_or_else(|| {
            if levels == 1 {
                // The element is an output vertex of the one step: named by the input's.
                call_error(e, ms, mesh0, &n0)
            } else {
                CliError::bad_input(format!(
                    "{}: {} levels of {} with sharp-feature tags: {e}",
                    n0.file(),
                    levels,
                    ms.name()
                ))
            }
        })
    })?;
    let kernel = kernel_started.elapsed();
    if report.sizes != out_sizes {
        return Err(CliError::internal(
            "tagged subdivision wrote other sizes than planned",
        ));
    }
    // Later levels are described by their index (as `run` does).
    let describe = |level: u32, i: u32| describe_step_vertex(ms, mesh0, &n0, level, i);
    Ok(Outcome {
        mesh: next,
        fallbacks: u64::from(report.fallbacks),
        first_fallback: (report.fallbacks > 0)
            .then(|| describe(report.first_fallback_level, report.first_fallback)),
        guarded: u64::from(report.guarded),
        first_guarded: (report.guarded > 0)
            .then(|| describe(report.first_guarded_level, report.first_guarded)),
        elapsed: started.elapsed(),
        kernel,
        // The tagged rules run on the calling thread (tests/parallel.rs covers the untagged
        // passes).
        threads: 1,
    })
}
