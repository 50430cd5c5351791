//! A pass's bind groups kept from frame to frame, found again by the resources they bind.
//!
//! Creating a bind group costs the CPU several microseconds (wgpu's validation and
//! tracking, the driver's descriptor set): the nine passes' five to eight a frame were
//! half of a small level's `encode` on the development VM. A frame's resources are mostly
//! the last frame's (the renderer's buffers are reused, a game's targets seldom change),
//! so each pass keeps the few it made last and returns one whose bindings are the same
//! buffers (with the same ranges), views and samplers. An entry not asked for in
//! [`MAX_IDLE_CALLS`] calls is dropped, with the resources it holds (a target the game
//! replaced on a resize is not kept alive longer than that).

use std::sync::Mutex;

/// Bind groups a pass keeps (a pass binds at most two sets of resources a frame: the clear
/// its main and atlas buffers, a stereo frame its two eyes' targets; across frames the two
/// slots by turns, and with a bound upload each of the two or three upload buffers of the
/// frames in flight: six combinations).
const CAPACITY: usize = 8;

/// Calls of [`BindGroupCache::get`] after which an entry no call matched is dropped.
pub(crate) const MAX_IDLE_CALLS: u64 = 8;

/// What one binding binds, by identity (wgpu's handles compare by the resource).
#[derive(Clone, Debug, PartialEq)]
enum Bound {
    Buffer(wgpu::Buffer, u64, Option<wgpu::BufferSize>),
    View(wgpu::TextureView),
    Sampler(wgpu::Sampler),
}

#[derive(Debug)]
struct Cached {
    key: Vec<(u32, Bound)>,
    group: wgpu::BindGroup,
    last_call: u64,
}

/// The bind groups of one pass (one layout), the most recently used last.
#[derive(Debug, Default)]
pub(crate) struct BindGroupCache {
    state: Mutex<(u64, Vec<Cached>)>,
}

impl BindGroupCache {
    /// A bind group for `desc` (whose layout must be this cache's pass's, always the same):
    /// a kept one that binds the same resources, else a new one, then kept.
    pub(crate) fn get(&self, device: &wgpu::Device, desc: &wgpu::BindGroupDescriptor<'_>) -> wgpu::BindGroup {
        let mut state = self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let (calls, kept) = &mut *state;
        *calls += 1;
        let call = *calls;
        kept.retain(|c| call - c.last_call <= MAX_IDLE_CALLS);
        let Some(key) = key_of(desc.entries) else {
            // Arrays and other kinds are not compared: made each time.
            return device.create_bind_group(desc);
        };
        if let Some(i) = kept.iter().position(|c| c.key == key) {
            let mut hit = kept.remove(i);
            hit.last_call = call;
            let group = hit.group.clone();
            kept.push(hit);
            return group;
        }
        let group = device.create_bind_group(desc);
        if kept.len() == CAPACITY {
            kept.remove(0);
        }
        kept.push(Cached { key, group: group.clone(), last_call: call });
        group
    }

    /// How many bind groups are kept (tests).
    #[cfg(test)]
    fn len(&self) -> usize {
        self.state.lock().map_or(0, |s| s.1.len())
    }
}

/// The bindings as comparable values, or `None` where one is of a kind not compared.
fn key_of(entries: &[wgpu::BindGroupEntry<'_>]) -> Option<Vec<(u32, Bound)>> {
    entries
        .iter()
        .map(|e| {
            let bound = match &e.resource {
                wgpu::BindingResource::Buffer(b) => Bound::Buffer(b.buffer.clone(), b.offset, b.size),
                wgpu::BindingResource::TextureView(v) => Bound::View((*v).clone()),
                wgpu::BindingResource::Sampler(s) => Bound::Sampler((*s).clone()),
                _ => return None,
            };
            Some((e.binding, bound))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_device::device;

    #[test]
    fn a_bind_group_is_made_again_only_for_other_resources_and_dropped_when_idle() {
        let device = device();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: None,
            entries: &[super::super::storage_entry(0, true)],
        });
        let buffer = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: 256,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        let (a, b) = (buffer("a"), buffer("b"));
        let cache = BindGroupCache::default();
        let get = |buffer: &wgpu::Buffer, size: Option<u64>| {
            let resource = wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: size.and_then(wgpu::BufferSize::new),
            });
            cache.get(
                &device,
                &wgpu::BindGroupDescriptor {
                    label: None,
                    layout: &layout,
                    entries: &[wgpu::BindGroupEntry { binding: 0, resource }],
                },
            )
        };
        let first = get(&a, None);
        assert_eq!(get(&a, None), first, "the same buffer: the kept group");
        assert_eq!(cache.len(), 1);
        let other = get(&b, None);
        assert_ne!(other, first, "another buffer: another group");
        let part = get(&a, Some(64));
        assert_ne!(part, first, "another range of the same buffer: another group");
        assert_eq!(get(&a, None), first, "kept beside the others");
        assert_eq!(cache.len(), 3);
        // `a` alone for longer than an idle entry is kept: `b`'s and the range's go.
        for _ in 0..MAX_IDLE_CALLS + 1 {
            assert_eq!(get(&a, None), first);
        }
        assert_eq!(cache.len(), 1, "idle entries dropped");
        assert_ne!(get(&b, None), other, "a dropped entry is made anew");
        // At most CAPACITY kept: the least recently used goes first.
        let more: Vec<wgpu::Buffer> = (0..CAPACITY).map(|_| buffer("more")).collect();
        for m in &more {
            get(m, None);
        }
        assert_eq!(cache.len(), CAPACITY);
        assert_ne!(get(&a, None), first, "the oldest entry made room");
    }
}
