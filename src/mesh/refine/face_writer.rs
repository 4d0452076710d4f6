//! A cursor that writes faces one after the other into CSR output (`offsets`, `indices`),
//! for the patterns whose faces are not a fixed block per parent element.

use crate::error::Result;
use crate::mesh::{idx, internal, set, MeshSizes};

/// Writes one face into the CSR output and advances the cursors.
pub(super) struct FaceWriter<'a> {
    offsets: &'a mut [u32],
    indices: &'a mut [u32],
    face: usize,
    corner: usize,
}

impl<'a> FaceWriter<'a> {
    pub(super) fn new(offsets: &'a mut [u32], indices: &'a mut [u32]) -> Result<Self> {
        set(offsets, 0, 0)?;
        Ok(FaceWriter {
            offsets,
            indices,
            face: 0,
            corner: 0,
        })
    }

    /// Appends corner `v` to the current face.
    #[inline]
    pub(super) fn push(&mut self, v: u32) -> Result<()> {
        set(self.indices, self.corner, v)?;
        self.corner += 1;
        Ok(())
    }

    /// Closes the current face.
    #[inline]
    pub(super) fn end_face(&mut self) -> Result<()> {
        self.face += 1;
        set(self.offsets, self.face, idx(self.corner)?)
    }

    /// Writes the face `vs`.
    #[inline]
    pub(super) fn face(&mut self, vs: &[u32]) -> Result<()> {
        for &v in vs {
            self.push(v)?;
        }
        self.end_face()
    }

    /// An internal error unless exactly `sizes` were written.
    pub(super) fn finish(&self, sizes: &MeshSizes) -> Result<()> {
        if self.face == sizes.faces && self.corner == sizes.indices {
            Ok(())
        } else {
            Err(internal())
        }
    }
}
