//! Shared by the fuzz targets: a byte reader that never fails (missing bytes read as 0) and
//! the sentinels the contract checks compare against.
#![allow(dead_code)]

/// Reads the fuzz input front to back; past the end every read gives 0, so any byte string
/// is an input.
pub struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Reader { data, at: 0 }
    }
    pub fn u8(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at = self.at.saturating_add(1);
        b
    }
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }
    pub fn f64(&mut self) -> f64 {
        let mut b = [0u8; 8];
        for x in &mut b {
            *x = self.u8();
        }
        f64::from_le_bytes(b)
    }
    /// Bytes left to read.
    pub fn left(&self) -> usize {
        self.data.len().saturating_sub(self.at)
    }
}

/// Special values a header byte can plant into an input coordinate (reliability-anchors §4.2).
pub const SPECIALS: [f64; 8] = [
    0.0,
    -0.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MIN_POSITIVE,
    1e308,
    1e-310,
];

/// The bit pattern output buffers are filled with before a call: "nothing written" means
/// every element still has it.
pub const SENTINEL_F64: u64 = 0x7ff8_dead_beef_0001;
pub const SENTINEL_U32: u32 = 0xa5a5_a5a5;
pub const SENTINEL_COUNT: usize = usize::MAX - 7;
pub const SENTINEL_ELEMENT: u32 = 0xbeef_0000;

pub fn f64_sentinels(n: usize) -> Vec<f64> {
    vec![f64::from_bits(SENTINEL_F64); n]
}

pub fn untouched_f64(v: &[f64]) -> bool {
    v.iter().all(|x| x.to_bits() == SENTINEL_F64)
}

pub fn untouched_u32(v: &[u32]) -> bool {
    v.iter().all(|&x| x == SENTINEL_U32)
}

pub fn same_bits(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// The size caps of a decoded mesh (each target keeps its executions fast).
#[derive(Clone, Copy)]
pub struct Limits {
    pub vertices: usize,
    pub faces: usize,
    pub indices: u32,
}

/// A mesh decoded from the fuzz input, in the C ABI's layout (positions xyz, CSR faces).
#[derive(Clone)]
pub struct Mesh {
    pub pos: Vec<f64>,
    pub off: Vec<u32>,
    pub idx: Vec<u32>,
}

impl Mesh {
    pub fn nv(&self) -> usize {
        self.pos.len() / 3
    }
    pub fn nf(&self) -> usize {
        self.off.len() - 1
    }
}

/// Decodes a mesh within `limits`; `tweak` plants an out-of-contract value the byte mutations
/// rarely reach (malformed offsets or a special coordinate at `tweak_at`).
pub fn decode_mesh(r: &mut Reader<'_>, tweak: u8, tweak_at: u16, limits: Limits) -> Mesh {
    let nv = usize::from(r.u16()).min(limits.vertices);
    // No more faces than bytes left and at most `limits.indices` corners: a mutated count must
    // not turn the missing bytes into a huge mesh of zeros (that made every execution
    // allocate megabytes and ran at ~100 exec/s).
    let nf = usize::from(r.u16()).min(limits.faces).min(r.left());
    let mut off = Vec::with_capacity(nf + 1);
    off.push(0u32);
    let mut total = 0u32;
    for _ in 0..nf {
        total = (total + u32::from(r.u8())).min(limits.indices);
        off.push(total);
    }
    let idx: Vec<u32> = (0..total).map(|_| u32::from(r.u16())).collect();
    let mut pos: Vec<f64> = (0..3 * nv).map(|_| r.f64()).collect();
    // Out-of-contract inputs the byte mutations rarely reach: malformed offsets and special
    // coordinates (in any vertex, referenced or not).
    match tweak & 3 {
        1 => {
            let k = usize::from(tweak_at) % off.len();
            off[k] ^= u32::from(tweak >> 2);
        }
        2 if !pos.is_empty() => {
            let k = usize::from(tweak_at) % pos.len();
            pos[k] = SPECIALS[usize::from(tweak >> 2) % SPECIALS.len()];
        }
        _ => {}
    }
    Mesh { pos, off, idx }
}

/// The C ABI's view of a packed mesh (shared by the mesh-taking targets).
pub fn view(m: &Mesh) -> nlsubdiv_ffi::mesh::nls_mesh_view {
    nlsubdiv_ffi::mesh::nls_mesh_view {
        positions: m.pos.as_ptr(),
        vertex_count: m.nv(),
        positions_stride: 0,
        offsets: m.off.as_ptr(),
        face_count: m.nf(),
        indices: m.idx.as_ptr(),
        index_count: m.idx.len(),
    }
}
