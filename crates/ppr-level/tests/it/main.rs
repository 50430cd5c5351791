//! `ppr-level`'s integration tests: every shared scene, and malformed files built in code.

mod fuzz_corpus;
mod fuzz_findings;
mod malformed;
mod roughness_maps;
mod scenes;
