//! `vericad convert`: read a model, write it in the format of the output's extension (or
//! `--format`), print what was written.

use super::EXIT_FAILURE;
use super::output::bad;
use std::path::Path;

/// Run the command; returns the exit code.
pub(super) fn run(
    input: &Path,
    output: &Path,
    format: Option<&str>,
    memory: &super::memory::MemoryArg,
) -> i32 {
    if let Err(e) = memory.watch("convert") {
        return bad(e);
    }
    let m = match crate::io::read_model(input) {
        Ok(m) => m,
        Err(e) => return bad(e),
    };
    match crate::io::write_model_as(output, &m, format) {
        Ok(warnings) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            let ext = format.map(str::to_string).unwrap_or_else(|| {
                output
                    .extension()
                    .and_then(|e| e.to_str())
                    .unwrap_or("")
                    .to_string()
            });
            let mesh_format = matches!(
                ext.to_ascii_lowercase().as_str(),
                "stl" | "stl-binary" | "vtp" | "obj"
            );
            match m.brep.as_ref().filter(|_| mesh_format) {
                Some(b) => println!(
                    "wrote {} ({} B-rep faces triangulated inside their trims)",
                    output.display(),
                    b.faces.len()
                ),
                None => println!(
                    "wrote {} ({} surfaces, {} curves)",
                    output.display(),
                    m.surfaces.len(),
                    m.curves.len()
                ),
            }
            0
        }
        Err(e @ crate::io::WriteError::Io(..)) => {
            eprintln!("error: {e}");
            EXIT_FAILURE
        }
        Err(e) => bad(e),
    }
}
