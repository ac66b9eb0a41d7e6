//! Compiled bodies to a rigid [`Model`]: each MuJoCo joint a rigid joint, in MuJoCo's order;
//! bodies without joints welded to their parent.
//!
//! A body with joints `j1 … jk` (anchors `p1 … pk`, axes in the body frame `F`) moves as MuJoCo's
//! `mj_kinematics` moves it: each joint turns (or slides) the frame left by the previous ones
//! about its anchor, `F_k = F_{k-1} Tr(p_k) X_J(q_k) Tr(-p_k)`. Rigid's joint `k` therefore sits
//! at the anchor with the body's axes: placed at `F_0 Tr(p_1)` in its parent's frame for the
//! first, at `Tr(p_k - p_{k-1})` in joint `k-1`'s frame for the others, with massless bodies
//! between them; the last carries the body, whose frame is `Tr(-p_k)` in its joint frame. A free
//! joint's frame is the body frame itself, placed at the world origin: rigid's `q` is then
//! MuJoCo's world pose of the body.

use super::compile::{self, Compiled};
use super::inertia::Inertial;
use super::orientation::{self, Pose};
use super::parse::{self, Document};
use super::tree::{self, Body, Geom, GeomType};
use super::xml::{self, Element};
use super::{
    MjcfBody, MjcfError, MjcfGeom, MjcfInertial, MjcfJoint, MjcfJointKind, MjcfModel, MjcfShape,
    MjcfSite, Reader,
};
use crate::mass::{RotationalInertia, SpatialInertia};
use crate::multibody::{FrameKind, JointId, JointType, ModelBuilder, ModelError};
use crate::spatial::{Mat3, Transform, Vec3};
use std::collections::HashSet;
use std::path::Path;

/// Reads an MJCF file (and the files it includes, and its meshes) into an [`MjcfModel`].
///
/// # Errors
/// An [`MjcfError`] naming the file, the element and the line.
pub fn load_mjcf(path: impl AsRef<Path>) -> Result<MjcfModel, MjcfError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| MjcfError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut m = load(&text, Some(path), dir)?;
    m.path = Some(path.to_path_buf());
    Ok(m)
}

/// Reads MJCF text; included files and meshes are looked up from `dir`.
///
/// # Errors
/// As [`load_mjcf`].
pub fn load_mjcf_str(text: &str, dir: &Path) -> Result<MjcfModel, MjcfError> {
    load(text, None, dir)
}

fn load(text: &str, path: Option<&Path>, dir: &Path) -> Result<MjcfModel, MjcfError> {
    let (root, sources) = xml::read_document(text, path, dir)?;
    let mut r = Reader {
        sources,
        warnings: Vec::new(),
    };
    let doc = parse::document(&root, &mut r)?;
    let mut bodies = tree::bodies(&root, &mut r, &doc)?;
    let meshes = compile::meshes(&doc, &r)?;
    let compiled = compile::inertias(&bodies, &doc, &meshes, &r)?;
    let name = path
        .and_then(|p| p.file_stem())
        .map(|s| s.to_string_lossy().into_owned());
    let name = root
        .attr("model")
        .map(str::to_string)
        .or(name)
        .unwrap_or_else(|| "mujoco".into());
    let inertials = align_free(&mut bodies, compiled.bodies.clone(), &doc);
    build(
        &name,
        &root,
        &bodies,
        &Compiled {
            bodies: inertials,
            ..compiled
        },
        &doc,
        r,
    )
}

/// MuJoCo's free-joint alignment (`alignfree`, or a free joint's `align`): a body with one free
/// joint and no children gets its inertial frame as its body frame (its geoms and sites
/// re-expressed), so that the free joint's `qpos` is the pose of the principal axes.
fn align_free(bodies: &mut [Body], mut inertials: Vec<Inertial>, doc: &Document) -> Vec<Inertial> {
    for (k, b) in bodies.iter_mut().enumerate().skip(1) {
        let aligned = matches!(b.joints.as_slice(), [j] if j.kind == MjcfJointKind::Free
            && j.align.unwrap_or(doc.compiler.alignfree))
            && b.children.is_empty();
        if !aligned {
            continue;
        }
        let (d, axes) = inertials[k].principal_axes();
        let i = Pose {
            pos: inertials[k].com,
            quat: quat_of(&axes),
        };
        b.pose = b.pose.then(&i);
        let inv = i.inverse();
        for g in b.geoms.iter_mut().chain(b.sites.iter_mut()) {
            g.pose = inv.then(&g.pose);
        }
        inertials[k] = Inertial::principal(inertials[k].mass, &Pose::IDENTITY, &d);
    }
    inertials
}

/// The quaternion `(w, x, y, z)` of a rotation matrix.
fn quat_of(r: &Mat3) -> orientation::Quat {
    let [x, y, z, w] = crate::spatial::so3::to_quaternion(r);
    [w, x, y, z]
}

/// The spatial inertia of a compiled body in its body frame.
fn spatial(i: &Inertial) -> SpatialInertia {
    let inertia = RotationalInertia::from_matrix_unchecked(&i.matrix());
    SpatialInertia::from_com(i.mass, Vec3::from(i.com), inertia)
}

/// Names unique within their namespace: a clash gets `_2`, `_3`, ...
struct Names(HashSet<String>);

impl Names {
    fn unique(&mut self, base: String) -> String {
        let mut name = base.clone();
        let mut k = 2;
        while self.0.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.0.insert(name.clone());
        name
    }
}

#[allow(clippy::too_many_lines)]
fn build(
    name: &str,
    root: &Element,
    bodies: &[Body],
    compiled: &Compiled,
    doc: &Document,
    mut r: Reader,
) -> Result<MjcfModel, MjcfError> {
    let mut b = ModelBuilder::new(name);
    b.set_gravity(doc.gravity);
    // a body's frame: the rigid joint it is fixed in, and its pose in that joint's frame
    let mut frames: Vec<(Option<JointId>, Transform)> = vec![(None, Transform::identity())];
    let mut body_names = Names(HashSet::new());
    let mut joint_names = Names(
        bodies
            .iter()
            .flat_map(|b| b.joints.iter().filter_map(|j| j.name.clone()))
            .collect(),
    );
    let mut out_bodies = vec![MjcfBody {
        name: "world".into(),
        parent: None,
        joint: None,
        placement: Transform::identity(),
        mass: 0.0,
        inertial: (Transform::identity(), Vec3::zeros()),
        given: None,
        gravcomp: 0.0,
        mocap: false,
        line: 0,
    }];
    body_names.0.insert("world".into());
    let mut joints = Vec::new();
    let mut qpos0 = Vec::new();
    let mut world_pose = vec![Pose::IDENTITY];
    for (k, body) in bodies.iter().enumerate().skip(1) {
        let elem = body.elem.as_ref().expect("a body element");
        let bname = body_names.unique(body.name.clone().unwrap_or_else(|| format!("body{k}")));
        let at = |e: ModelError| r.invalid(elem, e.to_string());
        let (attach, t_parent) = frames[body.parent];
        let t0 = t_parent * body.pose.transform();
        world_pose.push(world_pose[body.parent].then(&body.pose));
        let g_body = spatial(&compiled.bodies[k]);
        let frame = match body.joints.as_slice() {
            [] => {
                b.add_fixed_body(attach, &bname, t0, g_body).map_err(at)?;
                (attach, t0)
            }
            [j] if j.kind == MjcfJointKind::Free => {
                if body.parent != 0 {
                    return Err(r.invalid(
                        &j.elem,
                        "a free joint can only be used on a top-level body (MuJoCo's rule)".into(),
                    ));
                }
                let jname = joint_name(&mut joint_names, j, &bname, 0);
                let id = b
                    .add_joint(
                        None,
                        &jname,
                        JointType::FreeFlyer,
                        Transform::identity(),
                        g_body,
                    )
                    .map_err(at)?;
                let at_joint = |e: ModelError| r.invalid(&j.elem, e.to_string());
                b.set_armature(id, &[j.armature; 6]).map_err(at_joint)?;
                b.set_joint_dynamics(id, &[j.damping; 6], &[j.frictionloss; 6])
                    .map_err(at_joint)?;
                let p = world_pose[k];
                qpos0.extend(p.pos);
                qpos0.extend(p.quat);
                joints.push(mjcf_joint(j, &jname, id, k, 0.0));
                b.add_frame_of_kind(Some(id), &bname, Transform::identity(), FrameKind::Body)
                    .map_err(at)?;
                (Some(id), Transform::identity())
            }
            chain => {
                check_chain(chain, elem, &r)?;
                let mut parent = attach;
                let mut prev = [0.0; 3];
                let n = chain.len();
                for (i, j) in chain.iter().enumerate() {
                    let p = Vec3::from(j.pos);
                    let placement = if i == 0 {
                        t0 * Transform::from_translation(p)
                    } else {
                        Transform::from_translation(p - Vec3::from(prev))
                    };
                    prev = j.pos;
                    let inertia = if i + 1 == n {
                        g_body.transformed(&Transform::from_translation(-p))
                    } else {
                        SpatialInertia::zero()
                    };
                    let axis = Vec3::from(j.axis);
                    let kind = match j.kind {
                        MjcfJointKind::Hinge => JointType::Revolute { axis },
                        MjcfJointKind::Slide => JointType::Prismatic { axis },
                        _ => JointType::Spherical,
                    };
                    let jname = joint_name(&mut joint_names, j, &bname, i);
                    let at_joint = |e: ModelError| r.invalid(&j.elem, e.to_string());
                    let id = b
                        .add_joint(parent, &jname, kind, placement, inertia)
                        .map_err(at_joint)?;
                    let nv = kind.nv();
                    b.set_armature(id, &vec![j.armature; nv])
                        .map_err(at_joint)?;
                    b.set_joint_dynamics(id, &vec![j.damping; nv], &vec![j.frictionloss; nv])
                        .map_err(at_joint)?;
                    if let (Some([lo, hi]), 1) = (j.range, nv) {
                        let inf = f64::INFINITY;
                        b.set_limits(id, &[lo - j.reference], &[hi - j.reference], &[inf], &[inf])
                            .map_err(at_joint)?;
                    }
                    if j.kind == MjcfJointKind::Ball {
                        qpos0.extend([1.0, 0.0, 0.0, 0.0]);
                    } else {
                        qpos0.push(j.reference);
                    }
                    joints.push(mjcf_joint(j, &jname, id, k, j.reference));
                    parent = Some(id);
                }
                let t = Transform::from_translation(-Vec3::from(prev));
                b.add_frame_of_kind(parent, &bname, t, FrameKind::Body)
                    .map_err(at)?;
                (parent, t)
            }
        };
        frames.push(frame);
        let i = &compiled.bodies[k];
        let (d, axes) = i.principal_axes();
        out_bodies.push(MjcfBody {
            name: bname,
            parent: Some(body.parent),
            joint: frame.0,
            placement: frame.1,
            mass: i.mass,
            inertial: (Transform::new(axes, Vec3::from(i.com)), Vec3::from(d)),
            given: body.inertial.as_ref().map(given),
            gravcomp: body.gravcomp,
            mocap: body.mocap,
            line: elem.line,
        });
    }
    let mut geoms = Vec::new();
    let mut sites = Vec::new();
    for (k, body) in bodies.iter().enumerate() {
        let (parent, t) = frames[k];
        // the last guard against numbers that overflow when composed (a huge position)
        if let Some(g) = body
            .geoms
            .iter()
            .chain(&body.sites)
            .find(|g| !finite(&(t * g.pose.transform())))
        {
            return Err(r.invalid(&g.elem, "its placement is not finite".into()));
        }
        for (g, m) in body.geoms.iter().zip(&compiled.geom_mass[k]) {
            geoms.push(MjcfGeom {
                name: g.elem.attr("name").map(str::to_string),
                body: k,
                parent,
                placement: t * g.pose.transform(),
                shape: shape(g, doc),
                group: g.group,
                contype: g.contype,
                conaffinity: g.conaffinity,
                friction: g.friction,
                rgba: color(g, doc),
                mass: *m,
                line: g.elem.line,
            });
        }
        for s in &body.sites {
            sites.push(MjcfSite {
                name: s.elem.attr("name").map(str::to_string),
                body: k,
                parent,
                placement: t * s.pose.transform(),
                shape: shape(s, doc),
                group: s.group,
                line: s.elem.line,
            });
        }
    }
    gravcomp_warnings(bodies, &mut r);
    let model = b.build().map_err(|e| MjcfError::Model(e.to_string()))?;
    let _ = root;
    Ok(MjcfModel {
        model,
        joints,
        bodies: out_bodies,
        geoms,
        sites,
        equalities: doc.equalities.clone(),
        tendons: doc.tendons.clone(),
        timestep: doc.timestep,
        contact: doc.contact.clone(),
        qpos0,
        warnings: r.warnings,
        path: None,
    })
}

fn finite(t: &Transform) -> bool {
    t.rotation
        .iter()
        .chain(t.translation.iter())
        .all(|x| x.is_finite())
}

/// An `<inertial>` as written.
fn given(e: &tree::ExplicitInertial) -> MjcfInertial {
    let a = |k: &str| {
        e.elem
            .attr(k)
            .unwrap_or_default()
            .split_whitespace()
            .map(str::to_string)
    };
    let mut text: [String; 7] = Default::default();
    text[0] = e.elem.attr("mass").unwrap_or_default().trim().to_string();
    let (frame, inertia) = match e.full {
        Some(f) => {
            for (slot, t) in text[1..].iter_mut().zip(a("fullinertia")) {
                *slot = t;
            }
            let i = RotationalInertia::new(f[0], f[1], f[2], f[3], f[4], f[5]);
            (Transform::from_translation(Vec3::from(e.pos)), i)
        }
        None => {
            for (slot, t) in text[1..4].iter_mut().zip(a("diaginertia")) {
                *slot = t;
            }
            text[4..].iter_mut().for_each(|t| *t = "0".into());
            let pose = Pose {
                pos: e.pos,
                quat: e.quat,
            };
            let d = e.diag;
            (
                pose.transform(),
                RotationalInertia::diagonal(d[0], d[1], d[2]),
            )
        }
    };
    MjcfInertial {
        mass: e.mass,
        frame,
        inertia,
        text,
        line: e.elem.line,
    }
}

/// MuJoCo's rules for the joints of one body: at most 6 degrees of freedom, no rotation after a
/// ball joint, a free joint alone.
fn check_chain(chain: &[tree::Joint], elem: &Element, r: &Reader) -> Result<(), MjcfError> {
    let dofs: usize = chain
        .iter()
        .map(|j| match j.kind {
            MjcfJointKind::Free => 6,
            MjcfJointKind::Ball => 3,
            _ => 1,
        })
        .sum();
    if chain.iter().any(|j| j.kind == MjcfJointKind::Free) {
        return Err(r.invalid(elem, "a free joint must be the body's only joint".into()));
    }
    if dofs > 6 {
        return Err(r.invalid(
            elem,
            format!("{dofs} degrees of freedom in one body (at most 6)"),
        ));
    }
    let mut ball = false;
    for j in chain {
        if ball && matches!(j.kind, MjcfJointKind::Ball | MjcfJointKind::Hinge) {
            return Err(r.invalid(
                &j.elem,
                "a rotation after a ball joint in the same body".into(),
            ));
        }
        ball |= j.kind == MjcfJointKind::Ball;
    }
    Ok(())
}

fn joint_name(names: &mut Names, j: &tree::Joint, body: &str, i: usize) -> String {
    match &j.name {
        Some(n) => n.clone(),
        None => names.unique(format!("{body}_jnt{i}")),
    }
}

fn mjcf_joint(j: &tree::Joint, name: &str, id: JointId, body: usize, reference: f64) -> MjcfJoint {
    MjcfJoint {
        name: name.to_string(),
        kind: j.kind,
        id,
        body,
        reference,
        springref: j.springref,
        stiffness: j.stiffness,
        damping: j.damping,
        frictionloss: j.frictionloss,
        armature: j.armature,
        range: j.range,
        line: j.elem.line,
    }
}

fn shape(g: &Geom, doc: &Document) -> MjcfShape {
    let s = g.size;
    match g.kind {
        GeomType::Plane => MjcfShape::Plane { half: [s[0], s[1]] },
        GeomType::Sphere => MjcfShape::Sphere { radius: s[0] },
        GeomType::Capsule => MjcfShape::Capsule {
            radius: s[0],
            half_length: s[1],
        },
        GeomType::Cylinder => MjcfShape::Cylinder {
            radius: s[0],
            half_length: s[1],
        },
        GeomType::Ellipsoid => MjcfShape::Ellipsoid {
            radii: Vec3::from(s),
        },
        GeomType::Box => MjcfShape::Box {
            half: Vec3::from(s),
        },
        GeomType::Hfield => MjcfShape::Hfield {
            name: g.hfield.clone().unwrap_or_default(),
        },
        GeomType::Mesh | GeomType::Sdf => {
            let name = g.mesh.clone().unwrap_or_default();
            match doc.meshes.iter().find(|m| m.name == name) {
                Some(m) => MjcfShape::Mesh {
                    name,
                    file: m.file.clone(),
                    inline: m.inline.as_ref().map(|d| crate::mass::TriMesh {
                        vertices: d
                            .vertices
                            .iter()
                            .map(|v| Vec3::new(v[0].into(), v[1].into(), v[2].into()))
                            .collect(),
                        triangles: d.faces.clone(),
                    }),
                    scale: Vec3::from(m.scale),
                    refpos: Vec3::from(m.refpos),
                    refrot: orientation::to_mat3(&m.refquat),
                },
                None => MjcfShape::Sphere { radius: 0.005 },
            }
        }
    }
}

/// `rgba`, else the material's, else MuJoCo's default grey.
fn color(g: &Geom, doc: &Document) -> [f64; 4] {
    g.rgba
        .or_else(|| {
            g.material
                .as_ref()
                .and_then(|m| doc.materials.get(m).copied())
        })
        .unwrap_or([0.5, 0.5, 0.5, 1.0])
}

/// One warning per body with gravity compensation (MuJoCo applies it as a passive force, so it
/// is not in `qfrc_bias` and rigid's dynamics leave it out too).
fn gravcomp_warnings(bodies: &[Body], r: &mut Reader) {
    for b in bodies.iter().skip(1) {
        if b.gravcomp != 0.0 {
            let elem = b.elem.as_ref().expect("a body element");
            r.warn(
                elem,
                format!(
                    "gravcomp=\"{}\": MuJoCo cancels this fraction of the body's weight by a \
                     passive force; rigid's dynamics (like qfrc_bias) leave it out",
                    b.gravcomp
                ),
            );
        }
    }
}
