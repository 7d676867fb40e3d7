//! The human summary of a faces repair ([`super::FacesReport`]).

use super::FacesReport;
use std::fmt;

/// `n` ids, at most five of them named.
fn some(ids: &[String]) -> String {
    let mut s = ids.iter().take(5).cloned().collect::<Vec<_>>().join(", ");
    if ids.len() > 5 {
        s += &format!(", and {} more", ids.len() - 5);
    }
    s
}

impl fmt::Display for FacesReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "repair of a B-rep's faces (trims kept)")?;
        writeln!(
            f,
            "  faces: {} ({} trimmed, {} bounded by their surface's rectangle)",
            self.faces,
            self.trimmed_faces.len(),
            self.faces - self.trimmed_faces.len()
        )?;
        let s = &self.sewing;
        writeln!(
            f,
            "  connectivity: {} free edges before, {} after; {} edge pairs sewn, {} vertices merged (largest move {:.3e}); {} non-manifold",
            self.free_edges_before,
            self.free_edges_after,
            s.edges_sewn.len(),
            s.vertices_merged,
            s.max_vertex_move,
            self.non_manifold_edges.len()
        )?;
        writeln!(
            f,
            "  shells: {} ({} closed) before, {} ({} closed) after{}",
            self.shells_before,
            self.closed_shells_before,
            self.shells.len(),
            self.shells.iter().filter(|x| x.closed).count(),
            if s.shells_joined > 0 {
                format!("; {} joined to others by sewn edges", s.shells_joined)
            } else {
                String::new()
            }
        )?;
        let proven = match self.gap_max_proven {
            Some(g) => format!("largest proven {g:.3e}"),
            None => "not every gap proven".to_string(),
        };
        writeln!(
            f,
            "  gaps along {} shared edges: {} proven below u2; {proven}; largest {:.3e} (evidence where unproven); {} at or above u2",
            self.edges.len(),
            self.gaps_proven_below_u2,
            self.gap_max_evidence,
            self.gaps_left.len()
        )?;
        writeln!(f, "  feature edges: {}", self.feature_edges)?;
        if !self.gaps_left.is_empty() {
            writeln!(f, "  gaps left: {}", some(&self.gaps_left))?;
        }
        for n in &self.not_done {
            writeln!(f, "  NOT DONE: {n}")?;
        }
        writeln!(f, "  time {:.3} s", self.seconds)
    }
}
