//! Mapped buffers for the frame uploads, reused frame after frame: a buffer written for
//! one encode comes back, mapped for writing again, once that encoder's commands have
//! been submitted and run. Creating a buffer a frame cost page faults and zeroing of
//! megabytes on every frame with thousands of shapes.
//!
//! Two kinds: staging buffers, copied from into the frame buffers' upload buffer
//! ([`UploadRing::staging`]); and, on devices with `MAPPABLE_PRIMARY_BUFFERS`, buffers
//! laid out as that upload buffer, which the passes bind themselves
//! ([`UploadRing::bindable`]: no copy, and no barrier behind one).

use std::sync::mpsc;

use crate::wgpu_compat::MappedRangeMut;

/// Smallest staging buffer: a frame of a few hundred shapes fits in one.
const MIN_BYTES: u64 = 1 << 20;
/// Most buffers kept waiting for a frame (the largest are kept).
const MAX_FREE: usize = 4;
/// Written into the gaps between parts.
static ZEROS: [u8; 4096] = [0; 4096];

/// What a ring's buffers are.
enum RingKind {
    /// Copy sources of any size (at least [`MIN_BYTES`]); the gaps between parts zeroed
    /// (a copy takes them along).
    Staging,
    /// Bound by the passes as the upload buffer: `size` bytes each, `fixed` written once
    /// at its offset when a buffer is created (the parts no frame writes); the gaps between
    /// a frame's parts are left as they are (no pass reads them).
    Bindable { size: u64, fixed: (u64, Vec<u8>) },
}

pub(crate) struct UploadRing {
    device: wgpu::Device,
    kind: RingKind,
    /// Mapped for writing, ready.
    free: Vec<wgpu::Buffer>,
    sender: mpsc::Sender<wgpu::Buffer>,
    returned: mpsc::Receiver<wgpu::Buffer>,
    /// Buffers created so far (the tests check that frames reuse them).
    created: usize,
}

impl UploadRing {
    /// Staging buffers (`MAP_WRITE | COPY_SRC`).
    pub fn staging(device: &wgpu::Device) -> Self {
        Self::new(device, RingKind::Staging)
    }

    /// Buffers of `size` bytes that the passes bind as the upload buffer (`MAP_WRITE |
    /// UNIFORM | STORAGE`: the device must have `MAPPABLE_PRIMARY_BUFFERS`), each holding
    /// `fixed.1` at offset `fixed.0` from its creation on.
    pub fn bindable(device: &wgpu::Device, size: u64, fixed: (u64, Vec<u8>)) -> Self {
        debug_assert!(device.features().contains(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS));
        debug_assert!(fixed.0 + fixed.1.len() as u64 <= size);
        Self::new(device, RingKind::Bindable { size, fixed })
    }

    fn new(device: &wgpu::Device, kind: RingKind) -> Self {
        let (sender, returned) = mpsc::channel();
        Self { device: device.clone(), kind, free: Vec::new(), sender, returned, created: 0 }
    }

    /// How many buffers the ring has created.
    pub fn created(&self) -> usize {
        self.created
    }

    /// A buffer of at least `size` bytes holding each of `parts` at its offset (in order of
    /// offset, apart, the last ending at `size`; each a whole number of 4-byte words), with
    /// zeros between them in a staging buffer, for commands recorded in `encoder`; it comes
    /// back to the ring once `encoder`'s commands are submitted and done (one never
    /// submitted is dropped). A bindable ring's `size` is at most its buffers'.
    pub fn stage(
        &mut self,
        encoder: &wgpu::CommandEncoder,
        size: u64,
        parts: &[(u64, &[u8])],
    ) -> wgpu::Buffer {
        self.free.extend(self.returned.try_iter());
        if self.free.len() > MAX_FREE {
            self.free.sort_by_key(|b| std::cmp::Reverse(b.size()));
            self.free.truncate(MAX_FREE);
        }
        let buffer = match self.free.iter().position(|b| b.size() >= size) {
            Some(i) => self.free.swap_remove(i),
            None => self.create(size),
        };
        let zero_gaps = matches!(self.kind, RingKind::Staging);
        {
            // One mapped range (a range's offset must be a multiple of 8); each part
            // written through its own slice of it, and each gap zeroed where it is copied.
            let mut view = buffer.slice(..size).get_mapped_range_mut().into_view_mut();
            let mut end = 0;
            for &(offset, part) in parts {
                let offset = offset as usize;
                debug_assert!(offset >= end, "parts in order, apart");
                for start in (end..offset).step_by(ZEROS.len()).filter(|_| zero_gaps) {
                    let len = ZEROS.len().min(offset - start);
                    view.slice(start..start + len).copy_from_slice(&ZEROS[..len]);
                }
                view.slice(offset..offset + part.len()).copy_from_slice(part);
                end = offset + part.len();
            }
            debug_assert!(!zero_gaps || end as u64 == size, "the last part ends the staged bytes");
        }
        buffer.unmap();
        let (sender, back) = (self.sender.clone(), buffer.clone());
        encoder.map_buffer_on_submit(&buffer, wgpu::MapMode::Write, .., move |mapped| {
            if mapped.is_ok() {
                let _ = sender.send(back);
            }
        });
        buffer
    }

    /// A new buffer of the ring's kind for `size` bytes, mapped.
    fn create(&mut self, size: u64) -> wgpu::Buffer {
        self.created += 1;
        let (size, usage) = match &self.kind {
            RingKind::Staging => (
                size.max(MIN_BYTES).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
                wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::COPY_SRC,
            ),
            RingKind::Bindable { size: bytes, .. } => {
                debug_assert!(size <= *bytes, "a frame's parts fit the upload layout");
                let usage =
                    wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE;
                (*bytes, usage)
            }
        };
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ppr frame upload"),
            size,
            usage,
            mapped_at_creation: true,
        });
        if let RingKind::Bindable { fixed: (offset, bytes), .. } = &self.kind
            && !bytes.is_empty()
        {
            let range = *offset..*offset + bytes.len() as u64;
            buffer.slice(range).get_mapped_range_mut().into_view_mut().slice(..).copy_from_slice(bytes);
        }
        buffer
    }
}
