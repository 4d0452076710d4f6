//! `nlsubdiv demo [--out DIR]`: the main job on the bundled input, with no files needed.
//!
//! Subdivides the dome-like cage of [`crate::dome`] (seed 000, Fig. 1 in spirit) with
//! canonical Möbius Catmull–Clark (4 levels by default), writes the cage
//! (`demo_cage.off`), the result (`demo_out.off`) and a picture of the result coloured by
//! its discrete Willmore energy (`demo.png`), and prints what it did: counts, time,
//! fallbacks, the distance from the best-fit sphere before and after (and what linear
//! Catmull–Clark gives), and the check that a cage on a sphere stays on it.
//! `nlsubdiv subdivide --scheme mobius-catmull-clark --levels 4 demo_cage.off x.off`
//! reproduces `demo_out.off` exactly.

use std::path::{Path, PathBuf};
use std::time::Instant;

use nlsubdiv::scheme::Scheme;

use super::render::{self, ColorBy, Edges, Up};
use super::Ctx;
use crate::dome;
use crate::error::{CliError, CliResult, Exit};
use crate::fields::{self, Field, Stats};
use crate::io::{write_mesh, WriteOptions};
use crate::mesh::{Mesh, Source};
use crate::sphere::{self, SphereFit};
use crate::subdiv::{self, MeshScheme};
use crate::topology::Topology;

/// Arguments of `demo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Folder to write demo_cage.off, demo_out.off and demo.png into (created if missing).
    #[arg(long, value_name = "DIR", default_value = ".")]
    pub out: PathBuf,
    /// Number of levels.
    #[arg(long, value_name = "N", default_value_t = 4,
          value_parser = clap::value_parser!(u32).range(1..=6))]
    pub levels: u32,
}

const MOBIUS_CC: MeshScheme = MeshScheme {
    scheme: Scheme::CatmullClark,
    mobius: true,
};
const LINEAR_CC: MeshScheme = MeshScheme {
    scheme: Scheme::CatmullClark,
    mobius: false,
};

fn fit(m: &Mesh) -> Option<SphereFit> {
    sphere::fit(&m.positions)
}

fn fit_text(s: Option<SphereFit>) -> String {
    match s {
        Some(s) => format!(
            "rms {:.2e} r, max {:.2e} r (r = {:.4})",
            s.rms_relative, s.max_relative, s.radius
        ),
        None => "no sphere (coplanar points)".to_string(),
    }
}

fn willmore(m: &Mesh, ctx: &Ctx) -> (Stats, Topology) {
    let topo = Topology::build(m);
    let mut progress = ctx.progress(m.num_vertices(), "measuring");
    let w = fields::compute(Field::Willmore, m, &topo, &mut progress);
    progress.finish();
    let s = Stats::of(&w, &topo);
    (s, topo)
}

fn face_census(m: &Mesh) -> String {
    let mut counts = std::collections::BTreeMap::new();
    for f in m.faces() {
        *counts.entry(f.len()).or_insert(0usize) += 1;
    }
    counts
        .iter()
        .map(|(&n, &c)| {
            let name = match n {
                3 => "triangle",
                4 => "quad",
                5 => "pentagon",
                6 => "hexagon",
                _ => "polygon",
            };
            format!("{c} {name}{}", if c == 1 { "" } else { "s" })
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Runs `demo`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    let started = Instant::now();
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::io(&args.out, "create the folder", &e))?;
    let levels = args.levels as usize;
    // `demo_out.off` rather than `./demo_out.off` in messages.
    let path = |name: &str| {
        if args.out == Path::new(".") {
            PathBuf::from(name)
        } else {
            args.out.join(name)
        }
    };
    let cage_path = path("demo_cage.off");
    let out_path = path("demo_out.off");
    let png_path = path("demo.png");

    let cage = dome::cage(true);
    let src = Source::new(Path::new("demo_cage.off"));
    write_mesh(&cage_path, &cage, &WriteOptions::default())?;

    let r = subdiv::run(&cage, &src, MOBIUS_CC, levels, false, false, ctx)?;
    let lin = subdiv::run(&cage, &src, LINEAR_CC, levels, false, false, ctx)?;
    // The same connectivity on the unit sphere: Möbius subdivision reproduces spheres.
    let sphere_cage = dome::cage(false);
    let rs = subdiv::run(&sphere_cage, &src, MOBIUS_CC, levels, false, false, ctx)?;
    let ls = subdiv::run(&sphere_cage, &src, LINEAR_CC, levels, false, false, ctx)?;
    let off_unit = |m: &Mesh| {
        m.positions
            .iter()
            .map(|p| (crate::mesh::norm(*p) - 1.0).abs())
            .fold(0.0f64, f64::max)
    };

    write_mesh(&out_path, &r.mesh, &WriteOptions::default())?;
    let (w_cage, _) = willmore(&cage, ctx);
    let (w_stats, topo) = willmore(&r.mesh, ctx);
    let render_args = render::Args {
        input: out_path.clone(),
        output: png_path.clone(),
        color: ColorBy::Willmore,
        size: (960, 720),
        edges: Edges::Off,
        up: Up::Y,
        azimuth: 20.0,
        elevation: 28.0,
        strict: false,
    };
    let img = render::render(&r.mesh, &topo, Some(Field::Willmore), &render_args, ctx)?;
    render::save_png(&png_path, &img)?;

    let boundary = Topology::build(&cage).boundary_loop_starts().len();
    println!(
        "nlsubdiv demo: canonical Möbius Catmull–Clark (seed 000 §4) on a dome-like cage \
         (seed 000 Fig. 1)"
    );
    println!(
        "  cage     {} vertices, {} faces ({}), {} boundary loop",
        cage.num_vertices(),
        cage.num_faces(),
        face_census(&cage),
        boundary
    );
    println!(
        "  result   {} levels of {}: {} vertices, {} faces ({}) in {:.3} s; {} fallback{}{}",
        levels,
        MOBIUS_CC.name(),
        r.mesh.num_vertices(),
        r.mesh.num_faces(),
        face_census(&r.mesh),
        r.elapsed.as_secs_f64(),
        r.fallbacks,
        if r.fallbacks == 1 { "" } else { "s" },
        r.first_fallback
            .as_deref()
            .map(|f| format!(" (first: {f})"))
            .unwrap_or_default()
    );
    println!("  distance from the best-fit sphere");
    println!("    cage                      {}", fit_text(fit(&cage)));
    println!("    Möbius Catmull–Clark      {}", fit_text(fit(&r.mesh)));
    println!("    linear Catmull–Clark      {}", fit_text(fit(&lin.mesh)));
    println!(
        "  the same cage on the unit sphere: Möbius Catmull–Clark stays on it (max |r − 1| = \
         {:.1e}); linear Catmull–Clark does not ({:.1e})",
        off_unit(&rs.mesh),
        off_unit(&ls.mesh)
    );
    println!(
        "  Willmore energy per vertex: cage mean {:.3e}, max {:.3e}; result mean {:.3e}, max \
         {:.3e} at vertex {}",
        w_cage.mean, w_cage.max, w_stats.mean, w_stats.max, w_stats.argmax
    );
    println!(
        "  wrote {}, {}, {} ({}x{}, coloured by Willmore energy) in {:.2} s",
        cage_path.display(),
        out_path.display(),
        png_path.display(),
        img.width,
        img.height,
        started.elapsed().as_secs_f64()
    );
    Ok(Exit::Ok)
}
