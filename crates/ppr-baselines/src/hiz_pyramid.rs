//! The min-depth pyramid of Hi-Z SSR: level 0 is each pixel's linear view depth and every
//! further texel is the minimum of its children (see `hiz_build.wgsl`). The levels live in
//! one `R32Float` atlas texture (level 0 at the origin, the others stacked in a column to
//! its right; `hiz_layout.wgsl`), with the uniforms and bind groups that build it.

use crate::error::BaselineError;
use crate::passes::HiZBuildPass;

/// Format of the pyramid: linear view depth, metres (sky: [`SKY_DEPTH`]).
pub const HIZ_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// Linear view depth the pyramid stores where nothing was drawn (`BASELINE_SKY_DEPTH`).
pub const SKY_DEPTH: f32 = 1e30;

/// Most levels a pyramid has (`HIZ_MAX_LEVELS` in `hiz_layout.wgsl`): viewports up to
/// 65535 pixels a side.
pub const HIZ_MAX_LEVELS: usize = 16;

/// `HiZLevels` of `hiz_layout.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct HiZLevelsUniform {
    /// Per level: origin x, y in the atlas, width, height.
    pub rects: [[u32; 4]; HIZ_MAX_LEVELS],
    /// Levels in use.
    pub count: u32,
    /// Padding.
    pub _pad: [u32; 3],
}
const _: () = assert!(size_of::<HiZLevelsUniform>() == 272);

/// `DownsampleParams` of `hiz_build.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DownsampleUniform {
    /// The level written (≥ 1).
    pub level: u32,
    /// Padding.
    pub _pad: [u32; 3],
}
const _: () = assert!(size_of::<DownsampleUniform>() == 16);

/// The pyramid of one viewport size.
///
/// Invariant: `rects.len() == levels` and `downsample_groups.len() == levels - 1`.
pub struct HiZPyramid {
    size: [u32; 2],
    rects: Vec<[u32; 4]>,
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    levels_uniform: wgpu::Buffer,
    downsample_groups: Vec<wgpu::BindGroup>,
}

impl HiZPyramid {
    /// Levels of the full chain for `size`: down to 1 × 1.
    pub fn level_count(size: [u32; 2]) -> u32 {
        32 - size[0].max(size[1]).max(1).leading_zeros()
    }

    /// Width and height of `level` for a base of `size` (halved, rounded down, at least 1).
    pub fn level_size(size: [u32; 2], level: u32) -> [u32; 2] {
        [(size[0] >> level).max(1), (size[1] >> level).max(1)]
    }

    /// Where each level lies in the atlas: `[x, y, width, height]`.
    pub fn level_rects(size: [u32; 2]) -> Vec<[u32; 4]> {
        let mut y = 0;
        (0..Self::level_count(size))
            .map(|l| {
                let [w, h] = Self::level_size(size, l);
                if l == 0 {
                    return [0, 0, w, h];
                }
                let rect = [size[0], y, w, h];
                y += h;
                rect
            })
            .collect()
    }

    /// Width and height of the atlas holding every level.
    pub fn atlas_size(size: [u32; 2]) -> [u32; 2] {
        Self::level_rects(size).iter().fold([1, 1], |[w, h], r| [w.max(r[0] + r[2]), h.max(r[1] + r[3])])
    }

    /// Allocates the pyramid for `size` and the bind groups of `build`'s downsampling.
    ///
    /// # Panics
    /// If `size` is larger than 65535 pixels a side.
    pub fn new(device: &wgpu::Device, build: &HiZBuildPass, size: [u32; 2]) -> Self {
        let size = [size[0].max(1), size[1].max(1)];
        let rects = Self::level_rects(size);
        assert!(rects.len() <= HIZ_MAX_LEVELS, "{size:?} needs more than {HIZ_MAX_LEVELS} Hi-Z levels");
        let [aw, ah] = Self::atlas_size(size);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("hi-z pyramid atlas"),
            size: wgpu::Extent3d { width: aw, height: ah, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: HIZ_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("hi-z pyramid atlas"),
            ..Default::default()
        });
        let mut uniform = HiZLevelsUniform { rects: [[0; 4]; HIZ_MAX_LEVELS], count: 0, _pad: [0; 3] };
        uniform.rects[..rects.len()].copy_from_slice(&rects);
        uniform.count = rects.len() as u32;
        let levels_uniform = uniform_buffer(device, "hi-z levels", bytemuck::bytes_of(&uniform));
        let downsample_groups = (1..rects.len() as u32)
            .map(|level| {
                let params = DownsampleUniform { level, _pad: [0; 3] };
                let buffer = uniform_buffer(device, "hi-z downsample level", bytemuck::bytes_of(&params));
                build.downsample_bind_group(device, &levels_uniform, &buffer, &view)
            })
            .collect();
        Self { size, rects, texture, view, levels_uniform, downsample_groups }
    }

    /// Width and height of level 0.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Number of levels.
    pub fn levels(&self) -> u32 {
        self.rects.len() as u32
    }

    /// The atlas (what the build writes and the trace reads).
    pub fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// The `HiZLevels` uniform of this pyramid.
    pub fn levels_uniform(&self) -> &wgpu::Buffer {
        &self.levels_uniform
    }

    /// The bind groups building levels 1, 2, … from the level below.
    pub fn downsample_groups(&self) -> &[wgpu::BindGroup] {
        &self.downsample_groups
    }

    /// Reads `level` back (rows top to bottom; waits for the GPU). For tests and tools.
    ///
    /// # Errors
    /// [`BaselineError::NoSuchLevel`] or [`BaselineError::Readback`].
    pub fn read_level(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        level: u32,
    ) -> Result<Vec<f32>, BaselineError> {
        let &[x, y, w, h] = self
            .rects
            .get(level as usize)
            .ok_or(BaselineError::NoSuchLevel { level, levels: self.levels() })?;
        let row = w * 4;
        let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("hi-z readback"),
            size: u64::from(padded) * u64::from(h),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("hi-z readback") });
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.texture,
                mip_level: 0,
                origin: wgpu::Origin3d { x, y, z: 0 },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
        queue.submit([encoder.finish()]);
        let err = |reason: String| BaselineError::Readback { what: format!("hi-z level {level}"), reason };
        let (tx, rx) = std::sync::mpsc::channel();
        buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            // The receiver waits below; a send error only means it gave up already.
            let _ = tx.send(r);
        });
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| err(e.to_string()))?;
        rx.recv().map_err(|e| err(e.to_string()))?.map_err(|e| err(e.to_string()))?;
        let values = {
            let bytes = buffer.get_mapped_range(..).map_err(|e| err(e.to_string()))?;
            bytes
                .chunks_exact(padded as usize)
                .flat_map(|r| {
                    r[..row as usize].chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                })
                .collect()
        };
        buffer.unmap();
        Ok(values)
    }
}

fn uniform_buffer(device: &wgpu::Device, label: &str, contents: &[u8]) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::UNIFORM,
    })
}

#[cfg(test)]
mod tests {
    use super::HiZPyramid;

    /// The levels tile the atlas without overlap, level 0 at the origin.
    #[test]
    fn level_rects_do_not_overlap() {
        for size in [[1, 1], [1, 7], [151, 97], [256, 192], [3840, 2160], [7680, 4320], [5, 300]] {
            let rects = HiZPyramid::level_rects(size);
            assert_eq!(rects[0], [0, 0, size[0], size[1]]);
            assert_eq!(rects.last().map(|r| [r[2], r[3]]), Some([1, 1]), "{size:?}");
            let [aw, ah] = HiZPyramid::atlas_size(size);
            for (i, a) in rects.iter().enumerate() {
                assert!(a[0] + a[2] <= aw && a[1] + a[3] <= ah, "{size:?}: level {i} outside the atlas");
                for b in &rects[..i] {
                    let apart = a[0] >= b[0] + b[2]
                        || b[0] >= a[0] + a[2]
                        || a[1] >= b[1] + b[3]
                        || b[1] >= a[1] + a[3];
                    assert!(apart, "{size:?}: {a:?} overlaps {b:?}");
                }
            }
        }
    }
}
