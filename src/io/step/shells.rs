//! STEP shells and solids (ISO 10303-42) into the [`Brep`](crate::brep::Brep) that
//! [`super::topology`] builds: `closed_shell`/`open_shell` of faces (possibly
//! `oriented_face`s), `manifold_solid_brep` and `brep_with_voids` (`oriented_closed_shell`
//! voids). Faults are reported per instance, as for faces.

use super::part21::Inst;
use super::topology::{TopologyReader, type_of};
use crate::brep::{IssueKind, Shell, Solid};

impl TopologyReader<'_> {
    pub(super) fn shell(&mut self, id: u64) -> Option<usize> {
        if let Some(s) = self.shells.get(&id) {
            return *s;
        }
        self.shells.insert(id, None);
        let e = self.r.p.entities.inst(id)?;
        let ty = type_of(e, &["CLOSED_SHELL", "OPEN_SHELL"]);
        let Some(list) = e
            .part(&ty)
            .and_then(|a| a.get(1))
            .and_then(|v| v.list_refs())
        else {
            self.invalid(
                id,
                &ty,
                None,
                IssueKind::Malformed("cfs_faces is not a list".into()),
            );
            return None;
        };
        let mut faces = Vec::with_capacity(list.len());
        for v in list {
            let Some(fid) = v else {
                self.invalid(
                    id,
                    &ty,
                    None,
                    IssueKind::Malformed("a face is not a reference".into()),
                );
                return None;
            };
            let (fe, fty) = self.referenced(
                (id, &ty),
                fid,
                "face",
                &["ADVANCED_FACE", "FACE_SURFACE", "ORIENTED_FACE"],
                None,
            )?;
            let (target, orientation) = if fty == "ORIENTED_FACE" {
                let a = fe.part("ORIENTED_FACE").unwrap_or_default();
                match (
                    a.get(2).and_then(|v| v.reference()),
                    a.get(3).and_then(|v| v.enumeration()),
                ) {
                    (Some(t), Some(o)) => {
                        self.converted(fid, "ORIENTED_FACE");
                        (t, o != "F")
                    }
                    _ => {
                        self.invalid(
                            fid,
                            "ORIENTED_FACE",
                            None,
                            IssueKind::Malformed(
                                "expected (name, *, face_element, orientation)".into(),
                            ),
                        );
                        return None;
                    }
                }
            } else {
                (fid, true)
            };
            match self.faces.get(&target) {
                Some(fi) => faces.push((*fi, orientation)),
                None => {
                    self.invalid(
                        id,
                        &ty,
                        None,
                        IssueKind::WrongType {
                            attribute: format!("face #{target}"),
                            expected: "a face that was read (ADVANCED_FACE or FACE_SURFACE)".into(),
                            found: self
                                .r
                                .p
                                .entities
                                .inst(target)
                                .map_or("(missing)", |e| e.name())
                                .to_string(),
                        },
                    );
                    return None;
                }
            }
        }
        self.converted(id, &ty);
        let i = self.brep.shells.len();
        self.brep.shells.push(Shell {
            source: format!("#{id}"),
            closed: ty == "CLOSED_SHELL",
            faces,
        });
        self.shells.insert(id, Some(i));
        Some(i)
    }

    pub(super) fn solid(&mut self, id: u64, e: Inst) {
        let ty = type_of(e, &["BREP_WITH_VOIDS", "MANIFOLD_SOLID_BREP"]);
        let outer = e
            .part("MANIFOLD_SOLID_BREP")
            .and_then(|a| a.get(1)?.reference());
        let Some(outer) = outer else {
            self.invalid(
                id,
                &ty,
                None,
                IssueKind::Malformed("outer is not a reference".into()),
            );
            return;
        };
        let Some(_) = self.referenced((id, &ty), outer, "outer", &["CLOSED_SHELL"], None) else {
            return;
        };
        let Some(outer) = self.shell(outer) else {
            self.invalid(
                id,
                &ty,
                None,
                IssueKind::Malformed("its outer shell was refused".into()),
            );
            return;
        };
        let mut voids = Vec::new();
        if let Some(list) = e
            .part("BREP_WITH_VOIDS")
            .and_then(|a| a.last()?.list_refs())
        {
            for v in list.flatten() {
                let Some((ve, _)) =
                    self.referenced((id, &ty), v, "void", &["ORIENTED_CLOSED_SHELL"], None)
                else {
                    return;
                };
                let inner = ve
                    .part("ORIENTED_CLOSED_SHELL")
                    .and_then(|a| a.get(2)?.reference())
                    .and_then(|s| self.shell(s));
                match inner {
                    Some(s) => {
                        self.converted(v, "ORIENTED_CLOSED_SHELL");
                        voids.push(s);
                    }
                    None => {
                        self.invalid(
                            v,
                            "ORIENTED_CLOSED_SHELL",
                            None,
                            IssueKind::Malformed("closed_shell_element was refused".into()),
                        );
                        return;
                    }
                }
            }
        }
        self.converted(id, &ty);
        self.brep.solids.push(Solid {
            source: format!("#{id}"),
            outer,
            voids,
        });
    }
}
