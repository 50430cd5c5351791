//! Integration tests of the walkthrough (one test binary): the headless frame against the
//! testbed's frame of the same camera, hot reload, device-loss recovery, the command line.
//!
//! GPU tests run on whatever adapter wgpu finds (llvmpipe through the GL backend on
//! machines without a GPU); with no adapter they fail, they never skip.

mod command_line;
mod common;
mod composite;
mod device_loss;
mod headless_vs_testbed;
mod hot_reload;
mod previous_frame;
mod shared_scenes;
mod stereo;
