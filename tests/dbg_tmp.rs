#![allow(clippy::indexing_slicing, clippy::unwrap_used)]
mod common;
use common::*;
use nlsubdiv::mesh::{MeshOut, Topology};
use nlsubdiv::scheme::{self, mobius, Scheme};
#[test]
fn dbg() {
    let m = tetrahedron().map_positions(|p| [p[0] - 0.25, p[1] - 0.25, p[2] - 0.25]).map_positions(|p| { let n=(p[0]*p[0]+p[1]*p[1]+p[2]*p[2]).sqrt(); [p[0]/n,p[1]/n,p[2]/n]});
    for s in [Scheme::ModifiedButterfly] {
    let mut m = m.clone();
    for level in 0..3 {
    let mut scratch = vec![0u32; scheme::scratch_len(&m.view()).unwrap()];
    let topo = Topology::build(m.view(), &mut scratch).unwrap();
    let sizes = scheme::subdivide_size(s, &topo).unwrap();
    let mut out = OwnedMesh { positions: vec![[0.0;3]; sizes.vertices], offsets: vec![0; sizes.faces+1], indices: vec![0; sizes.indices]};
    let mut pts = vec![[0.0; 3]; mobius::scratch_len(&topo).unwrap()];
    let r = mobius::subdivide(s, &topo, &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices), &mut pts, Default::default()).unwrap();
    println!("{s:?} {:?}", r.1);
    let nv = m.positions.len(); let ne = topo.num_edges();
    for (i,p) in out.positions.iter().enumerate() { let n=(p[0]*p[0]+p[1]*p[1]+p[2]*p[2]).sqrt(); if (n-1.0).abs()>1e-9 { println!("  level {level} {i} {n} kind {}", if i < nv {"vertex"} else if i < nv+ne {"edge"} else {"face"}); } }
    drop(topo);
    m = out;
    }
    }
}
