//! `nlsubdiv subdivide --scheme differential-loop|differential-butterfly|differential-dirmag`:
//! differential-space subdivision (seed 001, `nlsubdiv::differential`), one core call as a
//! Rust or C host makes it, and the thin-plate energy of `nlsubdiv metrics` (§4.3).

use std::time::{Duration, Instant};

use nlsubdiv::differential::metrics::thin_plate_energy;
use nlsubdiv::differential::{self as diff, DifferentialOptions, DifferentialReport, Stencil};
use nlsubdiv::mesh::{topology_scratch_size, Mesh as CoreMesh, MeshOut, Topology};
use nlsubdiv::{Status, NO_ELEMENT};

use crate::cmd::Ctx;
use crate::edits::Edits;
use crate::error::{CliError, CliResult};
use crate::memory;
use crate::mesh::{Mesh, Source};

/// A differential-space scheme of the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DifferentialScheme {
    /// `differential-loop`: Loop on the differential coordinates.
    Loop,
    /// `differential-butterfly`: Modified Butterfly on the differential coordinates.
    Butterfly,
    /// `differential-dirmag`: DirMag (§3.4) with Modified Butterfly for the first levels.
    DirMag,
}

impl DifferentialScheme {
    /// The three names.
    pub const NAMES: [&'static str; 3] = [
        "differential-loop",
        "differential-butterfly",
        "differential-dirmag",
    ];

    /// Parses a command-line name.
    pub fn from_name(name: &str) -> Option<DifferentialScheme> {
        match name {
            "differential-loop" => Some(DifferentialScheme::Loop),
            "differential-butterfly" => Some(DifferentialScheme::Butterfly),
            "differential-dirmag" => Some(DifferentialScheme::DirMag),
            _ => None,
        }
    }

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            DifferentialScheme::Loop => "differential-loop",
            DifferentialScheme::Butterfly => "differential-butterfly",
            DifferentialScheme::DirMag => "differential-dirmag",
        }
    }
}

/// The result of [`run`].
pub struct Outcome {
    /// The subdivided mesh.
    pub mesh: Mesh,
    /// The solver report.
    pub report: DifferentialReport,
    /// Time in the core.
    pub elapsed: Duration,
}

/// Options of [`run`] beyond the scheme and levels.
#[derive(Clone, Copy, Debug)]
pub struct RunOptions<'a> {
    /// DirMag levels (`differential-dirmag` only).
    pub dirmag_levels: usize,
    /// Solver tolerance.
    pub tolerance: f64,
    /// Solver iteration cap.
    pub max_iterations: u32,
    /// §4.4 edits (`--edit FILE`), or none.
    pub edits: Option<&'a Edits>,
    /// With edits: a fold of the output is an error naming the face (`--strict`).
    pub strict: bool,
    /// Threads of the kernel's passes (`nlsubdiv_threads`; the output is the same bits for
    /// every count).
    pub threads: usize,
}

fn core_error(e: nlsubdiv::Error, src: &Source, name: &str, rep: &DifferentialReport) -> CliError {
    let el = e.element;
    match e.status {
        Status::UnsupportedFaceType if el != NO_ELEMENT => CliError::bad_input(format!(
            "{}: not a triangle; {name} needs a triangle mesh (triangulate it first)",
            src.at_face(el as usize)
        )),
        Status::NonManifoldVertex | Status::NonFiniteInput if el != NO_ELEMENT => {
            CliError::bad_input(format!(
                "{}: {}",
                src.at_vertex(el as usize),
                e.status.message()
            ))
        }
        Status::NotConverged => CliError::bad_input(format!(
            "{}: {name}: the reconstruction did not converge in {} iterations (relative \
             residual {:.3e}); raise --max-iterations or --tolerance",
            src.path.display(),
            rep.solve.iterations,
            rep.solve.relative_residual
        )),
        Status::SizeOverflow => CliError::usage(format!(
            "{}: {name} would exceed the kernel's 32-bit indices: use fewer levels",
            src.path.display()
        )),
        Status::FoldedSurface => CliError::bad_input(format!(
            "{}: {name}: the edits fold the surface ({} faces turned by more than 90° from the \
             unedited result, the first output face {el}; {} folded edges) and --strict refuses \
             it: edit less, or drop --strict to write it with a count",
            src.path.display(),
            rep.folded_faces,
            rep.folded_edges
        )),
        Status::BufferTooSmall | Status::InvalidArgument => CliError::internal(format!(
            "{}: {name}: the kernel reported '{e}' (a bug: please report it with the input)",
            src.path.display()
        )),
        s if el != NO_ELEMENT => {
            CliError::bad_input(format!("{}: {}", src.at_face(el as usize), s.message()))
        }
        s => CliError::bad_input(format!("{}: {name}: {}", src.path.display(), s.message())),
    }
}

/// Runs `levels` levels of `scheme` on `mesh`.
///
/// # Errors
/// Bad input (non-triangles, non-convergence, …) naming the element.
pub fn run(
    mesh: &Mesh,
    src: &Source,
    scheme: DifferentialScheme,
    levels: usize,
    o: RunOptions,
    ctx: &Ctx,
) -> CliResult<Outcome> {
    let _spinner = ctx.spinner(scheme.name());
    let t = Instant::now();
    let view = CoreMesh::new(&mesh.positions, &mesh.offsets, &mesh.indices);
    let opts = DifferentialOptions {
        stencil: if scheme == DifferentialScheme::Loop {
            Stencil::Loop
        } else {
            Stencil::ModifiedButterfly
        },
        levels,
        dirmag_levels: if scheme == DifferentialScheme::DirMag {
            o.dirmag_levels
        } else {
            0
        },
        solve: diff::solve::SolveOptions {
            tolerance: o.tolerance,
            max_iterations: o.max_iterations,
            ..Default::default()
        },
        curvature_scale: o.edits.and_then(|e| e.curvature_scale.as_deref()),
        normals: o.edits.and_then(|e| e.normals.as_deref()),
        // The fold census compares an edited result with the unedited one: without edits
        // there is nothing to refuse.
        strict: o.strict,
    };
    let mut rep = DifferentialReport::default();
    let err = |e, rep: &DifferentialReport| core_error(e, src, scheme.name(), rep);
    let need = diff::plan_scratch_size(&view).map_err(|e| err(e, &rep))?;
    let mut su = memory::filled(need, 0u32, "the differential plan")?;
    let plan = diff::plan(view, &opts, &mut su).map_err(|e| err(e, &rep))?;
    let s = plan.output();
    // Everything the call holds at once, checked before any of it is allocated.
    let bytes = 4 * plan.scratch_u32.max(need) as u128
        + 24 * plan.scratch_points as u128
        + 24 * s.vertices as u128
        + 4 * (s.faces as u128 + 1 + s.indices as u128);
    memory::check(
        bytes,
        &format!("{levels} levels of {}", scheme.name()),
        "use fewer levels",
    )?;
    if plan.scratch_u32 > su.len() {
        su.try_reserve_exact(plan.scratch_u32 - su.len())
            .map_err(|_| {
                CliError::usage(format!(
                    "cannot allocate the scratch of {levels} levels of {}: use fewer levels",
                    scheme.name()
                ))
            })?;
    }
    su.resize(plan.scratch_u32, 0);
    let mut sp = memory::filled(plan.scratch_points, [0.0; 3], "the differential scratch")?;
    let mut pos = memory::filled(s.vertices, [0.0; 3], "the output positions")?;
    let mut offs = memory::filled(s.faces + 1, 0u32, "the output faces")?;
    let mut idx = memory::filled(s.indices, 0u32, "the output faces")?;
    let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
    nlsubdiv_threads::differential_subdivide(
        view, &opts, &mut su, &mut sp, &mut out, &mut rep, o.threads,
    )
    .map_err(|e| err(e, &rep))?;
    Ok(Outcome {
        mesh: Mesh {
            positions: pos,
            offsets: offs,
            indices: idx,
        },
        report: rep,
        elapsed: t.elapsed(),
    })
}

/// The normalised thin-plate energy `∫(κ₁² + κ₂²) / ∫1` of a triangle mesh (seed 001 §4.3,
/// Cohen-Steiner–Morvan tensor); `None` when the mesh is not a valid triangle mesh or has no
/// area.
pub fn thin_plate(mesh: &Mesh) -> Option<f64> {
    if mesh.faces().any(|f| f.len() != 3) {
        return None;
    }
    let view = CoreMesh::new(&mesh.positions, &mesh.offsets, &mesh.indices);
    let mut su = vec![0u32; topology_scratch_size(mesh.num_vertices(), mesh.indices.len()).ok()?];
    let topo = Topology::build(view, &mut su).ok()?;
    let mut sc = vec![[0.0; 3]; mesh.num_vertices()];
    thin_plate_energy(&topo, &mut sc).ok()
}
