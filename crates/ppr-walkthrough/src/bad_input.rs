//! Input the walkthrough cannot run with (a level or reflector set that is missing, invalid
//! or refused): the program exits with [`EXIT_BAD_INPUT`], the message naming the file.

/// Exit status for bad input (as `ppr-extract`'s).
pub const EXIT_BAD_INPUT: u8 = 2;
/// Exit status for any other failure (GPU, window, screenshot).
pub const EXIT_FAILURE: u8 = 1;

/// A level or set the walkthrough refuses; the message names the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BadInput(pub String);

impl std::fmt::Display for BadInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BadInput {}

/// The exit status for an error that stopped the run.
pub fn exit_status(error: &anyhow::Error) -> u8 {
    if error.chain().any(|cause| cause.is::<BadInput>()) { EXIT_BAD_INPUT } else { EXIT_FAILURE }
}
