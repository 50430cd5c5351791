//! `ppr-walkthrough`: parses the command line and runs the walkthrough.

use clap::Parser;

fn main() -> anyhow::Result<()> {
    ppr_walkthrough::run(ppr_walkthrough::Args::parse())
}
