//! `ppr-format`'s integration tests: one binary, modules by subject.

mod format;
mod fuzz_corpus;
