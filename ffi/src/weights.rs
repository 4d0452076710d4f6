//! Per-vertex weights of the Möbius–linear spectrum (seed 000 §7.2) in the C ABI:
//! `nls_subdivide_options.linear_weights`, `vertex_count` doubles, the weight `u` of the
//! linear result at each input vertex (the convention of `linear_weight`, which they
//! replace). NULL keeps the global weight. The array is an input: it may overlap the other
//! inputs but no output, scratch or out-pointer. The values are checked by the core
//! (`nlsubdiv::scheme::VertexWeights::Linear`): NaN or outside `[0, 1]` is
//! `NLS_STATUS_INVALID_ARGUMENT` naming the vertex.

use nlsubdiv::scheme::VertexWeights;
use nlsubdiv::Status;

use crate::guard::check_ptr;
use crate::mesh::{nls_subdivide_options, slice, RawMesh, Span};

/// The weights' byte range as given, for the out-element decision: empty without weights
/// (or without options, which describe no buffer then), `None` when it cannot be named (the
/// options struct or the mesh view could not be read, so the length is unknown).
pub(crate) fn weight_raw_span(
    options: *const nls_subdivide_options,
    opts: &Result<nls_subdivide_options, Status>,
    mesh: &Result<RawMesh, Status>,
) -> Option<Span> {
    match (opts, mesh) {
        (Ok(o), _) if o.linear_weights.is_null() => Some(Span::EMPTY),
        (Ok(o), Ok(m)) => Some(Span::raw(o.linear_weights, m.vertex_count())),
        (Err(_), _) if options.is_null() => Some(Span::EMPTY),
        _ => None,
    }
}

/// The weights' byte range when it is a valid buffer (see [`Span::checked`]).
pub(crate) fn weight_span(opts: &nls_subdivide_options, mesh: &RawMesh) -> Span {
    Span::checked(opts.linear_weights, mesh.vertex_count())
}

/// Checks the weights pointer (alignment, size; NULL is no weights).
pub(crate) fn check_weights(opts: &nls_subdivide_options, mesh: &RawMesh) -> Result<(), Status> {
    if opts.linear_weights.is_null() {
        return Ok(());
    }
    check_ptr(opts.linear_weights, mesh.vertex_count())
}

/// The core's weights, `None` for NULL.
///
/// # Safety
/// [`check_weights`] passed, and the array is readable and not written while the weights
/// live.
pub(crate) unsafe fn weights_of<'a>(
    opts: &nls_subdivide_options,
    mesh: &RawMesh,
) -> Option<VertexWeights<'a>> {
    if opts.linear_weights.is_null() {
        return None;
    }
    // SAFETY: checked (alignment, size) and readable by the caller's contract.
    Some(VertexWeights::Linear(unsafe {
        slice(opts.linear_weights, mesh.vertex_count())
    }))
}

#[cfg(test)]
mod tests {
    use crate::mesh::*;
    use nlsubdiv::Status;

    /// A bent, jittered 3 × 3 quad grid (16 vertices), packed.
    fn grid() -> (Vec<f64>, Vec<u32>, Vec<u32>) {
        let mut p = Vec::new();
        for j in 0..4 {
            for i in 0..4 {
                let (x, y) = (f64::from(i) / 3.0, f64::from(j) / 3.0);
                let jit = 0.03 * f64::from((i * 7 + j * 3) % 5);
                p.extend_from_slice(&[x + jit, y, 0.4 * (x * x - y * y) + jit]);
            }
        }
        let (mut off, mut idx) = (vec![0u32], Vec::new());
        for j in 0..3u32 {
            for i in 0..3u32 {
                let v = j * 4 + i;
                idx.extend_from_slice(&[v, v + 1, v + 5, v + 4]);
                off.push(idx.len() as u32);
            }
        }
        (p, off, idx)
    }

    /// Plan and subdivide with `o`; the status of each, the positions' bits and the element.
    fn call(o: &nls_subdivide_options) -> (Status, Status, Vec<u64>, u32) {
        let (p, off, idx) = grid();
        let m = nls_mesh_view {
            positions: p.as_ptr(),
            vertex_count: 16,
            positions_stride: 0,
            offsets: off.as_ptr(),
            face_count: 9,
            indices: idx.as_ptr(),
            index_count: 36,
        };
        let mut su = vec![0u32; 1 << 14];
        let mut plan = nls_plan::default();
        let mut element = 77u32;
        let ps =
            unsafe { nls_mesh_plan(&m, o, su.as_mut_ptr(), su.len(), &mut plan, &mut element) };
        let mut sp = vec![0.0; 3 * 4096];
        let (mut op, mut oo, mut oi) = (vec![f64::NAN; 3 * 256], vec![0u32; 257], vec![0u32; 1024]);
        let sc = nls_scratch {
            u32s: su.as_mut_ptr(),
            u32_capacity: su.len(),
            points: sp.as_mut_ptr(),
            point_capacity: 4096,
        };
        let buf = nls_mesh_buffers {
            positions: op.as_mut_ptr(),
            vertex_capacity: 256,
            offsets: oo.as_mut_ptr(),
            face_capacity: 256,
            indices: oi.as_mut_ptr(),
            index_capacity: 1024,
        };
        let mut sizes = nls_mesh_sizes::default();
        let mut e2 = 77u32;
        let s = unsafe {
            nls_mesh_subdivide(&m, o, &sc, &buf, &mut sizes, core::ptr::null_mut(), &mut e2)
        };
        if ps != Status::Ok {
            assert_eq!(element, e2, "plan and subdivide name one element");
        }
        let n = 3 * sizes.vertex_count;
        (ps, s, op[..n].iter().map(|x| x.to_bits()).collect(), e2)
    }

    fn opts(linear_weight: f64, weights: *const f64) -> nls_subdivide_options {
        nls_subdivide_options {
            scheme: NLS_SCHEME_CATMULL_CLARK,
            flags: NLS_SUBDIVIDE_MOBIUS,
            levels: 2,
            linear_weight,
            executor: core::ptr::null(),
            linear_weights: weights,
        }
    }

    /// Equal weights are the global weight bit for bit; all 0 the Möbius result, all 1 the
    /// linear one; mixed weights are the Rust path's weights of the linear result.
    #[test]
    fn weights_through_the_abi() {
        let null = core::ptr::null();
        for u in [0.0, 1.0, 0.3] {
            let w = [u; 16];
            let got = call(&opts(0.0, w.as_ptr()));
            assert_eq!(got.0, Status::Ok);
            assert_eq!(got, call(&opts(u, null)), "all {u}");
        }
        let lin = call(&nls_subdivide_options {
            flags: 0,
            ..opts(0.0, null)
        });
        assert_eq!(call(&opts(0.0, [1.0; 16].as_ptr())), lin);
        // Mixed: the kernel's own call with the same weights.
        let w: Vec<f64> = (0..16).map(|i| f64::from(i % 5) / 4.0).collect();
        let got = call(&opts(0.0, w.as_ptr()));
        let (p, off, idx) = grid();
        let pts: Vec<[f64; 3]> = p.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
        let mesh = nlsubdiv::Mesh::new(&pts, &off, &idx);
        let o = nlsubdiv::Options::new(nlsubdiv::Scheme::CatmullClark)
            .mobius(true)
            .levels(2);
        let weights = Some(nlsubdiv::VertexWeights::Linear(&w));
        let tags = nlsubdiv::Tags::new();
        let mut su = vec![0u32; 1 << 14];
        let plan = nlsubdiv::plan_weighted(mesh, &o, &tags, weights, &mut su).unwrap();
        let out = plan.output();
        let mut sp = vec![[0.0; 3]; plan.scratch.points];
        let (mut op, mut oo, mut oi) = (
            vec![[0.0; 3]; out.vertices],
            vec![0u32; out.faces + 1],
            vec![0u32; out.indices],
        );
        nlsubdiv::subdivide_weighted(
            mesh,
            &o,
            &tags,
            weights,
            nlsubdiv::Scratch::new(&mut su, &mut sp),
            &mut nlsubdiv::MeshOut::new(&mut op, &mut oo, &mut oi),
            &nlsubdiv::exec::Serial,
        )
        .unwrap();
        let want: Vec<u64> = op.iter().flatten().map(|x| x.to_bits()).collect();
        assert_eq!(got.2, want);
        assert_ne!(got.2, lin.2);
    }

    /// A bad weight is `InvalidArgument` naming the vertex from both calls, and nothing is
    /// written; a misaligned array is refused; an array inside an output buffer is aliasing.
    #[test]
    fn bad_weights_through_the_abi() {
        for bad in [f64::NAN, -0.5, 1.0 + f64::EPSILON, f64::INFINITY] {
            let mut w = [0.5; 16];
            w[5] = bad;
            w[11] = bad;
            let (ps, s, pos, e) = call(&opts(0.0, w.as_ptr()));
            assert_eq!(
                (ps, s, e),
                (Status::InvalidArgument, Status::InvalidArgument, 5)
            );
            assert!(pos.is_empty(), "sizes written");
        }
        let w = [0.5f64; 17];
        let odd = w.as_ptr().cast::<u8>().wrapping_add(1).cast::<f64>();
        let (ps, s, _, _) = call(&opts(0.0, odd));
        assert_eq!(
            (ps, s),
            (Status::MisalignedPointer, Status::MisalignedPointer)
        );
    }
}
