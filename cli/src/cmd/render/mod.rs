//! `nlsubdiv render IN OUT.png`: a software rasteriser for a quick look at a mesh.
//!
//! Perspective camera from a 3/4 view (azimuth and elevation around the model, the model's
//! bounding box filling 90 % of the frame), z-buffer, 2×2 supersampling, Lambert diffuse
//! plus Blinn–Phong specular from a key and a fill light, normals smoothed across edges
//! whose faces meet at less than 40°, back faces in a dim orange (holes and inverted faces
//! show), optional polygon edges (not the triangulation's), and optional per-vertex colour
//! by a field with a colour bar. Deterministic: the same mesh and options give the same
//! PNG bytes.

pub mod font;

use std::path::PathBuf;

use clap::ValueEnum;

use crate::cmd::{load, Ctx, Policy, PolicyArgs};
use crate::error::{CliError, CliResult, Exit};
use crate::fields::{self, Field};
use crate::io::{write_error, AtomicFile};
use crate::memory;
use crate::mesh::{add, area_vector, cross, dot, norm, normalize, scale, sub, Mesh, P3};
use crate::topology::Topology;

/// What to colour the surface by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ColorBy {
    /// A uniform material.
    None,
    /// Discrete Willmore energy per vertex (0 where the star is cospherical).
    Willmore,
    /// Mean curvature per vertex (blue concave, red convex).
    MeanCurvature,
    /// Möbius-regularity defect per vertex.
    MobiusRegularity,
    /// Highlight lines (seed 001 Fig. 13): dark bands where the surface normal points at one
    /// of a row of parallel linear lights above the model. Kinks and wobbles of the lines
    /// show curvature discontinuities that shading hides.
    Highlight,
}

/// Whether to draw polygon edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Edges {
    /// When edges are at least 6 pixels long on average.
    Auto,
    /// Always.
    On,
    /// Never.
    Off,
}

/// The axis that points up.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Up {
    /// +x up.
    X,
    /// +y up (most OBJ and OFF models).
    Y,
    /// +z up (CAD and many scans).
    Z,
}

/// Arguments of `render`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh file (.off, .obj, .ply).
    pub input: PathBuf,
    /// PNG file to write.
    pub output: PathBuf,
    /// Colour the surface by a per-vertex field.
    #[arg(long, value_enum, default_value = "none")]
    pub color: ColorBy,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    pub size: (usize, usize),
    /// Draw polygon edges.
    #[arg(long, value_enum, default_value = "auto")]
    pub edges: Edges,
    /// The model's up axis.
    #[arg(long, value_enum, default_value = "y")]
    pub up: Up,
    /// Camera azimuth in degrees around the up axis (0: from the front, +: from the right).
    #[arg(long, default_value_t = 35.0, allow_negative_numbers = true)]
    pub azimuth: f64,
    /// Camera elevation in degrees above the horizon.
    #[arg(long, default_value_t = 25.0, allow_negative_numbers = true)]
    pub elevation: f64,
    /// Refuse meshes with topological defects (by default they are drawn, with warnings;
    /// drawing them is one way to see them).
    #[arg(long)]
    pub strict: bool,
}

fn parse_size(s: &str) -> Result<(usize, usize), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{s}': expected WIDTHxHEIGHT, e.g. 800x600"))?;
    let w: usize = w
        .trim()
        .parse()
        .map_err(|_| format!("'{w}' is not a width"))?;
    let h: usize = h
        .trim()
        .parse()
        .map_err(|_| format!("'{h}' is not a height"))?;
    if !(16..=8192).contains(&w) || !(16..=8192).contains(&h) {
        return Err(format!("{w}x{h}: width and height must be 16 to 8192"));
    }
    Ok((w, h))
}

/// Runs `render`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    let ext_ok = args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !ext_ok {
        return Err(CliError::usage(format!(
            "{}: the picture is written as PNG; use a file name ending in .png",
            args.output.display()
        )));
    }
    let policy = PolicyArgs {
        lenient: !args.strict,
        strict: args.strict,
    }
    .policy(Policy::Lenient);
    let l = load(&args.input, policy, ctx)?;
    let field = match args.color {
        ColorBy::None => None,
        ColorBy::Willmore => Some(Field::Willmore),
        ColorBy::MeanCurvature => Some(Field::MeanCurvature),
        ColorBy::MobiusRegularity => Some(Field::MobiusRegularity),
        ColorBy::Highlight => None,
    };
    let img = render(&l.mesh, &l.topo, field, args, ctx)?;
    save_png(&args.output, &img)?;
    ctx.note(&format!(
        "wrote {} ({}x{})",
        args.output.display(),
        img.width,
        img.height
    ));
    Ok(Exit::Ok)
}

/// An 8-bit RGB picture.
#[derive(Debug)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Rows top to bottom, `RGB` per pixel.
    pub rgb: Vec<u8>,
}

/// Writes `img` to `path` as PNG, atomically.
///
/// # Errors
/// Exit 3 when the file cannot be written.
pub fn save_png(path: &std::path::Path, img: &Image) -> CliResult<()> {
    let mut file = AtomicFile::create(path)?;
    write_png(file.writer(), img).map_err(|e| match e {
        png::EncodingError::IoError(io) => write_error(path, &io),
        e => CliError::io(path, "write", &std::io::Error::other(e.to_string())),
    })?;
    file.commit()
}

fn write_png(out: &mut dyn std::io::Write, img: &Image) -> Result<(), png::EncodingError> {
    let mut enc = png::Encoder::new(out, img.width as u32, img.height as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Balanced);
    let mut w = enc.write_header()?;
    w.write_image_data(&img.rgb)?;
    w.finish()
}

/// The mesh's axes expressed in the picture's frame (x right, y up, z towards the front).
fn frame(up: Up) -> [P3; 3] {
    match up {
        Up::Y => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        // z up, the front looks towards −y.
        Up::Z => [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]],
        Up::X => [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    }
}

/// A perspective camera looking at the model.
struct Camera {
    eye: P3,
    right: P3,
    up: P3,
    forward: P3,
    focal: f64,
    cx: f64,
    cy: f64,
}

impl Camera {
    /// Screen position (pixels, y down) and depth along the view direction.
    fn project(&self, p: P3) -> (f64, f64, f64) {
        let d = sub(p, self.eye);
        let z = dot(d, self.forward);
        let x = dot(d, self.right) / z;
        let y = dot(d, self.up) / z;
        (self.cx + self.focal * x, self.cy - self.focal * y, z)
    }
}

fn camera(points: &[P3], args: &Args, w: f64, h: f64) -> Camera {
    let (lo, hi) = crate::mesh::bbox(points).unwrap_or(([0.0; 3], [0.0; 3]));
    let center = scale(add(lo, hi), 0.5);
    let radius = (0.5 * norm(sub(hi, lo))).max(1e-300);
    let (az, el) = (args.azimuth.to_radians(), args.elevation.to_radians());
    let dir = [az.sin() * el.cos(), el.sin(), az.cos() * el.cos()];
    // 30° field of view on the bounding sphere, then zoomed to the projected extent.
    let dist = radius / (15f64.to_radians()).sin();
    let eye = add(center, scale(dir, dist));
    let forward = normalize(sub(center, eye));
    let world_up = if el.cos().abs() < 1e-6 {
        [0.0, 0.0, -el.sin().signum()]
    } else {
        [0.0, 1.0, 0.0]
    };
    let right = normalize(cross(forward, world_up));
    let up = cross(right, forward);
    let mut cam = Camera {
        eye,
        right,
        up,
        forward,
        focal: 1.0,
        cx: 0.0,
        cy: 0.0,
    };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in points {
        let (x, y, _) = cam.project(*p);
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (ew, eh) = ((x1 - x0).max(1e-12), (y1 - y0).max(1e-12));
    let focal = 0.9 * (w / ew).min(h / eh);
    cam.focal = focal;
    cam.cx = 0.5 * w - focal * 0.5 * (x0 + x1);
    cam.cy = 0.5 * h - focal * 0.5 * (y0 + y1);
    cam
}

/// Up to this many faces at a vertex, corner normals are computed exactly (every pair of
/// faces at the vertex compared: quadratic in the valence). Above it, the faces are first
/// gathered into direction cells ([`direction_cell`]) and each corner is compared with the
/// cells: linear in the valence, so a vertex shared by 200,000 faces does not take minutes.
const EXACT_VALENCE: usize = 64;

/// Normals at every corner: the area-weighted normals of the faces at the vertex that meet
/// the corner's face at less than 40°.
fn corner_normals(mesh: &Mesh, topo: &Topology, face_n: &[P3]) -> CliResult<Vec<P3>> {
    let cos_crease = 40f64.to_radians().cos();
    let mut out = memory::filled(mesh.indices.len(), [0.0; 3], "the corner normals")?;
    for v in 0..mesh.num_vertices() as u32 {
        let corners = topo.corners(v);
        if corners.len() > EXACT_VALENCE {
            high_valence_normals(corners, topo, face_n, cos_crease, &mut out);
            continue;
        }
        for &h in corners {
            let f = topo.face_of[h as usize] as usize;
            let nf = normalize(face_n[f]);
            let mut s = [0.0; 3];
            for &g in corners {
                let fg = topo.face_of[g as usize] as usize;
                if dot(nf, normalize(face_n[fg])) >= cos_crease {
                    s = add(s, face_n[fg]);
                }
            }
            out[h as usize] = if norm(s) > 0.0 { normalize(s) } else { nf };
        }
    }
    Ok(out)
}

/// The cell of a unit direction on a cube map of 6 × 16 × 16 cells (about 7° wide): the
/// dominant axis and its sign, and the other two components over it, in 16 steps each.
fn direction_cell(n: P3) -> u32 {
    let a = (0..3)
        .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    let m = n[a].abs().max(f64::MIN_POSITIVE);
    let q = |x: f64| (((x / m + 1.0) * 8.0).floor() as u32).min(15);
    let (u, w) = ((a + 1) % 3, (a + 2) % 3);
    ((a as u32 * 2 + u32::from(n[a] < 0.0)) * 16 + q(n[u])) * 16 + q(n[w])
}

/// Corner normals at a vertex of high valence: the faces' area vectors summed per direction
/// cell; a corner takes the cells whose mean direction meets its face at less than the
/// crease angle. Faces of zero area (no direction) count for none, as in the exact rule.
fn high_valence_normals(
    corners: &[u32],
    topo: &Topology,
    face_n: &[P3],
    cos_crease: f64,
    out: &mut [P3],
) {
    let mut cells: std::collections::BTreeMap<u32, P3> = std::collections::BTreeMap::new();
    for &g in corners {
        let n = face_n[topo.face_of[g as usize] as usize];
        let u = normalize(n);
        if norm(u) > 0.0 {
            let c = cells.entry(direction_cell(u)).or_insert([0.0; 3]);
            *c = add(*c, n);
        }
    }
    let reps: Vec<(P3, P3)> = cells.values().map(|&s| (normalize(s), s)).collect();
    for &h in corners {
        let nf = normalize(face_n[topo.face_of[h as usize] as usize]);
        let mut s = [0.0; 3];
        for (dir, sum) in &reps {
            if dot(nf, *dir) >= cos_crease {
                s = add(s, *sum);
            }
        }
        out[h as usize] = if norm(s) > 0.0 { normalize(s) } else { nf };
    }
}

/// Linear RGB in 0…1 with depth, at the supersampled resolution.
struct Frame {
    w: usize,
    h: usize,
    color: Vec<[f32; 3]>,
    depth: Vec<f32>,
}

const SS: usize = 2;

fn background(y: usize, h: usize) -> [f32; 3] {
    let t = y as f32 / h.max(1) as f32;
    let top = [0.93, 0.95, 0.98];
    let bottom = [0.78, 0.81, 0.86];
    [0, 1, 2].map(|k| top[k] + (bottom[k] - top[k]) * t)
}

/// Per-vertex values to colour a surface by, and the range the colour map spans (values
/// outside it take the end colours; `None` values the undefined colour).
#[derive(Clone, Copy, Debug)]
pub struct Coloring<'a> {
    /// One value per vertex.
    pub values: &'a [Option<f64>],
    /// The values at the two ends of the colour map.
    pub range: (f64, f64),
    /// A diverging map centred on zero (signed values) rather than viridis.
    pub signed: bool,
}

/// Renders the mesh into an image of `args.size`, coloured by `field` with a colour bar
/// (its range the 2nd to 98th percentile of the values, said on the bar).
pub fn render(
    mesh: &Mesh,
    topo: &Topology,
    field: Option<Field>,
    args: &Args,
    ctx: &Ctx,
) -> CliResult<Image> {
    let Some(fl) = field else {
        return render_colored(mesh, topo, None, args, ctx);
    };
    let mut p = ctx.progress(mesh.num_vertices(), "measuring");
    let values = fields::compute(fl, mesh, topo, &mut p);
    p.finish();
    let range = fields::color_range(&values, fl.signed());
    let coloring = Coloring {
        values: &values,
        range,
        signed: fl.signed(),
    };
    let mut img = render_colored(mesh, topo, Some(coloring), args, ctx)?;
    draw_legend(&mut img, fl, range);
    Ok(img)
}

/// Renders the mesh into an image of `args.size`, coloured by `coloring` (leaving room on
/// the right for a colour bar, which the caller draws) or plain.
pub fn render_colored(
    mesh: &Mesh,
    topo: &Topology,
    coloring: Option<Coloring<'_>>,
    args: &Args,
    ctx: &Ctx,
) -> CliResult<Image> {
    let field = coloring;
    let (w, h) = args.size;
    let (sw, sh) = (w * SS, h * SS);
    // Everything this function holds at once: the supersampled frame (colour and depth),
    // the picture, and per vertex, corner and face: view positions, projections, colours,
    // corner normals, face normals and a copy of the faces.
    let (nv, nc, nf) = (
        mesh.num_vertices() as u128,
        mesh.indices.len() as u128,
        mesh.num_faces() as u128,
    );
    let bytes =
        (sw * sh) as u128 * 16 + (w * h) as u128 * 3 + nv * (24 * 4) + nc * (24 + 4) + nf * 28;
    memory::check(
        bytes,
        &format!("a {w}x{h} picture of this mesh"),
        "use a smaller --size",
    )?;
    let fr = frame(args.up);
    let pts: Vec<P3> = mesh
        .positions
        .iter()
        .map(|p| [dot(*p, fr[0]), dot(*p, fr[1]), dot(*p, fr[2])])
        .collect();
    let used: Vec<P3> = (0..mesh.num_vertices())
        .filter(|&v| topo.face_count(v as u32) > 0)
        .map(|v| pts[v])
        .collect();
    // With a colour bar, the model fills the part of the picture left of it.
    let fit_w = if field.is_some() { 0.78 } else { 1.0 } * sw as f64;
    let cam = camera(&used, args, fit_w, sh as f64);
    let highlight = (args.color == ColorBy::Highlight).then(|| Highlight::above(&used));
    let view_mesh = Mesh {
        positions: pts,
        offsets: mesh.offsets.clone(),
        indices: mesh.indices.clone(),
    };
    let face_n: Vec<P3> = view_mesh
        .faces()
        .map(|f| area_vector(&view_mesh, f))
        .collect();
    let normals = corner_normals(&view_mesh, topo, &face_n)?;

    // Per-vertex colours.
    let base = [0.72f64, 0.77, 0.85];
    let vcolor: Vec<[f64; 3]> = match field {
        Some(c) => (0..mesh.num_vertices())
            .map(|v| match c.values.get(v).copied().flatten() {
                Some(x) => fields::colormap((x - c.range.0) / (c.range.1 - c.range.0), c.signed),
                None => fields::UNDEFINED_COLOR,
            })
            .collect(),
        None => vec![base; mesh.num_vertices()],
    };

    let mut fb = Frame {
        w: sw,
        h: sh,
        color: memory::filled(sw * sh, [0.0f32; 3], "the picture")?,
        depth: memory::filled(sw * sh, f32::INFINITY, "the picture")?,
    };
    for (y, row) in fb.color.chunks_mut(sw).enumerate() {
        row.fill(background(y, sh));
    }
    let proj: Vec<(f64, f64, f64)> = view_mesh
        .positions
        .iter()
        .map(|p| cam.project(*p))
        .collect();
    let lights = Lights::new(&cam);
    let mut progress = ctx.progress(mesh.num_faces(), "rendering");
    for (f, face) in view_mesh.faces().enumerate() {
        progress.inc(1);
        let base_h = view_mesh.offsets[f] as usize;
        for i in 1..face.len().saturating_sub(1) {
            let c = [0, i, i + 1];
            let tri = c.map(|k| Vertex {
                s: proj[face[k] as usize],
                n: normals[base_h + k],
                p: view_mesh.positions[face[k] as usize],
                c: vcolor[face[k] as usize],
            });
            raster_triangle(&mut fb, &tri, &lights, &cam, highlight.as_ref());
        }
    }
    progress.finish();

    let mean_edge_px = {
        let mut sum = 0.0;
        for &(a, b) in &topo.edges {
            let (pa, pb) = (proj[a as usize], proj[b as usize]);
            sum += ((pa.0 - pb.0).powi(2) + (pa.1 - pb.1).powi(2)).sqrt();
        }
        sum / topo.edges.len().max(1) as f64 / SS as f64
    };
    let draw_edges = match args.edges {
        Edges::On => true,
        Edges::Off => false,
        Edges::Auto => mean_edge_px >= 6.0,
    };
    if draw_edges {
        let depth_bias = 0.004 * used_depth_range(&proj);
        for &(a, b) in &topo.edges {
            draw_line(&mut fb, proj[a as usize], proj[b as usize], depth_bias);
        }
    }

    drop(normals);
    downsample(&fb, w, h)
}

fn used_depth_range(proj: &[(f64, f64, f64)]) -> f64 {
    let (mut lo, mut hi) = (f64::MAX, f64::MIN);
    for p in proj {
        lo = lo.min(p.2);
        hi = hi.max(p.2);
    }
    (hi - lo).max(0.0)
}

#[derive(Clone, Copy)]
struct Vertex {
    /// Screen x, y and depth.
    s: (f64, f64, f64),
    /// Normal (picture frame).
    n: P3,
    /// Position (picture frame).
    p: P3,
    /// Colour.
    c: [f64; 3],
}

struct Lights {
    dirs: [(P3, f64); 2],
    ambient: f64,
}

impl Lights {
    fn new(cam: &Camera) -> Lights {
        // Key light from the upper left in front of the camera, fill from the right.
        let key = normalize(add(
            add(scale(cam.up, 0.8), scale(cam.right, -0.6)),
            scale(cam.forward, -1.0),
        ));
        let fill = normalize(add(
            add(scale(cam.up, -0.1), scale(cam.right, 0.9)),
            scale(cam.forward, -0.5),
        ));
        Lights {
            dirs: [(key, 0.75), (fill, 0.3)],
            ambient: 0.18,
        }
    }

    fn shade(&self, n: P3, view: P3, albedo: [f64; 3], front: bool) -> [f64; 3] {
        let albedo = if front { albedo } else { [0.80, 0.45, 0.25] };
        let mut diffuse = self.ambient;
        let mut spec = 0.0;
        for (l, k) in &self.dirs {
            let nl = dot(n, *l);
            if nl > 0.0 {
                diffuse += k * nl;
                let hv = normalize(add(*l, view));
                spec += k * dot(n, hv).max(0.0).powf(48.0);
            }
        }
        let s = if front { 0.35 } else { 0.1 };
        [0, 1, 2].map(|i| (albedo[i] * diffuse + s * spec).min(1.0))
    }
}

fn raster_triangle(
    fb: &mut Frame,
    t: &[Vertex; 3],
    lights: &Lights,
    cam: &Camera,
    highlight: Option<&Highlight>,
) {
    let [a, b, c] = [t[0].s, t[1].s, t[2].s];
    if a.2 <= 0.0 || b.2 <= 0.0 || c.2 <= 0.0 {
        return; // behind the eye (cannot happen with the fitted camera)
    }
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let x0 = a.0.min(b.0).min(c.0).floor().max(0.0) as usize;
    let x1 = (a.0.max(b.0).max(c.0).ceil().max(0.0) as usize).min(fb.w.saturating_sub(1));
    let y0 = a.1.min(b.1).min(c.1).floor().max(0.0) as usize;
    let y1 = (a.1.max(b.1).max(c.1).ceil().max(0.0) as usize).min(fb.h.saturating_sub(1));
    if x0 > x1 || y0 > y1 {
        return;
    }
    let inv_w = [1.0 / a.2, 1.0 / b.2, 1.0 / c.2];
    // A thin sliver's bounding box can hold thousands of times its pixels (a fan of 40,000
    // slivers from one centre would test billions of pixels): then only the columns of each
    // row where the three edge functions can be non-negative are visited. Each pixel's test
    // below is unchanged, so the picture is the same.
    let bbox_px = (x1 - x0 + 1) as f64 * (y1 - y0 + 1) as f64;
    let sliver = bbox_px > 8.0 * 0.5 * area.abs() + 256.0;
    for y in y0..=y1 {
        let py = y as f64 + 0.5;
        let (xa, xb) = if sliver {
            let w0 = |px: f64| ((b.0 - px) * (c.1 - py) - (b.1 - py) * (c.0 - px)) / area;
            let w1 = |px: f64| ((c.0 - px) * (a.1 - py) - (c.1 - py) * (a.0 - px)) / area;
            let (l, r) = (x0 as f64 + 0.5, x1 as f64 + 0.5);
            let (w0l, w0r, w1l, w1r) = (w0(l), w0(r), w1(l), w1(r));
            let spans = [
                span(w0l, w0r, x0, x1),
                span(w1l, w1r, x0, x1),
                span(1.0 - w0l - w1l, 1.0 - w0r - w1r, x0, x1),
            ];
            let mut lo = x0;
            let mut hi = x1;
            let mut empty = false;
            for sp in spans {
                match sp {
                    Some((p, q)) => {
                        lo = lo.max(p);
                        hi = hi.min(q);
                    }
                    None => empty = true,
                }
            }
            if empty || lo > hi {
                continue;
            }
            (lo, hi)
        } else {
            (x0, x1)
        };
        for x in xa..=xb {
            let px = x as f64 + 0.5;
            let w0 = ((b.0 - px) * (c.1 - py) - (b.1 - py) * (c.0 - px)) / area;
            let w1 = ((c.0 - px) * (a.1 - py) - (c.1 - py) * (a.0 - px)) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            // Perspective-correct weights.
            let q = [w0 * inv_w[0], w1 * inv_w[1], w2 * inv_w[2]];
            let qs = q[0] + q[1] + q[2];
            let depth = 1.0 / qs;
            let idx = y * fb.w + x;
            if depth as f32 >= fb.depth[idx] {
                continue;
            }
            let k = [q[0] / qs, q[1] / qs, q[2] / qs];
            let mix = |f: &dyn Fn(&Vertex) -> P3| {
                let (u, v, w) = (f(&t[0]), f(&t[1]), f(&t[2]));
                [0, 1, 2].map(|i| k[0] * u[i] + k[1] * v[i] + k[2] * w[i])
            };
            let n = normalize(mix(&|v| v.n));
            let p = mix(&|v| v.p);
            let mut col = mix(&|v| v.c);
            if highlight.is_some_and(|h| h.on_line(p, n)) {
                col = Highlight::INK;
            }
            let view = normalize(sub(cam.eye, p));
            let front = dot(n, view) >= 0.0;
            let n = if front { n } else { scale(n, -1.0) };
            let rgb = lights.shade(n, view, col, front);
            fb.depth[idx] = depth as f32;
            fb.color[idx] = rgb.map(|x| x as f32);
        }
    }
}

/// Highlight lines (Beier and Chen's model, as seed 001 Fig. 13 uses them): parallel
/// linear lights along the picture's x axis, in the plane `y = height` above the model,
/// `spacing` apart in z. A surface point is on a highlight line when the line through it
/// along its normal meets the light plane within a band around one of the lights: the
/// lines follow the surface's normal field, so a curvature discontinuity shows as a kink.
/// Evaluated per pixel from the interpolated normal.
struct Highlight {
    height: f64,
    spacing: f64,
}

impl Highlight {
    const INK: [f64; 3] = [0.07, 0.07, 0.09];
    /// Band half-width, as a fraction of the spacing.
    const BAND: f64 = 0.12;

    /// Lights a quarter of the model's size above the bounding box of `points` (picture
    /// frame), six across it.
    fn above(points: &[P3]) -> Highlight {
        let (lo, hi) = crate::mesh::bbox(points).unwrap_or(([0.0; 3], [0.0; 3]));
        let size = norm(sub(hi, lo)).max(1e-300);
        Highlight {
            height: hi[1] + 0.25 * size,
            spacing: size / 6.0,
        }
    }

    fn on_line(&self, p: P3, n: P3) -> bool {
        if n[1] <= 0.2 {
            return false; // the normal meets the light plane far away, or never: no band
        }
        let t = (self.height - p[1]) / n[1];
        let z = (p[2] + t * n[2]) / self.spacing;
        let d = z - z.round();
        d.is_finite() && d.abs() < Self::BAND
    }
}

/// The columns `x0..=x1` of a row where an edge function with the values `fl` at the
/// first column and `fr` at the last (it is linear along the row) may be non-negative, with
/// two columns of margin for rounding; `None` when it is clearly negative on the whole row.
fn span(fl: f64, fr: f64, x0: usize, x1: usize) -> Option<(usize, usize)> {
    const EPS: f64 = 1e-9;
    if !(fl.is_finite() && fr.is_finite()) {
        return Some((x0, x1));
    }
    if fl < -EPS && fr < -EPS {
        return None;
    }
    if fl >= -EPS && fr >= -EPS {
        return Some((x0, x1));
    }
    // One end negative: the zero crossing, in columns from x0.
    let t = fl / (fl - fr);
    let xc = x0 as f64 + t * (x1 - x0) as f64;
    if fl < 0.0 {
        let from = (xc.floor() - 2.0).max(x0 as f64) as usize;
        Some((from.min(x1), x1))
    } else {
        let to = (xc.ceil() + 2.0).max(x0 as f64) as usize;
        Some((x0, to.min(x1)))
    }
}

fn draw_line(fb: &mut Frame, a: (f64, f64, f64), b: (f64, f64, f64), bias: f64) {
    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let steps = (len.ceil() as usize).clamp(1, 1 << 16);
    let ink = [0.12f32, 0.13, 0.16];
    let alpha = 0.55f32;
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        // Perspective-correct depth along the segment.
        let inv = (1.0 - t) / a.2 + t / b.2;
        let z = 1.0 / inv;
        let (x, y) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
        // A 2-pixel pen at the supersampled resolution: 1 pixel in the picture.
        for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            let (px, py) = ((x - 0.5 + dx).floor(), (y - 0.5 + dy).floor());
            if px < 0.0 || py < 0.0 || px >= fb.w as f64 || py >= fb.h as f64 {
                continue;
            }
            let idx = py as usize * fb.w + px as usize;
            if (z - bias) as f32 <= fb.depth[idx] {
                let c = &mut fb.color[idx];
                for k in 0..3 {
                    c[k] = c[k] * (1.0 - alpha) + ink[k] * alpha;
                }
            }
        }
    }
}

fn downsample(fb: &Frame, w: usize, h: usize) -> CliResult<Image> {
    let mut rgb = memory::filled(0, 0u8, "the picture")?;
    rgb.try_reserve_exact(w * h * 3).map_err(|_| {
        CliError::usage(format!(
            "cannot allocate a {w}x{h} picture: use a smaller --size"
        ))
    })?;
    for y in 0..h {
        for x in 0..w {
            let mut s = [0.0f32; 3];
            for dy in 0..SS {
                for dx in 0..SS {
                    let c = fb.color[(y * SS + dy) * fb.w + x * SS + dx];
                    for k in 0..3 {
                        s[k] += c[k];
                    }
                }
            }
            for v in s {
                let v = v / (SS * SS) as f32;
                rgb.push((v.clamp(0.0, 1.0) * 255.0).round() as u8);
            }
        }
    }
    Ok(Image {
        width: w,
        height: h,
        rgb,
    })
}

/// Sets pixel `(x, y)` (nothing outside the picture).
pub fn set_px(img: &mut Image, x: usize, y: usize, c: [u8; 3]) {
    if x < img.width && y < img.height {
        let i = (y * img.width + x) * 3;
        img.rgb[i..i + 3].copy_from_slice(&c);
    }
}

/// Formats a legend value compactly.
pub fn label(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else if (1e-2..1e4).contains(&x.abs()) {
        let s = format!("{x:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{x:.2e}")
    }
}

fn draw_legend(img: &mut Image, field: Field, range: (f64, f64)) {
    let scale = if img.height >= 500 { 2 } else { 1 };
    let bar_w = 14 * scale;
    let bar_h = img.height * 3 / 5;
    let labels = [range.1, 0.5 * (range.0 + range.1), range.0].map(label);
    let label_w = labels
        .iter()
        .map(|l| font::text_width(l, scale))
        .max()
        .unwrap_or(0);
    let margin = 10 * scale;
    let Some(x0) = img.width.checked_sub(margin + label_w + 6 * scale + bar_w) else {
        return;
    };
    let y0 = (img.height - bar_h) / 2;
    let signed = field.signed();
    for dy in 0..bar_h {
        let t = 1.0 - dy as f64 / (bar_h - 1).max(1) as f64;
        let c = fields::colormap(t, signed).map(|k| (k * 255.0).round() as u8);
        for dx in 0..bar_w {
            set_px(img, x0 + dx, y0 + dy, c);
        }
    }
    let dark = [40, 42, 48];
    for dx in 0..bar_w {
        set_px(img, x0 + dx, y0, dark);
        set_px(img, x0 + dx, y0 + bar_h - 1, dark);
    }
    for dy in 0..bar_h {
        set_px(img, x0, y0 + dy, dark);
        set_px(img, x0 + bar_w - 1, y0 + dy, dark);
    }
    let th = font::text_height(scale);
    let lx = x0 + bar_w + 6 * scale;
    for (i, l) in labels.iter().enumerate() {
        let cy = y0 + i * (bar_h - 1) / 2;
        let ty = cy.saturating_sub(th / 2);
        font::draw_text(l, lx, ty, scale, |x, y| set_px(img, x, y, dark));
    }
    // The range is the 2nd to 98th percentile of the values (a few extreme vertices would
    // otherwise flatten the map): say so under the bar.
    let note = "percentiles 2 to 98";
    let nw = font::text_width(note, 1);
    let nx = (x0 + bar_w / 2)
        .saturating_sub(nw / 2)
        .min(img.width.saturating_sub(nw + 2));
    font::draw_text(note, nx, y0 + bar_h + 6 * scale, 1, |x, y| {
        set_px(img, x, y, dark)
    });
    let title = field.name().replace('-', " ");
    let tw = font::text_width(&title, scale);
    let tx = (x0 + bar_w / 2)
        .saturating_sub(tw / 2)
        .min(img.width.saturating_sub(tw + 2));
    let ty = y0.saturating_sub(th + 8 * scale);
    font::draw_text(&title, tx, ty, scale, |x, y| set_px(img, x, y, dark));
}
