//! `ppr-level`'s integration tests: every shared scene, and malformed files built in code.

mod malformed;
mod roughness_maps;
mod scenes;
