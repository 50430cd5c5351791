//! The wgpu-29 build of the runtime on the software adapter, held to the wgpu-30 build.

mod gpu29;
mod parity;
