//! What the screen shows: the game's image or one of PPR's buffers (the `V` key cycles).

use crate::composite_pass::CompositeMode;

/// What the screen shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ViewMode {
    /// The scene with reflections composited.
    #[default]
    Final,
    /// PPR's raw output: reflected colour, holes dark purple.
    Reflection,
    /// PPR's raw intermediate buffer: the encoded offsets, black where nothing was written.
    Intermediate,
    /// The forward pass's reflection weight (reflectivity × Fresnel).
    Weight,
}

impl ViewMode {
    /// The next mode in the `V` key's cycle.
    pub fn next(self) -> Self {
        match self {
            Self::Final => Self::Reflection,
            Self::Reflection => Self::Intermediate,
            Self::Intermediate => Self::Weight,
            Self::Weight => Self::Final,
        }
    }

    /// Short name for the status line.
    pub fn label(self) -> &'static str {
        match self {
            Self::Final => "final",
            Self::Reflection => "reflection buffer",
            Self::Intermediate => "intermediate buffer",
            Self::Weight => "reflection weight",
        }
    }

    /// The composite's mode, or `None` for the intermediate-buffer view (its own pass).
    pub fn composite_mode(self) -> Option<CompositeMode> {
        match self {
            Self::Final => Some(CompositeMode::Final),
            Self::Reflection => Some(CompositeMode::ReflectionBuffer),
            Self::Weight => Some(CompositeMode::ReflectionWeight),
            Self::Intermediate => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cycle_visits_every_mode_once() {
        let mut seen = vec![ViewMode::Final];
        let mut m = ViewMode::Final.next();
        while m != ViewMode::Final {
            assert!(!seen.contains(&m));
            seen.push(m);
            m = m.next();
        }
        assert_eq!(seen.len(), 4);
    }
}
