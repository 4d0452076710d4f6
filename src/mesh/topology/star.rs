//! Vertex stars: the spokes of a vertex counter-clockwise, from the star's first spoke (an
//! interior vertex's lowest-numbered outgoing half-edge; a boundary vertex's outgoing boundary
//! half-edge, closed by the incoming one), `h → twin(prev(h))` (module docs of
//! [`super`]).

use arrayvec::ArrayVec;

use super::Topology;
use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal, NONE};
use crate::MAX_VALENCE;

/// One spoke of a vertex star: an edge from the centre to a neighbour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spoke {
    /// The neighbour vertex.
    pub neighbour: u32,
    /// The edge id of the spoke.
    pub edge: u32,
    /// The half-edge from the centre to the neighbour, or [`NONE`] for the closing spoke of a
    /// boundary star (its edge exists only as the incoming boundary half-edge).
    pub half_edge: u32,
    /// The face between this spoke and the next one counter-clockwise, or [`NONE`] after the
    /// last spoke of a boundary star.
    pub face: u32,
}

/// Iterator over the spokes of a vertex star, counter-clockwise (see the module docs).
#[derive(Clone, Debug)]
pub struct Star<'t, 'm, 's> {
    topo: &'t Topology<'m, 's>,
    cur: u32,
    closing: u32,
    remaining: u32,
}

impl Iterator for Star<'_, '_, '_> {
    type Item = Spoke;

    fn next(&mut self) -> Option<Spoke> {
        if self.remaining == 0 {
            return None;
        }
        self.remaining -= 1;
        let t = self.topo;
        if self.cur == NONE {
            // Closing spoke of a boundary star: the incoming boundary half-edge b1 -> v.
            let p = self.closing;
            self.remaining = 0;
            return Some(Spoke {
                neighbour: t.origin(p).ok()?,
                edge: t.edge(p).ok()?,
                half_edge: NONE,
                face: NONE,
            });
        }
        let h = self.cur;
        // One face lookup gives the spoke's face, its end (next corner) and the previous
        // corner, whose twin is the next spoke.
        let f = get(t.face_of, h as usize).ok()?;
        let start = get(t.mesh.offsets, f as usize).ok()?;
        let end = get(t.mesh.offsets, f as usize + 1).ok()?;
        let next = if h + 1 == end { start } else { h + 1 };
        let p = if h == start {
            end.wrapping_sub(1)
        } else {
            h.wrapping_sub(1)
        };
        let spoke = Spoke {
            neighbour: get(t.mesh.indices, next as usize).ok()?,
            edge: get(t.edge_of, h as usize).ok()?,
            half_edge: h,
            face: f,
        };
        let tw = get(t.twin, p as usize).ok()?;
        if tw == NONE {
            self.cur = NONE;
            self.closing = p;
        } else {
            self.cur = tw;
        }
        Some(spoke)
    }
}

impl<'m, 's> Topology<'m, 's> {
    /// The spokes of `v`'s star, counter-clockwise (module docs).
    pub fn star<'t>(&'t self, v: u32) -> Star<'t, 'm, 's> {
        let cur = self.vertex_half_edge(v).unwrap_or(NONE);
        let remaining = if cur == NONE {
            0
        } else {
            get(self.valence, v as usize).unwrap_or(0)
        };
        Star {
            topo: self,
            cur,
            closing: NONE,
            remaining,
        }
    }

    /// The spokes of `v`'s star collected in a fixed-capacity array.
    pub fn spokes(&self, v: u32) -> Result<ArrayVec<Spoke, MAX_VALENCE>> {
        let mut out = ArrayVec::new();
        self.spokes_into(v, &mut out)?;
        Ok(out)
    }

    /// [`Topology::spokes`] into a reused buffer (the drivers: no 2 KB array returned per
    /// vertex).
    pub(crate) fn spokes_into(&self, v: u32, out: &mut ArrayVec<Spoke, MAX_VALENCE>) -> Result<()> {
        out.clear();
        for s in self.star(v) {
            out.try_push(s)
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        }
        if out.len() != self.valence(v)? {
            return Err(internal());
        }
        Ok(())
    }

    /// The neighbours of `v`, counter-clockwise (the star's order).
    pub fn ring(&self, v: u32) -> Result<ArrayVec<u32, MAX_VALENCE>> {
        let mut out = ArrayVec::new();
        for s in self.spokes(v)? {
            out.try_push(s.neighbour)
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        }
        Ok(out)
    }
}
