//! `ppr-bench`: parses the command line and runs one suite (see `ppr-bench --help`).

fn main() -> anyhow::Result<()> {
    match ppr_bench::cli::run_cli(std::env::args_os()) {
        Ok(files) => {
            for f in files {
                println!("wrote {}", f.display());
            }
            Ok(())
        }
        Err(ppr_bench::BenchError::Spec(message)) => {
            eprintln!("{message}");
            std::process::exit(2);
        }
        Err(e) => Err(e.into()),
    }
}
