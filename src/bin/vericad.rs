//! The `vericad` command: argument parsing lives in the library (`vericad::cli`).

use clap::Parser;

fn main() {
    let cli = vericad::cli::Cli::parse();
    std::process::exit(vericad::cli::run(cli));
}
