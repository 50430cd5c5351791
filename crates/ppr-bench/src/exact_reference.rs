//! The exact planar reflection (the scene rendered again from the mirrored camera of every
//! visible reflector plane, the testbed's `MirrorReference`) timed as a technique: the
//! accuracy ceiling of the comparison and what it costs.

use ppr_runtime::Camera;

use crate::technique::{BenchFrame, BenchTechnique, Family, ReflectionOutput};
use crate::timing::{EncoderTimer, PassTime};

/// Times the level renderer's reference passes with encoder timestamps.
pub struct ExactReference {
    timer: Option<EncoderTimer>,
}

impl ExactReference {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self { timer: EncoderTimer::new(device, queue) }
    }
}

/// Label of the exact reference in reports.
pub const EXACT_LABEL: &str = "exact";

impl BenchTechnique for ExactReference {
    fn label(&self) -> String {
        EXACT_LABEL.into()
    }

    fn family(&self) -> Family {
        Family::Exact
    }

    fn output(&self) -> ReflectionOutput {
        ReflectionOutput::Reference
    }

    fn prepare(
        &mut self,
        _device: &wgpu::Device,
        _queue: &wgpu::Queue,
        _camera: &Camera,
        _size: [u32; 2],
    ) -> String {
        "mirrored re-render per visible plane (prepared with the level)".into()
    }

    fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, frame: &BenchFrame<'_>) {
        if let Some(t) = &self.timer {
            t.begin(encoder);
        }
        frame.level.encode_reference(encoder);
        if let Some(t) = &self.timer {
            t.end(encoder);
        }
    }

    fn read_timings(&mut self, device: &wgpu::Device) -> Option<Vec<PassTime>> {
        let ms = self.timer.as_ref()?.read_ms(device)?;
        Some(vec![PassTime::new("mirrored views + resolve", ms)])
    }
}
