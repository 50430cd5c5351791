//! Integration tests of `ppr-extract`: one binary, modules by subject.

mod checks;
mod cli;
mod demo_level;
mod fuzz_corpus;
mod level_size;
mod loading;
mod manual_edits;
mod near_planar;
mod roughness;
mod scaling;
mod scenes;
mod synthetic;
