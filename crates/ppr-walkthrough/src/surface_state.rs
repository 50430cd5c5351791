//! What the window does with its surface each frame: resize, minimise, and the outcomes of
//! acquiring a swapchain image, decided without a GPU so the rules are tested.
//!
//! - a resize only records the new size; the surface is configured once, before the next
//!   frame (a drag-resize sends many events);
//! - a minimised window renders nothing and the loop waits for events: a zero size
//!   (Windows), or hidden (X11 iconifies without a resize: `Window::is_minimized` or
//!   `WindowEvent::Occluded` say so);
//! - `Outdated`, `Suboptimal` and `Lost` reconfigure (`Lost` recreates the surface first);
//! - `Timeout` and `Occluded` skip the frame; `Validation` skips it and reconfigures.

/// The outcome of `Surface::get_current_texture`, without the texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AcquireOutcome {
    Success,
    Suboptimal,
    Timeout,
    Occluded,
    Outdated,
    Lost,
    Validation,
}

impl AcquireOutcome {
    /// The outcome of an acquire result.
    pub fn of(current: &wgpu::CurrentSurfaceTexture) -> Self {
        match current {
            wgpu::CurrentSurfaceTexture::Success(_) => Self::Success,
            wgpu::CurrentSurfaceTexture::Suboptimal(_) => Self::Suboptimal,
            wgpu::CurrentSurfaceTexture::Timeout => Self::Timeout,
            wgpu::CurrentSurfaceTexture::Occluded => Self::Occluded,
            wgpu::CurrentSurfaceTexture::Outdated => Self::Outdated,
            wgpu::CurrentSurfaceTexture::Lost => Self::Lost,
            wgpu::CurrentSurfaceTexture::Validation => Self::Validation,
        }
    }
}

/// What to do before recording a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BeforeFrame {
    /// The window has no area: render nothing, wait for the next event.
    SkipMinimised,
    /// (Re)configure the surface at this size, then render.
    Configure([u32; 2]),
    /// The surface is configured for the window's size: render.
    Render,
}

/// What to do with an acquire outcome.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AfterAcquire {
    /// Render into the image and present it.
    Render,
    /// Render and present this image, and reconfigure before the next frame.
    RenderThenReconfigure,
    /// Drop this frame; try again next time.
    Skip,
    /// Drop this frame and reconfigure before the next one.
    SkipAndReconfigure,
    /// Drop this frame, recreate the surface from the window, then configure it.
    RecreateSurface,
}

/// The window's size and whether the surface matches it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceState {
    window_size: [u32; 2],
    configured: Option<[u32; 2]>,
    hidden: bool,
    /// Acquires that failed in a row (reported on screen; the loop never gives up).
    pub failures_in_a_row: u32,
}

impl SurfaceState {
    /// A window of `size` whose surface is not configured yet.
    pub fn new(size: [u32; 2]) -> Self {
        Self { window_size: size, configured: None, hidden: false, failures_in_a_row: 0 }
    }

    /// The window was resized (or minimised: a zero size).
    pub fn resized(&mut self, size: [u32; 2]) {
        self.window_size = size;
    }

    /// The window's size.
    pub fn window_size(&self) -> [u32; 2] {
        self.window_size
    }

    /// The window was minimised or hidden (`true`), or shown again (`false`).
    pub fn set_hidden(&mut self, hidden: bool) {
        self.hidden = hidden;
    }

    /// Whether there is nothing to draw into: no area, or hidden.
    pub fn minimised(&self) -> bool {
        self.hidden || self.window_size[0] == 0 || self.window_size[1] == 0
    }

    /// Decides what happens before the frame is recorded.
    pub fn before_frame(&self) -> BeforeFrame {
        if self.minimised() {
            BeforeFrame::SkipMinimised
        } else if self.configured != Some(self.window_size) {
            BeforeFrame::Configure(self.window_size)
        } else {
            BeforeFrame::Render
        }
    }

    /// The surface was configured at `size`.
    pub fn configured(&mut self, size: [u32; 2]) {
        self.configured = Some(size);
    }

    /// The surface (or the device under it) is gone: configure again before rendering.
    pub fn invalidate(&mut self) {
        self.configured = None;
    }

    /// Decides what happens after an acquire.
    pub fn after_acquire(&mut self, outcome: AcquireOutcome) -> AfterAcquire {
        let action = match outcome {
            AcquireOutcome::Success => AfterAcquire::Render,
            AcquireOutcome::Suboptimal => AfterAcquire::RenderThenReconfigure,
            AcquireOutcome::Timeout | AcquireOutcome::Occluded => AfterAcquire::Skip,
            AcquireOutcome::Outdated | AcquireOutcome::Validation => AfterAcquire::SkipAndReconfigure,
            AcquireOutcome::Lost => AfterAcquire::RecreateSurface,
        };
        if matches!(action, AfterAcquire::Render | AfterAcquire::RenderThenReconfigure) {
            self.failures_in_a_row = 0;
        } else {
            self.failures_in_a_row += 1;
        }
        if matches!(
            action,
            AfterAcquire::RenderThenReconfigure
                | AfterAcquire::SkipAndReconfigure
                | AfterAcquire::RecreateSurface
        ) {
            self.invalidate();
        }
        action
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_resize_configures_once_before_the_next_frame() {
        let mut s = SurfaceState::new([800, 600]);
        assert_eq!(s.before_frame(), BeforeFrame::Configure([800, 600]));
        s.configured([800, 600]);
        assert_eq!(s.before_frame(), BeforeFrame::Render);
        for w in [801, 900, 1024] {
            s.resized([w, 700]);
        }
        assert_eq!(s.before_frame(), BeforeFrame::Configure([1024, 700]), "only the last size counts");
        s.configured([1024, 700]);
        assert_eq!(s.before_frame(), BeforeFrame::Render);
    }

    #[test]
    fn a_minimised_window_renders_nothing_until_restored() {
        let mut s = SurfaceState::new([800, 600]);
        s.configured([800, 600]);
        s.resized([0, 0]);
        assert_eq!(s.before_frame(), BeforeFrame::SkipMinimised);
        s.resized([800, 0]);
        assert_eq!(s.before_frame(), BeforeFrame::SkipMinimised);
        s.resized([800, 600]);
        assert_eq!(s.before_frame(), BeforeFrame::Render, "same size as configured: no reconfigure");
        // X11 iconifies without a resize.
        s.set_hidden(true);
        assert_eq!(s.before_frame(), BeforeFrame::SkipMinimised);
        s.set_hidden(false);
        assert_eq!(s.before_frame(), BeforeFrame::Render);
    }

    #[test]
    fn acquire_outcomes_map_to_the_documented_actions() {
        let cases = [
            (AcquireOutcome::Success, AfterAcquire::Render, BeforeFrame::Render),
            (
                AcquireOutcome::Suboptimal,
                AfterAcquire::RenderThenReconfigure,
                BeforeFrame::Configure([640, 480]),
            ),
            (AcquireOutcome::Timeout, AfterAcquire::Skip, BeforeFrame::Render),
            (AcquireOutcome::Occluded, AfterAcquire::Skip, BeforeFrame::Render),
            (AcquireOutcome::Outdated, AfterAcquire::SkipAndReconfigure, BeforeFrame::Configure([640, 480])),
            (
                AcquireOutcome::Validation,
                AfterAcquire::SkipAndReconfigure,
                BeforeFrame::Configure([640, 480]),
            ),
            (AcquireOutcome::Lost, AfterAcquire::RecreateSurface, BeforeFrame::Configure([640, 480])),
        ];
        for (outcome, action, next) in cases {
            let mut s = SurfaceState::new([640, 480]);
            s.configured([640, 480]);
            assert_eq!(s.after_acquire(outcome), action, "{outcome:?}");
            assert_eq!(s.before_frame(), next, "{outcome:?}");
        }
    }

    #[test]
    fn failures_are_counted_until_a_frame_renders() {
        let mut s = SurfaceState::new([640, 480]);
        s.after_acquire(AcquireOutcome::Timeout);
        s.after_acquire(AcquireOutcome::Outdated);
        assert_eq!(s.failures_in_a_row, 2);
        s.after_acquire(AcquireOutcome::Success);
        assert_eq!(s.failures_in_a_row, 0);
    }
}
