//! Integration tests of `ppr-extract`: one binary, modules by subject.

mod checks;
mod cli;
mod demo_level;
mod gltf_writer;
mod loading;
mod scenes;
mod synthetic;
