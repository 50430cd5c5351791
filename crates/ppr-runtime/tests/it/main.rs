//! ppr-runtime integration tests (one binary): GPU parity and pass behaviour on the
//! software adapter.

mod encoding_parity;
mod gpu;
mod harness;
mod reflection;
mod scene;
mod tiles;
