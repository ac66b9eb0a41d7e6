//! The compiled inertia of every body, by MuJoCo's rules (`mjCBody::Compile`,
//! `mjCModel::TryCompile`, `mj_setTotalmass`):
//!
//! 1. every mesh asset is read and its properties computed (MuJoCo compiles them all, so a
//!    missing file is an error even when no geom uses it);
//! 2. each geom whose `group` is in `inertiagrouprange` gets a mass (`mass`, or
//!    `density × volume`) and an inertia, in a body that takes its inertia from geoms: with
//!    `inertiafromgeom="auto"` (the default) a body without `<inertial>`, with `"true"` every
//!    body, with `"false"` none;
//! 3. the body's inertial frame is its `<inertial>`, or that of its geoms, or (neither) MuJoCo's
//!    fallback: massless, at the body's own `pos`/`quat` as written;
//! 4. `boundmass` and `boundinertia` raise small values, a negative mass or moment is an error,
//!    principal moments violating `A + B ≥ C` are an error unless `balanceinertia` (then all
//!    three become their mean);
//! 5. `settotalmass` scales every body's mass and moments (the world-fixed ones too);
//! 6. a body with joints must carry mass: its own (`mass ≥ 1e-15` and each moment `≥ 1e-15`) or
//!    that of a body welded below it (MuJoCo's `CheckBodyMassInertia`).

use super::inertia::{self, Inertial, Solid};
use super::mesh::{self, MeshProps};
use super::orientation::{self, Pose};

use super::parse::Document;
use super::tree::{Body, Geom, GeomType};
use super::{MjcfError, Reader};
use std::collections::HashMap;

/// MuJoCo's `mjMINVAL`.
const MINVAL: f64 = 1e-15;

/// What the compilation gives each body and geom.
pub(super) struct Compiled {
    /// Each body's inertial frame (index 0, the world: zero).
    pub bodies: Vec<Inertial>,
    /// Each body's geoms' masses.
    pub geom_mass: Vec<Vec<f64>>,
}

/// Reads every mesh asset: name → properties (and its file).
///
/// # Errors
/// A mesh file that cannot be read, or whose volume or inertia MuJoCo would refuse.
pub(super) fn meshes(doc: &Document, r: &Reader) -> Result<HashMap<String, MeshProps>, MjcfError> {
    let mut out = HashMap::new();
    let mut files: HashMap<std::path::PathBuf, mesh::MeshData> = HashMap::new();
    for m in &doc.meshes {
        if m.inline.is_none() && !files.contains_key(&m.file) {
            let data = mesh::read(&m.file)
                .map_err(|e| r.invalid(&m.elem, format!("mesh file {}: {e}", m.file.display())))?;
            files.insert(m.file.clone(), data);
        }
        let data = m.inline.as_ref().unwrap_or_else(|| &files[&m.file]);
        let vert = mesh::transformed(data, &m.refpos, &m.refquat, &m.scale);
        let props = mesh::props(&vert, &data.faces, m.rule).map_err(|e| {
            let message = if m.inline.is_some() {
                e // the element names the mesh
            } else {
                format!("mesh {}: {e}", m.file.display())
            };
            r.invalid(&m.elem, message)
        })?;
        if out.insert(m.name.clone(), props).is_some() {
            return Err(r.invalid(&m.elem, format!("mesh name \"{}\" is used twice", m.name)));
        }
    }
    Ok(out)
}

/// The shape of a geom for its inertia (a mesh with its properties).
fn solid(
    g: &Geom,
    doc: &Document,
    meshes: &HashMap<String, MeshProps>,
    r: &Reader,
) -> Result<Solid, MjcfError> {
    let s = g.size;
    Ok(match g.kind {
        GeomType::Sphere => Solid::Sphere(s[0]),
        GeomType::Capsule => Solid::Capsule(s[0], s[1]),
        GeomType::Cylinder => Solid::Cylinder(s[0], s[1]),
        GeomType::Ellipsoid => Solid::Ellipsoid(s),
        GeomType::Box => Solid::Box(s),
        GeomType::Hfield => {
            let name = g.hfield.as_deref().unwrap_or_default();
            let h = doc
                .hfields
                .get(name)
                .ok_or_else(|| r.invalid(&g.elem, format!("unknown height field \"{name}\"")))?;
            Solid::Box([h[0], h[1], 0.25 * h[2] + 0.5 * h[3]])
        }
        GeomType::Mesh | GeomType::Sdf => {
            let name = g.mesh.as_deref().unwrap_or_default();
            Solid::Mesh(
                *meshes
                    .get(name)
                    .ok_or_else(|| r.invalid(&g.elem, format!("unknown mesh \"{name}\"")))?,
            )
        }
        GeomType::Plane => Solid::None,
    })
}

/// The compiled inertia of every body.
///
/// # Errors
/// The checks of MuJoCo's compiler, naming the body or geom and its line.
pub(super) fn inertias(
    bodies: &[Body],
    doc: &Document,
    meshes: &HashMap<String, MeshProps>,
    r: &Reader,
) -> Result<Compiled, MjcfError> {
    let c = &doc.compiler;
    let mut out = vec![Inertial::ZERO];
    let mut geom_mass = vec![vec![0.0; bodies[0].geoms.len()]];
    for b in bodies.iter().skip(1) {
        let elem = b
            .elem
            .as_ref()
            .expect("every body but the world has an element");
        let explicit = b.inertial.is_some();
        let from_geoms =
            c.inertiafromgeom == Some(true) || (!explicit && c.inertiafromgeom.is_none());
        let mut masses = Vec::with_capacity(b.geoms.len());
        let mut frames = Vec::with_capacity(b.geoms.len());
        for g in &b.geoms {
            let in_range = (c.group_range[0]..=c.group_range[1]).contains(&g.group);
            if g.kind == GeomType::Plane && !b.joints.is_empty() {
                return Err(r.invalid(&g.elem, "a plane is only allowed in a static body".into()));
            }
            let infer = (!explicit || c.inertiafromgeom == Some(true)) && in_range;
            let s = solid(g, doc, meshes, r)?;
            if matches!(s, Solid::Mesh(_)) && g.shell {
                return Err(r.invalid(
                    &g.elem,
                    "for a mesh geom the shell inertia is set on the mesh asset".into(),
                ));
            }
            let shell = g.shell;
            let volume = s.volume(shell);
            let m = if !infer {
                0.0
            } else {
                match g.mass {
                    Some(0.0) => 0.0,
                    Some(m) if volume > orientation::EPS => m,
                    Some(_) => 0.0,
                    None if g.density == 0.0 => 0.0,
                    None => g.density * volume,
                }
            };
            let diag = if m != 0.0 {
                s.inertia(m, shell)
            } else {
                [0.0; 3]
            };
            if !m.is_finite() || diag.iter().any(|x| !x.is_finite() || *x < 0.0) || m < 0.0 {
                return Err(r.invalid(
                    &g.elem,
                    format!("its mass ({m}) or inertia is negative or not finite"),
                ));
            }
            masses.push(m);
            frames.push(if m != 0.0 {
                s.inertial(m, shell, &g.pose)
            } else {
                Inertial::ZERO
            });
        }
        let mut i = b.inertial.as_ref().map(|e| {
            let frame = Pose {
                pos: e.pos,
                quat: e.quat,
            };
            match e.full {
                Some(full) => Inertial {
                    mass: e.mass,
                    com: e.pos,
                    full,
                    axes: None,
                },
                None => Inertial::principal(e.mass, &frame, &e.diag),
            }
        });
        if from_geoms {
            if let Some(g) = inertia::from_geoms(&frames).map_err(|m| r.invalid(elem, m))? {
                i = Some(g);
            }
        }
        // neither: MuJoCo's fallback copies the body's own pose into the inertial frame
        let mut i = i.unwrap_or(Inertial {
            com: b.own_pose.pos,
            ..Inertial::ZERO
        });
        i.mass = i.mass.max(c.boundmass);
        if c.boundinertia > 0.0 {
            i = i.map_moments(|x| x.max(c.boundinertia));
        }
        let at = b.inertial.as_ref().map_or(elem, |e| &e.elem);
        let (d, _) = i.principal_axes();
        // moments below zero by round-off of the principal decomposition are zero
        let tiny = 1e-14 * d[0].abs();
        if i.mass < 0.0 || d.iter().any(|x| *x < -tiny) {
            return Err(r.invalid(at, format!("negative mass ({}) or inertia", i.mass)));
        }
        if d[0] + d[1] < d[2] - tiny || d[0] + d[2] < d[1] - tiny || d[1] + d[2] < d[0] - tiny {
            if c.balanceinertia {
                let mean = (d[0] + d[1] + d[2]) / 3.0;
                i = i.map_moments(|_| mean);
            } else {
                return Err(r.invalid(
                    at,
                    format!(
                        "principal moments {d:?} violate A + B >= C (MuJoCo refuses them; the \
                         compiler's balanceinertia=\"true\" replaces them by their mean)"
                    ),
                ));
            }
        }
        if !i.mass.is_finite() || i.com.iter().chain(&i.full).any(|x| !x.is_finite()) {
            return Err(r.invalid(at, "the inertia is not finite".into()));
        }
        out.push(i);
        geom_mass.push(masses);
    }
    if c.settotalmass > 0.0 {
        let total: f64 = out.iter().skip(1).map(|i| i.mass).sum();
        let scale = MINVAL.max(c.settotalmass / MINVAL.max(total));
        for i in out.iter_mut().skip(1) {
            i.mass *= scale;
            i.full = i.full.map(|x| x * scale);
        }
        for m in geom_mass.iter_mut().flatten() {
            *m *= scale;
        }
    }
    for (k, b) in bodies.iter().enumerate().skip(1) {
        if !b.joints.is_empty() && !carries_mass(bodies, &out, k) {
            let elem = b.elem.as_ref().expect("a body element");
            return Err(r.invalid(
                elem,
                "a moving body must have mass and inertia (each at least 1e-15), its own or that \
                 of a body welded to it (MuJoCo refuses it; the mass matrix would be singular)"
                    .into(),
            ));
        }
    }
    Ok(Compiled {
        bodies: out,
        geom_mass,
    })
}

/// MuJoCo's `CheckBodyMassInertia`: the body, or one of the bodies welded below it, has mass and
/// inertia.
fn carries_mass(bodies: &[Body], inertial: &[Inertial], k: usize) -> bool {
    let i = &inertial[k];
    if i.mass >= MINVAL && i.principal_axes().0.iter().all(|x| *x >= MINVAL) {
        return true;
    }
    bodies[k]
        .children
        .iter()
        .any(|&c| bodies[c].joints.is_empty() && carries_mass(bodies, inertial, c))
}
