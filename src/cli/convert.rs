//! `vericad convert`: read a model, write it in the format of the output's extension (or
//! `--format`), print what was written.

use super::output::bad;
use super::{EXIT_BAD_INPUT, EXIT_FAILURE, EXIT_UNCERTIFIED};
use std::path::Path;

/// Run the command; returns the exit code.
pub(super) fn run(
    input: &Path,
    output: &Path,
    format: Option<&str>,
    (chordal, prove): (Option<f64>, bool),
    memory: &super::memory::MemoryArg,
) -> i32 {
    if let Err(e) = memory.watch("convert") {
        return bad(e);
    }
    let ext = crate::io::output_format(output, format);
    let mesh_format = crate::io::is_mesh_format(&ext);
    if let Some(tol) = chordal {
        if !(tol > 0.0 && tol.is_finite()) {
            eprintln!("error: --chordal {tol}: the tolerance must be a positive finite length");
            return EXIT_BAD_INPUT;
        }
        if !mesh_format {
            eprintln!(
                "error: --chordal applies to triangulated output (STL, OBJ, VTP), not to '{ext}'"
            );
            return EXIT_BAD_INPUT;
        }
    }
    let m = match crate::io::read_model(input) {
        Ok(m) => m,
        Err(e) => return bad(e),
    };
    match crate::io::write_model_chordal(output, &m, format, chordal, prove) {
        Ok((warnings, reached)) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            let unapplied = chordal.is_some() && reached.is_none();
            if unapplied {
                eprintln!(
                    "warning: --chordal not applied: the model has no B-rep faces to triangulate"
                );
            }
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
            match reached {
                Some(c) => {
                    let how = "sampled at 7 points per triangle and at edge midpoints: evidence, not a bound";
                    if let Some(p) = c.proven {
                        let without = match c.unbounded {
                            0 => String::new(),
                            n => format!(
                                "; {n} triangle(s) without a bound: a corner on an uncertain side of a knot line where the surface is not C2, a box out of the domain, no enclosure, or a face of more than {} triangles",
                                crate::tessellate::bound::MAX_TRIANGLES
                            ),
                        };
                        println!(
                            "chordal deviation proven <= {p:.3e} (triangles and surfaces within it of each other over every parameter triangle, from enclosures of the second derivatives and of the corners{without})"
                        );
                    }
                    match &c.unmet {
                        None => {
                            println!(
                                "chordal deviation measured {:.3e} <= {:e} after {} round(s) ({how})",
                                c.measured, c.tol, c.rounds
                            );
                            0
                        }
                        Some(why) => {
                            eprintln!(
                                "warning: chordal tolerance {:e} not reached: measured {:.3e} after {} round(s); {why}",
                                c.tol, c.measured, c.rounds
                            );
                            EXIT_UNCERTIFIED
                        }
                    }
                }
                None if unapplied => EXIT_UNCERTIFIED,
                None => 0,
            }
        }
        Err(e @ crate::io::WriteError::Io(..)) => {
            eprintln!("error: {e}");
            EXIT_FAILURE
        }
        Err(e) => bad(e),
    }
}
