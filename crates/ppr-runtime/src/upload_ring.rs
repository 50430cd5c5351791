//! Staging buffers for the frame uploads, reused frame after frame: a buffer written for
//! one encode comes back, mapped for writing again, once that encoder's commands have
//! been submitted and run. Creating a staging buffer a frame cost page faults and zeroing
//! of megabytes on every frame with thousands of shapes.

use std::sync::mpsc;

use crate::wgpu_compat::MappedRangeMut;

/// Smallest staging buffer: a frame of a few hundred shapes fits in one.
const MIN_BYTES: u64 = 1 << 20;
/// Most buffers kept waiting for a frame (the largest are kept).
const MAX_FREE: usize = 4;
/// Written into the gaps between parts.
static ZEROS: [u8; 4096] = [0; 4096];

pub(crate) struct UploadRing {
    device: wgpu::Device,
    /// Mapped for writing, ready.
    free: Vec<wgpu::Buffer>,
    sender: mpsc::Sender<wgpu::Buffer>,
    returned: mpsc::Receiver<wgpu::Buffer>,
    /// Buffers created so far (the tests check that frames reuse them).
    created: usize,
}

impl UploadRing {
    pub fn new(device: &wgpu::Device) -> Self {
        let (sender, returned) = mpsc::channel();
        Self { device: device.clone(), free: Vec::new(), sender, returned, created: 0 }
    }

    /// How many staging buffers the ring has created.
    pub fn created(&self) -> usize {
        self.created
    }

    /// A staging buffer of `size` bytes holding each of `parts` at its offset (in order of
    /// offset, apart, the last ending at `size`; each a whole number of 4-byte words) and
    /// zeros between them, for copies recorded in `encoder`; it comes back to the ring once
    /// `encoder`'s commands are submitted and done (one never submitted is dropped).
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
            None => {
                self.created += 1;
                self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("ppr frame upload"),
                    size: size.max(MIN_BYTES).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
                    usage: wgpu::BufferUsages::MAP_WRITE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: true,
                })
            }
        };
        {
            // One mapped range (a range's offset must be a multiple of 8); each part
            // written through its own slice of it, and each gap zeroed.
            let mut view = buffer.slice(..size).get_mapped_range_mut().into_view_mut();
            let mut end = 0;
            for &(offset, part) in parts {
                let offset = offset as usize;
                debug_assert!(offset >= end, "parts in order, apart");
                for start in (end..offset).step_by(ZEROS.len()) {
                    let len = ZEROS.len().min(offset - start);
                    view.slice(start..start + len).copy_from_slice(&ZEROS[..len]);
                }
                view.slice(offset..offset + part.len()).copy_from_slice(part);
                end = offset + part.len();
            }
            debug_assert_eq!(end as u64, size, "the last part ends the staged bytes");
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
}
