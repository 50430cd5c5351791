//! Pixel-projected reflections in Bevy 0.19.
