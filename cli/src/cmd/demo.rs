//! `nlsubdiv demo [--out DIR]`: the main job on the bundled input, with no files needed.
//!
//! Subdivides the dome-like cage of [`crate::dome`] (seed 000, Fig. 1 in spirit) with
//! canonical Möbius Catmull–Clark (4 levels by default), writes the cage
//! (`demo_cage.off`), the result (`demo_out.off`) and a picture (`demo.png`), and prints
//! what it did: counts, time, fallbacks, the distance from the best-fit sphere before and
//! after (and what linear Catmull–Clark gives), and the check that a cage on a sphere stays
//! on it.
//!
//! The picture shows the point of the method in six panels: on top the cage, linear and
//! Möbius Catmull–Clark (similar shapes: off a sphere the two differ little); below the same
//! connectivity with its vertices on the unit sphere, where the two results are coloured by
//! their distance from the sphere on one scale (0 to the linear result's largest distance,
//! nothing clipped): the linear surface leaves the sphere, the Möbius one stays on it
//! (seed 000 §4: Möbius subdivision reproduces spheres).
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
use render::{font, Coloring, Image};

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

    let r = subdiv::run(&cage, &src, MOBIUS_CC, levels, subdiv::Mode::DEFAULT, ctx)?;
    let lin = subdiv::run(&cage, &src, LINEAR_CC, levels, subdiv::Mode::DEFAULT, ctx)?;
    // The same connectivity on the unit sphere: Möbius subdivision reproduces spheres.
    let sphere_cage = dome::cage(false);
    let rs = subdiv::run(
        &sphere_cage,
        &src,
        MOBIUS_CC,
        levels,
        subdiv::Mode::DEFAULT,
        ctx,
    )?;
    let ls = subdiv::run(
        &sphere_cage,
        &src,
        LINEAR_CC,
        levels,
        subdiv::Mode::DEFAULT,
        ctx,
    )?;
    let off_unit = |m: &Mesh| {
        m.positions
            .iter()
            .map(|p| (crate::mesh::norm(*p) - 1.0).abs())
            .fold(0.0f64, f64::max)
    };

    write_mesh(&out_path, &r.mesh, &WriteOptions::default())?;
    let (w_cage, _) = willmore(&cage, ctx);
    let (w_stats, _) = willmore(&r.mesh, ctx);
    let (off_lin, off_mob) = (off_unit(&ls.mesh), off_unit(&rs.mesh));
    let img = picture(
        [&cage, &lin.mesh, &r.mesh],
        [&sphere_cage, &ls.mesh, &rs.mesh],
        levels,
        (off_lin, off_mob),
        ctx,
    )?;
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
        off_mob, off_lin
    );
    println!(
        "  Willmore energy per vertex: cage mean {:.3e}, max {:.3e}; result mean {:.3e}, max \
         {:.3e} at vertex {}",
        w_cage.mean, w_cage.max, w_stats.mean, w_stats.max, w_stats.argmax
    );
    println!(
        "  wrote {}, {}, {} ({}x{}: top, the cage, linear and Möbius Catmull–Clark; bottom, \
         the same on the unit sphere, coloured by the distance from it) in {:.2} s",
        cage_path.display(),
        out_path.display(),
        png_path.display(),
        img.width,
        img.height,
        started.elapsed().as_secs_f64()
    );
    Ok(Exit::Ok)
}

/// Panel size of the demo picture, and the heights of its bands.
const PANEL: (usize, usize) = (480, 380);
const TITLE_H: usize = 44;
const CAPTION_H: usize = 34;
const LEGEND_H: usize = 76;
const INK: [u8; 3] = [40, 42, 48];

/// The six-panel picture: `top` (cage, linear, Möbius off the sphere) drawn plain,
/// `bottom` (the same on the unit sphere) with the two results coloured by `|r − 1|` on one
/// scale from 0 to the linear result's largest distance.
fn picture(
    top: [&Mesh; 3],
    bottom: [&Mesh; 3],
    levels: usize,
    (off_lin, off_mob): (f64, f64),
    ctx: &Ctx,
) -> CliResult<Image> {
    let (pw, ph) = PANEL;
    let (w, h) = (3 * pw, TITLE_H + 2 * (CAPTION_H + ph) + LEGEND_H);
    let mut img = Image {
        width: w,
        height: h,
        rgb: vec![250; w * h * 3],
    };
    let args = |edges: Edges| render::Args {
        input: PathBuf::new(),
        output: PathBuf::new(),
        color: ColorBy::None,
        size: PANEL,
        edges,
        up: Up::Y,
        azimuth: 20.0,
        elevation: 28.0,
        strict: false,
    };
    let range = (0.0, if off_lin > 0.0 { off_lin } else { 1.0 });
    text_centered(
        &mut img,
        &format!("nlsubdiv demo: {levels} levels of catmull-clark, linear and mobius"),
        w / 2,
        12,
        2,
    );
    let captions = [
        [
            "dome cage, off any sphere".to_string(),
            "linear catmull-clark".to_string(),
            "mobius catmull-clark".to_string(),
        ],
        [
            "the same cage on the unit sphere".to_string(),
            format!("linear: leaves it, max {}", render::label(off_lin)),
            format!("mobius: stays on it, max {}", render::label(off_mob)),
        ],
    ];
    for (row, meshes) in [top, bottom].iter().enumerate() {
        let y0 = TITLE_H + row * (CAPTION_H + ph);
        for (col, m) in meshes.iter().enumerate() {
            let topo = Topology::build(m);
            let edges = if col == 0 { Edges::On } else { Edges::Off };
            let values: Vec<Option<f64>> = m
                .positions
                .iter()
                .map(|p| Some((crate::mesh::norm(*p) - 1.0).abs()))
                .collect();
            let coloring = (row == 1 && col > 0).then_some(Coloring {
                values: &values,
                range,
                signed: false,
            });
            let panel = render::render_colored(m, &topo, coloring, &args(edges), ctx)?;
            blit(&mut img, &panel, col * pw, y0 + CAPTION_H);
            text_centered(&mut img, &captions[row][col], col * pw + pw / 2, y0 + 10, 2);
        }
    }
    legend(&mut img, range);
    Ok(img)
}

/// Copies `src` into `dst` with its top-left corner at `(x0, y0)`.
fn blit(dst: &mut Image, src: &Image, x0: usize, y0: usize) {
    for y in 0..src.height {
        for x in 0..src.width {
            let i = (y * src.width + x) * 3;
            if let Some(c) = src.rgb.get(i..i + 3) {
                render::set_px(dst, x0 + x, y0 + y, [c[0], c[1], c[2]]);
            }
        }
    }
}

fn text_centered(img: &mut Image, text: &str, cx: usize, y: usize, scale: usize) {
    let x = cx.saturating_sub(font::text_width(text, scale) / 2);
    font::draw_text(text, x, y, scale, |px, py| render::set_px(img, px, py, INK));
}

/// The colour bar of the bottom row, horizontal, under the panels: its full range, no
/// clipping, and what the colour means.
fn legend(img: &mut Image, range: (f64, f64)) {
    let (bar_w, bar_h) = (3 * PANEL.0 / 2, 14);
    let x0 = (img.width - bar_w) / 2;
    let y0 = img.height - LEGEND_H + 12;
    for dx in 0..bar_w {
        let c = fields::colormap(dx as f64 / (bar_w - 1) as f64, false)
            .map(|k| (k * 255.0).round() as u8);
        for dy in 0..bar_h {
            render::set_px(img, x0 + dx, y0 + dy, c);
        }
    }
    let ty = y0 + (bar_h - font::text_height(2)) / 2;
    let lo = render::label(range.0);
    font::draw_text(
        &lo,
        x0.saturating_sub(font::text_width(&lo, 2) + 10),
        ty,
        2,
        |x, y| render::set_px(img, x, y, INK),
    );
    font::draw_text(&render::label(range.1), x0 + bar_w + 10, ty, 2, |x, y| {
        render::set_px(img, x, y, INK)
    });
    text_centered(
        img,
        "bottom row colour: distance from the unit sphere, abs(r - 1), one scale, nothing clipped",
        img.width / 2,
        y0 + bar_h + 14,
        2,
    );
}
