//! The motions that place representations: frames, operators and occurrences, every length
//! in the model's unit (`super::units`): a frame or operator of a representation whose
//! length unit differs from the model's has its origin converted (the factor `k`, model units
//! per unit of that representation), and the items of such a representation are scaled by
//! `k` where they are placed ([`Walker::items`]).

use super::{CTO, MAX_DEPTH, Walker};
use crate::brep::place::Motion;
use crate::io::step::part21::Args;

impl Walker<'_> {
    /// Model units per length unit of representation `rep`: 1 where the units agree or
    /// either is unknown.
    pub(super) fn factor(&mut self, rep: u64) -> f64 {
        let Some(model) = self.model_metres else {
            return 1.0;
        };
        let p = self.r.p;
        match super::super::units::rep_metres(p, rep) {
            Some(m) if m != model => {
                if self.scaled.insert(rep) {
                    self.warnings.push(format!(
                        "assembly: representation #{rep} is in a length unit of {m:e} m, the model's is {model:e} m: its geometry and placements are scaled by {}",
                        m / model
                    ));
                }
                m / model
            }
            _ => 1.0,
        }
    }

    /// [`Walker::factor`] of the representation at attribute `i` of a relationship.
    fn rep_factor(&mut self, rr: Args, i: usize) -> f64 {
        rr.get(i)
            .and_then(|v| v.reference())
            .map_or(1.0, |r| self.factor(r))
    }

    /// A frame's motion (world frame to the `axis2_placement_3d`), its origin in model units
    /// (`k`: model units per unit of the representation the frame belongs to).
    fn frame(&self, id: u64, k: f64) -> Result<Motion, String> {
        let f = self
            .r
            .placement(id)
            .map_err(|e| format!("{}: {}", e.location, e.reason))?;
        Ok(Motion::from_frame(f.o.map(|x| x * k), f.x, f.y, f.z))
    }

    /// `B ∘ A⁻¹` for the frames `a` (in a representation of factor `ka`) and `b` (`kb`).
    fn map_frames(&self, (a, ka): (u64, f64), (b, kb): (u64, f64)) -> Result<Motion, String> {
        Ok(self
            .frame(b, kb)?
            .then_after(&self.frame(a, ka)?.inverse_rigid()))
    }

    /// A `cartesian_transformation_operator_3d` whose image lies in a representation of
    /// factor `k`: its origin in model units (its scale stays the operator's own).
    fn operator(&self, id: u64, k: f64) -> Result<Motion, String> {
        let t = self
            .r
            .transformation_operator(id)
            .map_err(|e| format!("{}: {}", e.location, e.reason))?;
        Ok(Motion {
            translation: t.translation.map(|x| x * k),
            ..t
        })
    }

    /// A mapped item `id` (attributes `a`) of a representation of factor `k`, inside a shape
    /// placed by `m`: its representation placed by `m ∘ B ∘ A⁻¹` (or `m ∘ T ∘ A⁻¹`).
    pub(super) fn mapped(
        &mut self,
        (id, a): (u64, Args),
        k: f64,
        m: Motion,
        depth: usize,
        out: &mut Vec<(Motion, Vec<u64>, Vec<u64>)>,
    ) {
        let map = a
            .get(1)
            .and_then(|v| v.reference())
            .and_then(|r| self.r.p.entities.inst(r)?.part("REPRESENTATION_MAP"));
        let (Some(map), Some(target)) = (map, a.get(2).and_then(|v| v.reference())) else {
            self.warnings.push(format!(
                "assembly: MAPPED_ITEM #{id}: mapping_source is not a REPRESENTATION_MAP or mapping_target not a reference; not placed"
            ));
            return;
        };
        let (Some(origin), Some(rep)) = (
            map.first().and_then(|v| v.reference()),
            map.get(1).and_then(|v| v.reference()),
        ) else {
            self.warnings.push(format!(
                "assembly: MAPPED_ITEM #{id}: its REPRESENTATION_MAP is malformed; not placed"
            ));
            return;
        };
        if depth >= MAX_DEPTH {
            self.warnings.push(format!(
                "assembly: MAPPED_ITEM #{id}: nested deeper than {MAX_DEPTH} (a cycle?); not placed"
            ));
            return;
        }
        let km = self.factor(rep);
        let to_target = if self.r.p.entities.inst(target).is_some_and(|e| e.is(CTO)) {
            // `T ∘ A⁻¹`: the origin frame onto the operator's image of the world frame.
            self.operator(target, k)
                .and_then(|t| Ok(t.then_after(&self.frame(origin, km)?.inverse_rigid())))
        } else {
            self.map_frames((origin, km), (target, k))
        };
        match to_target {
            Ok(t) => self.items(&[rep], m.then_after(&t), depth + 1, out),
            Err(e) => self
                .warnings
                .push(format!("assembly: MAPPED_ITEM #{id}: {e}; not placed")),
        }
    }

    /// The motion of occurrence `nauo` placing `child` in its parent: from the child's
    /// representation to the parent's.
    pub(super) fn occurrence_motion(&mut self, nauo: u64, child: u64) -> Motion {
        let Some(&srr) = self.placing.get(&nauo) else {
            self.warnings.push(format!(
                "assembly: NEXT_ASSEMBLY_USAGE_OCCURRENCE #{nauo} has no CONTEXT_DEPENDENT_SHAPE_REPRESENTATION; placed without motion"
            ));
            return Motion::IDENTITY;
        };
        let p = self.r.p;
        let e = p.entities.inst(srr);
        let rr = e.and_then(|e| e.part("REPRESENTATION_RELATIONSHIP"));
        let wt = e.and_then(|e| e.part("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION"));
        let (Some(rr), Some(wt)) = (rr, wt) else {
            self.warnings.push(format!(
                "assembly: #{srr} (placing #{nauo}) is not a REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION; placed without motion"
            ));
            return Motion::IDENTITY;
        };
        let op = wt.first().and_then(|v| v.reference());
        if let Some(op) = op.filter(|o| p.entities.inst(*o).is_some_and(|e| e.is(CTO))) {
            // A functionally defined transformation maps rep_1's coordinates to rep_2's.
            let k2 = self.rep_factor(rr, 3);
            return match self.operator(op, k2) {
                Ok(t) => self.towards_parent(srr, nauo, child, rr, t, Motion::inverse),
                Err(e) => {
                    self.warnings.push(format!(
                        "assembly: {e} ({CTO} placing #{nauo}); placed without motion"
                    ));
                    Motion::IDENTITY
                }
            };
        }
        let idt =
            op.and_then(|t| Some((t, p.entities.inst(t)?.part("ITEM_DEFINED_TRANSFORMATION")?)));
        let Some((tid, idt)) = idt else {
            self.warnings.push(format!(
                "assembly: #{srr} (placing #{nauo}): the transformation is neither an ITEM_DEFINED_TRANSFORMATION nor a {CTO} (not supported); placed without motion"
            ));
            return Motion::IDENTITY;
        };
        let (Some(a), Some(b)) = (
            idt.get(2).and_then(|v| v.reference()),
            idt.get(3).and_then(|v| v.reference()),
        ) else {
            self.warnings.push(format!(
                "assembly: ITEM_DEFINED_TRANSFORMATION #{tid}: items are not references; #{nauo} placed without motion"
            ));
            return Motion::IDENTITY;
        };
        let (k1, k2) = (self.rep_factor(rr, 2), self.rep_factor(rr, 3));
        let t = match self.map_frames((a, k1), (b, k2)) {
            Ok(t) => t,
            Err(e) => {
                self.warnings.push(format!(
                    "assembly: ITEM_DEFINED_TRANSFORMATION #{tid}: {e}; #{nauo} placed without motion"
                ));
                return Motion::IDENTITY;
            }
        };
        self.towards_parent(srr, nauo, child, rr, t, |m| Some(m.inverse_rigid()))
    }

    /// `t` (rep_1 to rep_2 of the relationship `rr`) as the map from the child's coordinates
    /// to the parent's: `t` when rep_1 is the child's, its inverse when rep_2 is.
    fn towards_parent(
        &mut self,
        srr: u64,
        nauo: u64,
        child: u64,
        rr: Args,
        t: Motion,
        inverse: fn(&Motion) -> Option<Motion>,
    ) -> Motion {
        let child_reps: Vec<u64> = self.reps.get(&child).map_or(vec![], |v| {
            v.iter().flat_map(|&r| self.closure(r)).collect()
        });
        let rep1 = rr.get(2).and_then(|v| v.reference());
        let rep2 = rr.get(3).and_then(|v| v.reference());
        if rep1.is_some_and(|r| child_reps.contains(&r)) {
            t
        } else if rep2.is_some_and(|r| child_reps.contains(&r)) {
            inverse(&t).unwrap_or_else(|| {
                self.warnings.push(format!(
                    "assembly: #{srr} (placing #{nauo}): its transformation cannot be inverted; placed without motion"
                ));
                Motion::IDENTITY
            })
        } else {
            self.warnings.push(format!(
                "assembly: #{srr} (placing #{nauo}) relates no representation of the child product; rep_1 taken as the child's"
            ));
            t
        }
    }
}
