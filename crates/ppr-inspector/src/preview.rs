//! What the viewport shows: the preview mode, the reflection-pass toggles and the overlay.

use ppr_runtime::ReflectionSettings;

use crate::overlay_geometry::ColorBy;

/// The image under the overlay.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PreviewMode {
    /// The G-buffer colour, no reflections.
    Scene,
    /// The scene composited with pixel-projected reflections (`ppr-runtime`).
    #[default]
    Ppr,
    /// The scene composited with the exact mirrored-camera reflection.
    Reference,
    /// PPR against the reference over reflector pixels (black: equal, red: far apart).
    Difference,
}

impl PreviewMode {
    /// Every mode, in menu order.
    pub const ALL: [PreviewMode; 4] = [Self::Scene, Self::Ppr, Self::Reference, Self::Difference];

    /// The name shown in the UI.
    pub fn label(self) -> &'static str {
        match self {
            Self::Scene => "Scene",
            Self::Ppr => "PPR",
            Self::Reference => "Reference",
            Self::Difference => "Difference",
        }
    }

    /// Whether the mode needs the mirrored-camera reference rendered.
    pub fn needs_reference(self) -> bool {
        matches!(self, Self::Reference | Self::Difference)
    }
}

/// Everything that decides the viewport image apart from the camera and the set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreviewSettings {
    /// The image.
    pub mode: PreviewMode,
    /// Steps of the PPR reflection pass (holes, filtering, anti-bleeding).
    pub reflection: ReflectionSettings,
    /// Weight of the reflection on reflector pixels, `[0, 1]`.
    pub reflectivity: f32,
    /// Draw the rectangles over the image.
    pub overlay: bool,
    /// What the rectangles' colour shows.
    pub color_by: ColorBy,
    /// Rendered pixels per screen pixel (1, 1/2 or 1/4): lower is faster on slow adapters.
    pub resolution: f32,
}

impl Default for PreviewSettings {
    fn default() -> Self {
        Self {
            mode: PreviewMode::default(),
            reflection: ReflectionSettings::ALL,
            reflectivity: 0.8,
            overlay: true,
            color_by: ColorBy::Kind,
            resolution: 1.0,
        }
    }
}
