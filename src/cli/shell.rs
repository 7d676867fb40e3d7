//! `vericad completions SHELL` and `vericad man`: shell completion scripts and man pages,
//! generated from the command line's own definition (clap), so they list exactly the
//! commands and options there are.

use clap::CommandFactory;
use std::path::{Path, PathBuf};

/// Arguments of `vericad completions`.
#[derive(clap::Args, Debug)]
pub struct CompletionsArgs {
    /// The shell: bash, zsh, fish, elvish or powershell.
    pub shell: clap_complete::Shell,
}

/// Arguments of `vericad man`.
#[derive(clap::Args, Debug)]
pub struct ManArgs {
    /// Write `vericad.1` and one page per command (`vericad-ssi.1`, …) into this directory
    /// (created if missing); without it, `vericad.1` goes to standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Print the completion script; exit code 0.
pub fn completions(a: CompletionsArgs) -> i32 {
    let mut cmd = super::Cli::command();
    clap_complete::generate(a.shell, &mut cmd, "vericad", &mut std::io::stdout());
    0
}

fn render(cmd: clap::Command) -> std::io::Result<Vec<u8>> {
    let mut buf = Vec::new();
    clap_mangen::Man::new(cmd).render(&mut buf)?;
    Ok(buf)
}

fn write_pages(dir: &Path) -> std::io::Result<usize> {
    std::fs::create_dir_all(dir)?;
    let cmd = super::Cli::command();
    let mut n = 0;
    for sub in cmd.get_subcommands() {
        let name = format!("vericad-{}", sub.get_name());
        let page = render(sub.clone().name(name.clone()))?;
        crate::io::write_atomic(&dir.join(format!("{name}.1")), page)?;
        n += 1;
    }
    crate::io::write_atomic(&dir.join("vericad.1"), render(cmd)?)?;
    Ok(n + 1)
}

/// Print or write the man pages; exit code 0, or 1 when a page cannot be written.
pub fn man(a: ManArgs) -> i32 {
    match a.out {
        Some(dir) => match write_pages(&dir) {
            Ok(n) => {
                println!("wrote {n} man pages to {}", dir.display());
                0
            }
            Err(e) => {
                eprintln!("error: cannot write man pages to {}: {e}", dir.display());
                super::EXIT_FAILURE
            }
        },
        None => match render(super::Cli::command()) {
            Ok(page) => {
                use std::io::Write;
                let _ = std::io::stdout().write_all(&page);
                0
            }
            Err(e) => {
                eprintln!("error: {e}");
                super::EXIT_FAILURE
            }
        },
    }
}
