//! STEP product structure (ISO 10303-44 and -43, AP203/AP214/AP242 assemblies): the tree of
//! `product_definition`s joined by `next_assembly_usage_occurrence`s (NAUO), each product's
//! shape through `shape_definition_representation` (and the representations joined to it by
//! `shape_representation_relationship`s without transformation), each occurrence's
//! placement from the `context_dependent_shape_representation` whose
//! `product_definition_shape` is the NAUO: a `representation_relationship_with_transformation`
//! whose `item_defined_transformation` is a pair of `axis2_placement_3d`s. The motion maps
//! the first placement onto the second (ISO 10303-43, `item_defined_transformation`):
//! `T = B ∘ A⁻¹` for frames `A` (`transform_item_1`) and `B` (`transform_item_2`), taking the
//! child representation's coordinates to the parent's; or a
//! `cartesian_transformation_operator_3d` (`super::transform_operator`: rotation, uniform
//! scale, mirroring) mapping rep_1's coordinates to rep_2's. When the relationship names the
//! parent as `rep_1` (reversed against the NAUO), the inverse is used. `mapped_item`s
//! (`representation_map` with `mapping_origin` `A`, `mapping_target` `B`) place their
//! representation by `B ∘ A⁻¹` likewise, or by `T ∘ A⁻¹` for an operator `T` as the target.
//! Nested occurrences compose their motions.
//!
//! The result is a list of placed occurrences (depth-first), each with the solids and shells
//! (STEP ids) its product's shape holds, and the warnings for what could not be placed.

use super::entities::Reader;
use super::part21::{Args, Inst, ListRefs};
mod motions;

use super::transform_operator::NAME as CTO;
use crate::brep::place::Motion;
use std::collections::{BTreeMap, BTreeSet};

/// Deepest assembly tree followed (deeper ones, and cycles, are reported).
const MAX_DEPTH: usize = 32;

/// One node of the tree as read: an occurrence of a product, placed.
#[derive(Clone, Debug)]
pub(super) struct Node {
    pub depth: usize,
    /// `#n` of the NAUO, or of the product definition for a root.
    pub source: String,
    /// The occurrence path from the root (`#54/#403`; the root's own id for a root).
    pub path: String,
    pub product: String,
    pub definition: String,
    pub motion: Motion,
    /// `(motion, solid ids, shell ids)`: the product's own shape items (mapped items each
    /// with their own motion).
    pub items: Vec<(Motion, Vec<u64>, Vec<u64>)>,
}

/// The product structure of a file with at least one NAUO or mapped item.
pub(super) struct Tree {
    pub nodes: Vec<Node>,
    pub warnings: Vec<String>,
}

struct Walker<'a> {
    r: &'a Reader<'a>,
    /// Metres per unit of the model's length unit (`None`: unknown, nothing is scaled).
    model_metres: Option<f64>,
    /// Representations already reported as scaled into the model's unit.
    scaled: BTreeSet<u64>,
    /// Representations of each product definition.
    reps: BTreeMap<u64, Vec<u64>>,
    /// Plain representation links (both directions).
    links: BTreeMap<u64, Vec<u64>>,
    /// NAUOs by parent definition: `(nauo, child definition)`.
    children: BTreeMap<u64, Vec<(u64, u64)>>,
    /// The shape representation relationship placing each NAUO.
    placing: BTreeMap<u64, u64>,
    nodes: Vec<Node>,
    warnings: Vec<String>,
}

fn str_at<'a>(a: Args<'a>, i: usize) -> Option<&'a str> {
    a.get(i)?.str()
}

/// The `items` of a representation instance (any `*REPRESENTATION` partial entity with a list
/// as its second attribute).
fn rep_items(e: Inst<'_>) -> Option<ListRefs<'_>> {
    e.parts().find_map(|(n, a)| {
        n.ends_with("REPRESENTATION")
            .then(|| a.get(1)?.list_refs())
            .flatten()
    })
}

/// Read the product structure, or `None` when the file has no NAUO and no mapped item.
pub(super) fn read(r: &Reader) -> Option<Tree> {
    let p = r.p;
    let mut w = Walker {
        r,
        model_metres: super::units::model_metres(p),
        scaled: BTreeSet::new(),
        reps: BTreeMap::new(),
        links: BTreeMap::new(),
        children: BTreeMap::new(),
        placing: BTreeMap::new(),
        nodes: Vec::new(),
        warnings: Vec::new(),
    };
    let mut any = false;
    let mut definitions = Vec::new();
    let mut is_child = BTreeSet::new();
    let mut in_cdsr = BTreeSet::new();
    let def_of_pds = |id: u64| {
        p.entities
            .inst(id)?
            .part("PRODUCT_DEFINITION_SHAPE")?
            .get(2)?
            .reference()
    };
    for (id, e) in p.entities.insts() {
        if e.is("PRODUCT_DEFINITION") {
            definitions.push(id);
        } else if let Some(a) = e.part("NEXT_ASSEMBLY_USAGE_OCCURRENCE") {
            any = true;
            match (a.get(3).and_then(|v| v.reference()), a.get(4).and_then(|v| v.reference())) {
                (Some(parent), Some(child)) => {
                    w.children.entry(parent).or_default().push((id, child));
                    is_child.insert(child);
                }
                _ => w.warnings.push(format!(
                    "assembly: NEXT_ASSEMBLY_USAGE_OCCURRENCE #{id}: relating or related product definition is not a reference; occurrence not placed"
                )),
            }
        } else if e.is("MAPPED_ITEM") {
            any = true;
        } else if let Some(a) = e.part("SHAPE_DEFINITION_REPRESENTATION") {
            if let (Some(d), Some(rep)) = (
                a.first().and_then(|v| v.reference()).and_then(def_of_pds),
                a.get(1).and_then(|v| v.reference()),
            ) {
                w.reps.entry(d).or_default().push(rep);
            }
        } else if let Some(a) = e.part("CONTEXT_DEPENDENT_SHAPE_REPRESENTATION")
            && let (Some(srr), Some(nauo)) = (
                a.first().and_then(|v| v.reference()),
                a.get(1).and_then(|v| v.reference()).and_then(def_of_pds),
            )
        {
            w.placing.insert(nauo, srr);
            in_cdsr.insert(srr);
        }
    }
    if !any {
        return None;
    }
    for (id, e) in p.entities.insts() {
        if let Some(a) = e.part("REPRESENTATION_RELATIONSHIP")
            && !e.is("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION")
            && !in_cdsr.contains(&id)
            && let (Some(r1), Some(r2)) = (
                a.get(2).and_then(|v| v.reference()),
                a.get(3).and_then(|v| v.reference()),
            )
        {
            w.links.entry(r1).or_default().push(r2);
            w.links.entry(r2).or_default().push(r1);
        }
    }
    for d in definitions {
        if !is_child.contains(&d) {
            w.visit(
                d,
                format!("#{d}"),
                String::new(),
                Motion::IDENTITY,
                &mut Vec::new(),
            );
        }
    }
    Some(Tree {
        nodes: w.nodes,
        warnings: w.warnings,
    })
}

impl Walker<'_> {
    fn name_of(&self, def: u64) -> String {
        let e = &self.r.p.entities;
        let formation = e
            .inst(def)
            .and_then(|x| x.part("PRODUCT_DEFINITION"))
            .and_then(|a| a.get(2)?.reference());
        let product = formation.and_then(|f| {
            let x = e.inst(f)?;
            let a = x
                .part("PRODUCT_DEFINITION_FORMATION")
                .or_else(|| x.part("PRODUCT_DEFINITION_FORMATION_WITH_SPECIFIED_SOURCE"))?;
            a.get(2)?.reference()
        });
        product
            .and_then(|pr| str_at(e.inst(pr)?.part("PRODUCT")?, 1).map(str::to_string))
            .unwrap_or_default()
    }

    /// The representations making up `rep` (itself and those joined by plain relationships).
    fn closure(&self, rep: u64) -> Vec<u64> {
        let mut seen = vec![rep];
        let mut i = 0;
        while i < seen.len() {
            for &n in self.links.get(&seen[i]).map_or(&[][..], |v| v) {
                if !seen.contains(&n) {
                    seen.push(n);
                }
            }
            i += 1;
        }
        seen
    }

    /// Solids, shells and mapped items of a definition's shape, placed by `m`; the items of a
    /// representation in another length unit than the model's scaled into it first.
    pub(super) fn items(
        &mut self,
        reps: &[u64],
        m: Motion,
        depth: usize,
        out: &mut Vec<(Motion, Vec<u64>, Vec<u64>)>,
    ) {
        let p = self.r.p;
        // `(factor, solids, shells)`, one group per length unit met.
        let mut groups: Vec<(f64, Vec<u64>, Vec<u64>)> = Vec::new();
        for &rep in reps {
            for rid in self.closure(rep) {
                let Some(items) = p.entities.inst(rid).and_then(rep_items) else {
                    continue;
                };
                let k = self.factor(rid);
                let g = match groups.iter().position(|g| g.0 == k) {
                    Some(i) => i,
                    None => {
                        groups.push((k, vec![], vec![]));
                        groups.len() - 1
                    }
                };
                for id in items.flatten() {
                    let Some(e) = p.entities.inst(id) else {
                        continue;
                    };
                    if e.is("MANIFOLD_SOLID_BREP") || e.is("BREP_WITH_VOIDS") {
                        groups[g].1.push(id);
                    } else if let Some(a) = e.part("SHELL_BASED_SURFACE_MODEL") {
                        let list = a.get(1).and_then(|v| v.list_refs()).unwrap_or_default();
                        groups[g].2.extend(list.flatten());
                    } else if let Some(a) = e.part("MAPPED_ITEM") {
                        self.mapped((id, a), k, m, depth, out);
                    }
                }
            }
        }
        for (k, solids, shells) in groups {
            if !solids.is_empty() || !shells.is_empty() {
                let placed = if k == 1.0 {
                    m
                } else {
                    m.then_after(&Motion {
                        rotation: Motion::IDENTITY.rotation.map(|r| r.map(|x| x * k)),
                        translation: [0.0; 3],
                    })
                };
                out.push((placed, solids, shells));
            }
        }
    }

    /// Visit definition `def` reached by occurrence `source` along `along` (the parent's
    /// occurrence path), placed by `m`; `path`: the definitions above (cycle guard).
    fn visit(&mut self, def: u64, source: String, along: String, m: Motion, path: &mut Vec<u64>) {
        let depth = path.len();
        if path.contains(&def) || depth > MAX_DEPTH {
            self.warnings.push(format!(
                "assembly: {source}: product definition #{def} is its own ancestor or nested deeper than {MAX_DEPTH}; not placed"
            ));
            return;
        }
        let reps = self.reps.get(&def).cloned().unwrap_or_default();
        let mut items = Vec::new();
        self.items(&reps, m, 0, &mut items);
        let here = if depth <= 1 {
            source.clone()
        } else {
            format!("{along}/{source}")
        };
        self.nodes.push(Node {
            depth,
            source,
            path: here.clone(),
            product: self.name_of(def),
            definition: format!("#{def}"),
            motion: m,
            items,
        });
        path.push(def);
        for (nauo, child) in self.children.get(&def).cloned().unwrap_or_default() {
            let t = self.occurrence_motion(nauo, child);
            self.visit(
                child,
                format!("#{nauo}"),
                here.clone(),
                m.then_after(&t),
                path,
            );
        }
        path.pop();
    }
}
