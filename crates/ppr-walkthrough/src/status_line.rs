//! The on-screen lines: frame rate, the frame plan, PPR's GPU time per pass, the reflector
//! set's state (a refused file in red), the toggles and the keys.

use ppr_runtime::{FramePlan, PassTimings, ReflectionSettings};

use crate::hot_reload::SetStatus;
use crate::overlay_text::{TextColour, TextLine};
use crate::view_mode::ViewMode;

/// Everything the status lines show.
pub struct StatusInputs<'a> {
    pub adapter: &'a str,
    pub size: [u32; 2],
    /// Mean frame time over the last half second, milliseconds.
    pub frame_ms: Option<f64>,
    pub plan: Option<&'a FramePlan>,
    /// The last timings read (every half second); `timestamps` says whether the device has them.
    pub timings: Option<&'a PassTimings>,
    pub timestamps: bool,
    pub set_file: &'a str,
    pub set_status: &'a SetStatus,
    pub settings: ReflectionSettings,
    pub view: ViewMode,
    /// Fly speed, shown with the keys.
    pub speed: f64,
    /// Times the device was lost and recreated.
    pub device_recoveries: u32,
    /// Set when a frame was dropped for a surface problem (`"outdated"`, ...).
    pub surface_note: Option<&'a str>,
    /// Whether to list the keys (the window does, headless frames do not).
    pub keys: bool,
}

fn on_off(b: bool) -> &'static str {
    if b { "on" } else { "off" }
}

/// One line about the plan: what is visible and which passes run.
pub fn plan_line(plan: &FramePlan) -> String {
    let [w, h] = plan.viewport;
    let culled = format!(
        "culled {} back-side, {} off-screen, {} disabled{}",
        plan.culled_back_side,
        plan.culled_frustum,
        plan.disabled,
        if plan.transparent_skipped > 0 {
            format!(", {} glass skipped", plan.transparent_skipped)
        } else {
            String::new()
        }
    );
    if plan.is_empty() {
        return format!("plan {w}x{h}: nothing visible ({culled}); no pass dispatched");
    }
    let e = &plan.encoding;
    format!(
        "plan {w}x{h}: {} visible ({culled}); {}; occluders {}, coverage {:.0}%, encoding {}.{}/{}.{}",
        plan.visible.len(),
        plan.passes().join(" > "),
        on_off(plan.occluder_tests),
        plan.coverage * 100.0,
        e.major_int_bits,
        e.major_frac_bits,
        e.minor_int_bits,
        e.minor_frac_bits
    )
}

/// One line of GPU times per pass.
pub fn timings_line(timings: Option<&PassTimings>, timestamps: bool) -> String {
    match (timings, timestamps) {
        (_, false) => "GPU: no timestamps on this device".to_owned(),
        (None, true) => "GPU: (no pass ran)".to_owned(),
        (Some(t), true) => {
            let mut s = "GPU ms:".to_owned();
            for (name, ms) in t.passes() {
                if let Some(ms) = ms {
                    s.push_str(&format!(" {name} {ms:.3}"));
                }
            }
            s.push_str(&format!(" | total {:.3}", t.total_ms()));
            s
        }
    }
}

/// The set's line and its colour.
pub fn set_line(file: &str, status: &SetStatus) -> TextLine {
    match status {
        SetStatus::Waiting(why) => {
            TextLine::new(format!("set: waiting for {file} ({why})"), TextColour::Warning)
        }
        SetStatus::Current { reflectors, reloads, .. } => {
            let reloaded = match reloads.saturating_sub(1) {
                0 => String::new(),
                1 => ", reloaded once".to_owned(),
                n => format!(", reloaded {n} times"),
            };
            TextLine::new(format!("set: {file}: {reflectors} reflectors{reloaded}"), TextColour::Good)
        }
        SetStatus::Refused { message, keeping } => {
            let keeping = match keeping {
                Some(n) => format!("keeping the last good set ({n} reflectors)"),
                None => "no set in use".to_owned(),
            };
            TextLine::new(format!("set REFUSED, {keeping}: {message}"), TextColour::Error)
        }
    }
}

/// The lines, top to bottom.
pub fn status_lines(s: &StatusInputs<'_>) -> Vec<TextLine> {
    let fps = match s.frame_ms {
        Some(ms) if ms > 0.0 => format!("{:.0} fps ({ms:.1} ms)", 1000.0 / ms),
        _ => "-- fps".to_owned(),
    };
    let mut lines = vec![TextLine::new(
        format!("PPR walkthrough | {} | {}x{} | {fps}", s.adapter, s.size[0], s.size[1]),
        TextColour::Normal,
    )];
    lines.push(TextLine::new(
        s.plan.map_or_else(|| "plan: (none yet)".to_owned(), plan_line),
        TextColour::Normal,
    ));
    lines.push(TextLine::new(timings_line(s.timings, s.timestamps), TextColour::Normal));
    lines.push(set_line(s.set_file, s.set_status));
    let st = s.settings;
    lines.push(TextLine::new(
        format!(
            "[H] holes {}  [F] filtering {}  [B] anti-bleeding {}  [G] glossy {}  [V] view: {}{}",
            on_off(st.holes),
            on_off(st.filtering),
            on_off(st.anti_bleeding),
            on_off(st.glossy),
            s.view.label(),
            if s.keys { format!("  speed {:.2} m/s", s.speed) } else { String::new() }
        ),
        TextColour::Dim,
    ));
    if s.device_recoveries > 0 {
        lines.push(TextLine::new(
            format!("device lost and recreated {} time(s)", s.device_recoveries),
            TextColour::Warning,
        ));
    }
    if let Some(note) = s.surface_note {
        lines.push(TextLine::new(format!("surface: {note}"), TextColour::Warning));
    }
    if s.keys {
        lines.push(TextLine::new(
            "WASD move, Q/E down/up, Shift fast, right mouse look, wheel speed, C next camera, P feed previous frame, F9 lose device, Esc quit",
            TextColour::Dim,
        ));
    }
    lines
}

#[cfg(test)]
mod tests {
    use std::time::SystemTime;

    use super::*;

    fn inputs<'a>(status: &'a SetStatus, timings: Option<&'a PassTimings>) -> StatusInputs<'a> {
        StatusInputs {
            adapter: "llvmpipe (Gl)",
            size: [1280, 720],
            frame_ms: Some(20.0),
            plan: None,
            timings,
            timestamps: true,
            set_file: "room.ppr.json",
            set_status: status,
            settings: ReflectionSettings { filtering: false, ..ReflectionSettings::ALL },
            view: ViewMode::Final,
            speed: 2.0,
            device_recoveries: 0,
            surface_note: None,
            keys: true,
        }
    }

    #[test]
    fn shows_fps_timings_toggles_and_a_refused_set_in_red() {
        let refused =
            SetStatus::Refused { message: "field `reflectors[0].half_extents`".into(), keeping: Some(14) };
        let t = PassTimings {
            clear_ms: Some(0.01),
            projection_ms: Some(0.2),
            reflection_ms: Some(0.1),
            ..PassTimings::default()
        };
        let lines = status_lines(&inputs(&refused, Some(&t)));
        assert!(lines[0].text.contains("50 fps (20.0 ms)"), "{}", lines[0].text);
        assert_eq!(lines[2].text, "GPU ms: clear 0.010 projection 0.200 reflection 0.100 | total 0.310");
        assert_eq!(lines[3].colour, TextColour::Error);
        assert!(lines[3].text.contains("keeping the last good set (14 reflectors)"), "{}", lines[3].text);
        assert!(lines[4].text.contains("filtering off"), "{}", lines[4].text);
    }

    #[test]
    fn a_current_set_counts_its_reloads() {
        let current = SetStatus::Current { reflectors: 14, reloads: 3, at: SystemTime::now() };
        let line = set_line("room.ppr.json", &current);
        assert_eq!(line.text, "set: room.ppr.json: 14 reflectors, reloaded 2 times");
        assert_eq!(line.colour, TextColour::Good);
        assert_eq!(timings_line(None, false), "GPU: no timestamps on this device");
    }
}
