//! What differs between wgpu 29 and wgpu 30 in the calls this crate makes, behind one name.
//!
//! The same sources build `ppr-runtime` (wgpu 30) and `ppr-runtime-wgpu29` (wgpu 29, for
//! Bevy 0.19). Each difference is a trait implemented for both versions' types, so no
//! `cfg` is needed: whichever wgpu the crate links picks its impl.

/// `BufferSlice::get_mapped_range()`: a `BufferView` in wgpu 29, a `Result` of one in 30.
pub(crate) trait MappedRange {
    /// The view, or `None` where wgpu 30 reports the range could not be mapped.
    fn into_view(self) -> Option<wgpu::BufferView>;
}

impl MappedRange for wgpu::BufferView {
    fn into_view(self) -> Option<wgpu::BufferView> {
        Some(self)
    }
}

impl<E> MappedRange for Result<wgpu::BufferView, E> {
    fn into_view(self) -> Option<wgpu::BufferView> {
        self.ok()
    }
}

/// `BufferSlice::get_mapped_range_mut()`: a `BufferViewMut` in wgpu 29, a `Result` of one
/// in 30.
pub(crate) trait MappedRangeMut {
    /// The view of a slice known to be mapped for writing.
    ///
    /// # Panics
    /// Where wgpu 30 reports the range could not be mapped.
    fn into_view_mut(self) -> wgpu::BufferViewMut;
}

impl MappedRangeMut for wgpu::BufferViewMut {
    fn into_view_mut(self) -> wgpu::BufferViewMut {
        self
    }
}

impl<E: std::fmt::Debug> MappedRangeMut for Result<wgpu::BufferViewMut, E> {
    fn into_view_mut(self) -> wgpu::BufferViewMut {
        self.expect("a staging buffer of the upload ring is mapped for writing")
    }
}
