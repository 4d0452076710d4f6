//! `nlsubdiv metrics IN [--json]`: counts, edge lengths, per-vertex Willmore energy and
//! Möbius regularity (the core's star measures), mean curvature, and the distance from the
//! best-fit sphere; optionally a copy of the mesh coloured by one of the fields.

use std::collections::BTreeMap;
use std::collections::HashMap;
use std::path::PathBuf;

use serde_json::{json, Value};

use super::{findings_json, load, print_json, Ctx, Policy, PolicyArgs};
use crate::error::{CliResult, Exit};
use crate::fields::{self, Field, Stats};
use crate::io::{write_mesh, Format, WriteOptions};
use crate::mesh::{norm, sub, Mesh};
use crate::sphere;
use crate::topology::{Severity, Topology};

/// Arguments of `metrics`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh file (.off, .obj, .ply).
    pub input: PathBuf,
    /// Print the measures as JSON.
    #[arg(long)]
    pub json: bool,
    /// Also write the mesh with per-vertex colours of `--color` (PLY: with the value as a
    /// `quality` property MeshLab can show; OFF: COFF; OBJ: `v x y z r g b`).
    #[arg(long, value_name = "OUT")]
    pub colored: Option<PathBuf>,
    /// The field `--colored` shows.
    #[arg(long, value_enum, default_value = "willmore")]
    pub color: Field,
    #[command(flatten)]
    pub policy: PolicyArgs,
}

fn stats_json(s: &Stats) -> Value {
    json!({
        "vertices": s.count,
        "undefined": s.undefined,
        "mean": s.mean,
        "rms": s.rms,
        "min": s.min,
        "max": s.max,
        "max_vertex": s.argmax,
    })
}

/// FNV-1a 64 over a byte stream (a cheap, stable fingerprint, not a security hash).
fn fnv1a(bytes: impl Iterator<Item = u8>) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// Topological counts per component: Euler characteristic and genus (for orientable
/// manifold components).
fn topology_json(mesh: &Mesh, topo: &Topology, manifold: bool) -> Value {
    let (comp, ncomp) = topo.components(mesh);
    let mut v_c = vec![0i64; ncomp];
    let mut e_c = vec![0i64; ncomp];
    let mut f_c = vec![0i64; ncomp];
    let mut b_c = vec![0i64; ncomp];
    let mut vcomp = vec![u32::MAX; mesh.num_vertices()];
    for (f, face) in mesh.faces().enumerate() {
        f_c[comp[f] as usize] += 1;
        for &v in face {
            vcomp[v as usize] = comp[f];
        }
    }
    for c in vcomp.iter().filter(|&&c| c != u32::MAX) {
        v_c[*c as usize] += 1;
    }
    for &(a, _) in &topo.edges {
        if let Some(&c) = vcomp.get(a as usize) {
            e_c[c as usize] += 1;
        }
    }
    for &h in &topo.boundary_loop_starts() {
        b_c[comp[topo.face_of[h as usize] as usize] as usize] += 1;
    }
    let comps: Vec<Value> = (0..ncomp)
        .map(|c| {
            let chi = v_c[c] - e_c[c] + f_c[c];
            let g2 = 2 - chi - b_c[c];
            json!({
                "faces": f_c[c],
                "euler_characteristic": chi,
                "boundary_loops": b_c[c],
                "genus": if manifold && g2 >= 0 && g2 % 2 == 0 { json!(g2 / 2) } else { Value::Null },
            })
        })
        .collect();
    json!({
        "components": ncomp,
        "euler_characteristic": v_c.iter().sum::<i64>() - e_c.iter().sum::<i64>() + f_c.iter().sum::<i64>(),
        "per_component": comps,
    })
}

/// Runs `metrics`.
pub fn run(args: &Args, ctx: &Ctx) -> CliResult<Exit> {
    if let Some(out) = &args.colored {
        Format::from_path(out)?;
    }
    let l = load(&args.input, args.policy.policy(Policy::Default), ctx)?;
    let (m, topo) = (&l.mesh, &l.topo);
    let nv = m.num_vertices();

    let mut sizes: BTreeMap<usize, usize> = BTreeMap::new();
    for f in m.faces() {
        *sizes.entry(f.len()).or_default() += 1;
    }
    let boundary_edges = (0..topo.edges.len())
        .filter(|&e| topo.is_boundary_edge(e))
        .count();
    let lengths: Vec<f64> = topo
        .edges
        .iter()
        .map(|&(a, b)| norm(sub(m.pos(a), m.pos(b))))
        .collect();
    let (mut lmin, mut lmax, mut lsum) = (f64::INFINITY, 0.0f64, 0.0);
    for &x in &lengths {
        lmin = lmin.min(x);
        lmax = lmax.max(x);
        lsum += x;
    }
    let lmean = lsum / lengths.len().max(1) as f64;
    let mut coincident = 0usize;
    {
        let mut seen: HashMap<[u64; 3], u32> = HashMap::new();
        for v in 0..nv as u32 {
            if topo.face_count(v) == 0 {
                continue;
            }
            let p = m.pos(v).map(|x| (x + 0.0).to_bits());
            *seen.entry(p).or_default() += 1;
        }
        for &c in seen.values() {
            coincident += (c as usize).saturating_sub(1);
        }
    }
    let mut progress = ctx.progress(3 * nv, "measuring");
    let willmore = fields::compute(Field::Willmore, m, topo, &mut progress);
    let mobius = fields::compute(Field::MobiusRegularity, m, topo, &mut progress);
    let mean_curv = fields::compute(Field::MeanCurvature, m, topo, &mut progress);
    progress.finish();
    let (sw, sm, sh) = (
        Stats::of(&willmore, topo),
        Stats::of(&mobius, topo),
        Stats::of(&mean_curv, topo),
    );
    let used: Vec<[f64; 3]> = (0..nv as u32)
        .filter(|&v| topo.face_count(v) > 0)
        .map(|v| m.pos(v))
        .collect();
    let used_ids: Vec<usize> = (0..nv).filter(|&v| topo.face_count(v as u32) > 0).collect();
    let sphere = sphere::fit(&used);
    let bbox = m.bbox();
    let folds = crate::folds::measure(m);
    let errors = l.findings.iter().any(|f| f.severity == Severity::Error);
    let topo_json = topology_json(m, topo, !errors);

    let report = json!({
        "file": args.input.display().to_string(),
        "vertices": nv,
        "referenced_vertices": topo.referenced_vertices(),
        "faces": m.num_faces(),
        "edges": topo.edges.len(),
        "corners": m.indices.len(),
        "face_sizes": sizes.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "boundary_edges": boundary_edges,
        "boundary_loops": topo.boundary_loop_starts().len(),
        "closed": boundary_edges == 0,
        "topology": topo_json,
        "coincident_vertices": coincident,
        "bbox": bbox.map(|(lo, hi)| json!({"min": lo, "max": hi, "diagonal": norm(sub(hi, lo))})),
        "edge_length": {"min": lmin, "max": lmax, "mean": lmean},
        "willmore": stats_json(&sw),
        "mobius_regularity": stats_json(&sm),
        "mean_curvature": stats_json(&sh),
        "thin_plate": crate::differential::thin_plate(m),
        "folds": json!({
            "folded_edges": folds.folded,
            "worst_normal_angle_degrees": if folds.worst_degrees.is_nan() { Value::Null } else { json!(folds.worst_degrees) },
            "worst_edge": folds.worst_edge.map(|(a, b)| json!([a, b])),
        }),
        "sphere": sphere.map(|s| json!({
            "center": s.center,
            "radius": s.radius,
            "rms_relative": s.rms_relative,
            "max_relative": s.max_relative,
            "max_vertex": used_ids.get(s.argmax),
        })),
        "findings": findings_json(&l.findings),
        "hash": {
            "positions": fnv1a(m.positions.iter().flat_map(|p| p.iter().flat_map(|x| x.to_bits().to_le_bytes()))),
            "faces": fnv1a(m.offsets.iter().chain(&m.indices).flat_map(|x| x.to_le_bytes())),
        },
    });
    if args.json {
        print_json(&report)?;
    } else {
        crate::out::print(&print_text(
            &report,
            args,
            &sw,
            &sm,
            &sh,
            sphere.as_ref(),
            &used_ids,
        ))?;
    }
    if let Some(out) = &args.colored {
        let values = match args.color {
            Field::Willmore => &willmore,
            Field::MobiusRegularity => &mobius,
            Field::MeanCurvature => &mean_curv,
        };
        let signed = args.color.signed();
        let range = fields::color_range(values, signed);
        let colors = fields::colors_u8(values, range, signed);
        let ply = Format::from_path(out)? == Format::Ply;
        let opts = WriteOptions {
            ply_ascii: false,
            colors: Some(colors),
            scalar: ply.then(|| {
                (
                    "quality".to_string(),
                    values.iter().map(|x| x.unwrap_or(0.0)).collect(),
                )
            }),
            tags: None,
        };
        write_mesh(out, m, &opts)?;
        ctx.note(&format!(
            "wrote {} coloured by {} ({:e} … {:e})",
            out.display(),
            args.color.name(),
            range.0,
            range.1
        ));
    }
    Ok(Exit::Ok)
}

// Writing to a String cannot fail: the `fmt::Result`s of `writeln!` carry nothing.
#[allow(unused_must_use)]
fn print_text(
    r: &Value,
    args: &Args,
    sw: &Stats,
    sm: &Stats,
    sh: &Stats,
    sphere: Option<&sphere::SphereFit>,
    used_ids: &[usize],
) -> String {
    use std::fmt::Write as _;
    let mut text = String::new();
    let o = &mut text;
    writeln!(o, "{}", args.input.display());
    writeln!(
        o,
        "  vertices {} ({} referenced), faces {}, edges {}, corners {}",
        r["vertices"], r["referenced_vertices"], r["faces"], r["edges"], r["corners"]
    );
    let sizes: Vec<String> = r["face_sizes"]
        .as_object()
        .map(|o| o.iter().map(|(k, v)| format!("{k}-gons {v}")).collect())
        .unwrap_or_default();
    writeln!(o, "  faces by size: {}", sizes.join(", "));
    let t = &r["topology"];
    let genus: Vec<String> = t["per_component"]
        .as_array()
        .map(|a| a.iter().map(|c| c["genus"].to_string()).collect())
        .unwrap_or_default();
    writeln!(
        o,
        "  boundary: {} edges in {} loops; components {}; Euler characteristic {}; genus {}",
        r["boundary_edges"],
        r["boundary_loops"],
        t["components"],
        t["euler_characteristic"],
        genus.join(", ")
    );
    if r["coincident_vertices"].as_u64().unwrap_or(0) > 0 {
        writeln!(
            o,
            "  coincident vertices: {} (distinct vertices at the same position)",
            r["coincident_vertices"]
        );
    }
    let e = &r["edge_length"];
    writeln!(
        o,
        "  edge length: min {:.6e}, mean {:.6e}, max {:.6e}",
        e["min"].as_f64().unwrap_or(f64::NAN),
        e["mean"].as_f64().unwrap_or(f64::NAN),
        e["max"].as_f64().unwrap_or(f64::NAN)
    );
    for (name, s) in [
        ("Willmore energy", sw),
        ("Möbius regularity", sm),
        ("mean curvature", sh),
    ] {
        writeln!(
            o,
            "  {name}: mean {:.6e}, rms {:.6e}, max {:.6e} at vertex {} ({} vertices{})",
            s.mean,
            s.rms,
            s.max,
            s.argmax,
            s.count,
            if s.undefined > 0 {
                format!(", {} undefined", s.undefined)
            } else {
                String::new()
            }
        );
    }
    let _ = match r["thin_plate"].as_f64() {
        Some(e) => writeln!(
            o,
            "  thin-plate energy (seed 001 §4.3, ∫(κ₁²+κ₂²)/area): {e:.6e}"
        ),
        None => writeln!(
            o,
            "  thin-plate energy: none (not a triangle mesh, or no area)"
        ),
    };
    writeln!(
        o,
        "  folds (interior edges whose faces' normals are > 90° apart): {}",
        crate::folds::Folds {
            folded: r["folds"]["folded_edges"].as_u64().unwrap_or(0) as usize,
            worst_degrees: r["folds"]["worst_normal_angle_degrees"]
                .as_f64()
                .unwrap_or(f64::NAN),
            worst_edge: r["folds"]["worst_edge"]
                .as_array()
                .and_then(|a| { Some((a.first()?.as_u64()? as u32, a.get(1)?.as_u64()? as u32)) }),
        }
        .describe()
    );
    let _ = match sphere {
        Some(s) => writeln!(
            o,
            "  best-fit sphere: centre ({:.6e}, {:.6e}, {:.6e}), radius {:.6e}; distance rms {:.3e} r, max {:.3e} r at vertex {}",
            s.center[0],
            s.center[1],
            s.center[2],
            s.radius,
            s.rms_relative,
            s.max_relative,
            used_ids.get(s.argmax).copied().unwrap_or(0)
        ),
        None => writeln!(
            o,"  best-fit sphere: none (the vertices are coplanar or too few)"),
    };
    let h = &r["hash"];
    writeln!(
        o,
        "  fingerprint: positions {}, faces {}",
        h["positions"].as_str().unwrap_or(""),
        h["faces"].as_str().unwrap_or("")
    );
    text
}
