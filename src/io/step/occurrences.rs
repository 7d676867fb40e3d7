//! The model of a STEP assembly: every occurrence of a part becomes its own placed copy of
//! the part's solids and shells ([`crate::brep::place`]), so a part placed twice appears
//! twice and the un-placed part not at all. Solids, shells and faces that no product's shape
//! holds are kept where the file puts them, with a warning naming them.

use super::assembly::Tree;
use crate::brep::Occurrence;
use crate::brep::place::{self, Motion, Placement};
use crate::model::Model;
use std::collections::{BTreeMap, BTreeSet};

/// Replace the model's B-rep and surfaces by the placed occurrences of `tree`.
pub(super) fn apply(model: &mut Model, tree: Tree) {
    model.warnings.extend(tree.warnings);
    let Some(brep) = model.brep.take() else {
        return;
    };
    let solid_of: BTreeMap<&str, usize> = brep
        .solids
        .iter()
        .enumerate()
        .map(|(i, s)| (s.source.as_str(), i))
        .collect();
    let shell_of: BTreeMap<&str, usize> = brep
        .shells
        .iter()
        .enumerate()
        .map(|(i, s)| (s.source.as_str(), i))
        .collect();
    let mut placements = Vec::new();
    // Which placements belong to each node.
    let mut owner = Vec::new();
    let mut used_solids = BTreeSet::new();
    let mut used_shells = BTreeSet::new();
    let mut missing = Vec::new();
    for (n, node) in tree.nodes.iter().enumerate() {
        for (m, solids, shells) in &node.items {
            let mut p = Placement {
                motion: *m,
                solids: vec![],
                shells: vec![],
                faces: vec![],
                label: format!(" @ {}", node.path),
            };
            for id in solids {
                match solid_of.get(format!("#{id}").as_str()) {
                    Some(&i) => {
                        used_solids.insert(i);
                        p.solids.push(i)
                    }
                    None => missing.push(format!("#{id}")),
                }
            }
            for id in shells {
                match shell_of.get(format!("#{id}").as_str()) {
                    Some(&i) => {
                        used_shells.insert(i);
                        p.shells.push(i)
                    }
                    None => missing.push(format!("#{id}")),
                }
            }
            placements.push(p);
            owner.push(n);
        }
    }
    if !missing.is_empty() {
        model.warnings.push(format!(
            "assembly: {} solid(s)/shell(s) of product shapes were not read as topology (see the topology report): {}",
            missing.len(),
            crate::model::list_ids(missing.iter().cloned())
        ));
    }
    // Items of the B-rep that no product's shape holds: kept in place.
    let mut loose = Placement {
        motion: Motion::IDENTITY,
        solids: vec![],
        shells: vec![],
        faces: vec![],
        label: String::new(),
    };
    for (i, s) in brep.solids.iter().enumerate() {
        if used_solids.contains(&i) {
            used_shells.extend(std::iter::once(s.outer).chain(s.voids.iter().copied()));
        }
    }
    let in_solid: BTreeSet<usize> = brep
        .solids
        .iter()
        .flat_map(|s| std::iter::once(s.outer).chain(s.voids.iter().copied()))
        .collect();
    loose.solids = (0..brep.solids.len())
        .filter(|i| !used_solids.contains(i))
        .collect();
    loose.shells = (0..brep.shells.len())
        .filter(|i| !used_shells.contains(i) && !in_solid.contains(i))
        .collect();
    let in_shell: BTreeSet<usize> = brep
        .shells
        .iter()
        .flat_map(|s| s.faces.iter().map(|f| f.0))
        .collect();
    let loose_faces: Vec<usize> = (0..brep.faces.len())
        .filter(|i| !in_shell.contains(i))
        .collect();
    if !loose.solids.is_empty() || !loose.shells.is_empty() || !loose_faces.is_empty() {
        model.warnings.push(format!(
            "assembly: {} solid(s), {} shell(s) and {} face(s) belong to no product's shape; kept unplaced: {}",
            loose.solids.len(),
            loose.shells.len(),
            loose_faces.len(),
            crate::model::list_ids(
                loose
                    .solids
                    .iter()
                    .map(|&i| brep.solids[i].source.clone())
                    .chain(loose.shells.iter().map(|&i| brep.shells[i].source.clone()))
                    .chain(loose_faces.iter().map(|&i| brep.faces[i].source.clone()))
            )
        ));
    }
    loose.faces = loose_faces;
    placements.push(loose);
    let (mut placed_brep, surfaces, placed) = place::place(&brep, &model.surfaces, &placements);
    let mut occurrences: Vec<Occurrence> = tree
        .nodes
        .iter()
        .map(|n| Occurrence {
            depth: n.depth,
            source: n.source.clone(),
            path: n.path.clone(),
            product: n.product.clone(),
            definition: n.definition.clone(),
            motion: n.motion,
            solids: vec![],
            shells: vec![],
        })
        .collect();
    for (k, r) in placed.iter().enumerate() {
        if let Some(&n) = owner.get(k) {
            occurrences[n].solids.extend(&r.solids);
            occurrences[n].shells.extend(&r.shells);
        }
    }
    placed_brep.occurrences = occurrences;
    model.surfaces = surfaces;
    model.brep = Some(placed_brep);
}
