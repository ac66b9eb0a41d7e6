//! The body tree: every `<worldbody>`, its bodies (depth-first, MuJoCo's order), and in each
//! body its joints, geoms, sites and `<inertial>`, with defaults and `<frame>`s applied
//! (`mjXReader::Body`, `src/xml/xml_native_reader.cc`; the frame composition of
//! `mjCBody::Compile`, `mjCJoint::Compile` and `mjCGeom::Compile`).
//!
//! A `<frame>` is not a body: its pose is composed into the pose of every body, joint, geom and
//! site inside it (a joint's `pos` is moved and its `axis` turned), and its `childclass` becomes
//! their default class.

use super::defaults::{Attrs, MAIN};
use super::orientation::{self, Pose, Quat};
use super::parse::{
    self, array, boolean, int, keyword, orientation, own, partial, scalar, Document,
};
use super::xml::Element;
use super::{MjcfError, MjcfJointKind, Reader};

/// Bodies nested deeper than this are refused (the walk is recursive).
const MAX_DEPTH: usize = 200;

/// A joint, resolved (angles still in the file's unit for `ref`, `springref`, `range`).
#[derive(Clone, Debug)]
pub(super) struct Joint {
    pub name: Option<String>,
    pub kind: MjcfJointKind,
    /// Anchor in the body frame (frames applied).
    pub pos: [f64; 3],
    /// Unit axis in the body frame.
    pub axis: [f64; 3],
    pub reference: f64,
    pub springref: f64,
    pub stiffness: f64,
    pub damping: f64,
    pub frictionloss: f64,
    pub armature: f64,
    /// `range` when limited (radians for hinges).
    pub range: Option<[f64; 2]>,
    /// `align` (`None`: auto).
    pub align: Option<bool>,
    pub elem: Element,
}

/// A geom's type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum GeomType {
    Plane,
    Hfield,
    Sphere,
    Capsule,
    Ellipsoid,
    Cylinder,
    Box,
    Mesh,
    Sdf,
}

const GEOM_TYPES: [&str; 9] = [
    "plane",
    "hfield",
    "sphere",
    "capsule",
    "ellipsoid",
    "cylinder",
    "box",
    "mesh",
    "sdf",
];

const TYPES: [GeomType; 9] = [
    GeomType::Plane,
    GeomType::Hfield,
    GeomType::Sphere,
    GeomType::Capsule,
    GeomType::Ellipsoid,
    GeomType::Cylinder,
    GeomType::Box,
    GeomType::Mesh,
    GeomType::Sdf,
];

/// A geom (or a site: `mass`, `density` and the mesh unused), resolved.
#[derive(Clone, Debug)]
pub(super) struct Geom {
    pub kind: GeomType,
    /// MuJoCo's `size`, `fromto` applied.
    pub size: [f64; 3],
    /// Pose in the body frame as written (`fromto` and frames applied; a mesh's own frame not).
    pub pose: Pose,
    /// `mass`, if given.
    pub mass: Option<f64>,
    pub density: f64,
    pub shell: bool,
    pub group: i32,
    pub contype: i32,
    pub conaffinity: i32,
    /// The sliding friction (`friction`'s first number).
    pub friction: f64,
    /// Mesh asset name.
    pub mesh: Option<String>,
    /// Height field asset name.
    pub hfield: Option<String>,
    pub rgba: Option<[f64; 4]>,
    pub material: Option<String>,
    pub elem: Element,
}

/// An `<inertial>`.
#[derive(Clone, Debug)]
pub(super) struct ExplicitInertial {
    pub mass: f64,
    pub pos: [f64; 3],
    pub quat: Quat,
    /// `diaginertia` (along `quat`'s axes).
    pub diag: [f64; 3],
    /// `fullinertia`, when given instead.
    pub full: Option<[f64; 6]>,
    pub elem: Element,
}

/// A body (index 0: the world).
#[derive(Clone, Debug)]
pub(super) struct Body {
    pub name: Option<String>,
    pub parent: usize,
    /// Pose in the parent body's frame (frames applied).
    pub pose: Pose,
    /// Pose as written (MuJoCo copies it into the inertial frame of a body without one).
    pub own_pose: Pose,
    pub joints: Vec<Joint>,
    pub geoms: Vec<Geom>,
    pub sites: Vec<Geom>,
    pub inertial: Option<ExplicitInertial>,
    pub children: Vec<usize>,
    pub mocap: bool,
    pub gravcomp: f64,
    /// The element (`None` for the world).
    pub elem: Option<Element>,
}

/// Context of the walk: the frame elements are in, and their default class.
#[derive(Clone, Copy)]
struct Scope<'a> {
    frame: Pose,
    class: &'a str,
}

/// Every body of every `<worldbody>`, world first, depth-first.
///
/// # Errors
/// An element of the tree that is malformed or that rigid cannot load.
pub(super) fn bodies(
    root: &Element,
    r: &mut Reader,
    doc: &Document,
) -> Result<Vec<Body>, MjcfError> {
    let mut out = vec![Body {
        name: Some("world".into()),
        parent: 0,
        pose: Pose::IDENTITY,
        own_pose: Pose::IDENTITY,
        joints: Vec::new(),
        geoms: Vec::new(),
        sites: Vec::new(),
        inertial: None,
        children: Vec::new(),
        mocap: false,
        gravcomp: 0.0,
        elem: None,
    }];
    for world in root.children_named("worldbody") {
        if !world.attrs.is_empty() {
            return Err(r.invalid(world, "the world body cannot have attributes".into()));
        }
        let scope = Scope {
            frame: Pose::IDENTITY,
            class: MAIN,
        };
        walk(world, 0, scope, r, doc, &mut out, 0)?;
    }
    Ok(out)
}

/// The children of body (or frame) element `e`, which belong to body `b`.
fn walk(
    e: &Element,
    b: usize,
    scope: Scope,
    r: &mut Reader,
    doc: &Document,
    out: &mut Vec<Body>,
    depth: usize,
) -> Result<(), MjcfError> {
    if depth > MAX_DEPTH {
        return Err(r.invalid(e, format!("bodies nested more than {MAX_DEPTH} deep")));
    }
    let d = &doc.defaults;
    for c in &e.children {
        let in_world = b == 0;
        let class = d.class_of(c, scope.class, r)?;
        match c.tag.as_str() {
            "inertial" if in_world => {
                return Err(r.invalid(c, "the world body cannot have an <inertial>".into()))
            }
            "joint" | "freejoint" if in_world => {
                return Err(r.invalid(c, "the world body cannot have joints".into()))
            }
            "inertial" => {
                let i = inertial(c, r, doc)?;
                out[b].inertial = Some(i);
            }
            "joint" => {
                let a = d.resolve(c, scope.class, r)?;
                let j = joint(c, &a, scope.frame, r, doc)?;
                out[b].joints.push(j);
            }
            "freejoint" => {
                let a = own(c);
                let align = match keyword(r, c, &a, "align", &["false", "true", "auto"], 2)? {
                    0 => Some(false),
                    1 => Some(true),
                    _ => None,
                };
                out[b].joints.push(Joint {
                    name: c.attr("name").map(str::to_string),
                    kind: MjcfJointKind::Free,
                    pos: [0.0; 3],
                    axis: [0.0, 0.0, 1.0],
                    reference: 0.0,
                    springref: 0.0,
                    stiffness: 0.0,
                    damping: 0.0,
                    frictionloss: 0.0,
                    armature: 0.0,
                    range: None,
                    align,
                    elem: c.clone(),
                });
            }
            "geom" | "site" => {
                let a = d.resolve(c, scope.class, r)?;
                let g = geom(c, &a, scope.frame, r, doc)?;
                if c.tag == "geom" {
                    out[b].geoms.push(g);
                } else {
                    out[b].sites.push(g);
                }
            }
            "camera" | "light" => {}
            "frame" => {
                let a = own(c);
                let pose = Pose {
                    pos: array(r, c, &a, "pos", [0.0; 3])?,
                    quat: orientation(r, c, &a, &doc.compiler)?,
                };
                let child_class = match c.attr("childclass") {
                    Some(cc) if !d.has(cc) => {
                        return Err(r.invalid(c, format!("unknown default childclass \"{cc}\"")))
                    }
                    Some(cc) => cc,
                    None => class,
                };
                let inner = Scope {
                    frame: scope.frame.then(&pose),
                    class: child_class,
                };
                walk(c, b, inner, r, doc, out, depth + 1)?;
            }
            "body" => {
                let child_class = match c.attr("childclass") {
                    Some(cc) if !d.has(cc) => {
                        return Err(r.invalid(c, format!("unknown default childclass \"{cc}\"")))
                    }
                    Some(cc) => cc,
                    None => class,
                };
                let a = own(c);
                let own_pose = Pose {
                    pos: array(r, c, &a, "pos", [0.0; 3])?,
                    quat: orientation(r, c, &a, &doc.compiler)?,
                };
                let index = out.len();
                out.push(Body {
                    name: c.attr("name").map(str::to_string),
                    parent: b,
                    pose: scope.frame.then(&own_pose),
                    own_pose,
                    joints: Vec::new(),
                    geoms: Vec::new(),
                    sites: Vec::new(),
                    inertial: None,
                    children: Vec::new(),
                    mocap: boolean(r, c, &a, "mocap", false)?,
                    gravcomp: scalar(r, c, &a, "gravcomp", 0.0)?,
                    elem: Some(c.clone()),
                });
                out[b].children.push(index);
                let inner = Scope {
                    frame: Pose::IDENTITY,
                    class: child_class,
                };
                walk(c, index, inner, r, doc, out, depth + 1)?;
            }
            "composite" | "flexcomp" | "replicate" | "attach" | "plugin" => {
                return Err(r.invalid(
                    c,
                    format!(
                        "<{}> is not supported by rigid's MJCF importer (it generates bodies or \
                         needs plugins)",
                        c.tag
                    ),
                ));
            }
            other => r.warn(c, format!("unknown element <{other}> in a body ignored")),
        }
    }
    Ok(())
}

fn joint(
    e: &Element,
    a: &Attrs,
    frame: Pose,
    r: &Reader,
    doc: &Document,
) -> Result<Joint, MjcfError> {
    let c = &doc.compiler;
    let kind = match keyword(r, e, a, "type", &["free", "ball", "slide", "hinge"], 3)? {
        0 => MjcfJointKind::Free,
        1 => MjcfJointKind::Ball,
        2 => MjcfJointKind::Slide,
        _ => MjcfJointKind::Hinge,
    };
    let rotational = matches!(kind, MjcfJointKind::Hinge | MjcfJointKind::Ball);
    let deg = |x: f64| {
        if c.degree && kind == MjcfJointKind::Hinge {
            x.to_radians_mj()
        } else {
            x
        }
    };
    let mut range = array(r, e, a, "range", [0.0; 2])?;
    let has_range = range != [0.0; 2];
    let limited = match keyword(r, e, a, "limited", &["false", "true", "auto"], 2)? {
        0 => false,
        1 => true,
        _ => {
            if !c.autolimits && has_range {
                return Err(r.invalid(
                    e,
                    "the joint has a range but no \"limited\"; set limited, or the compiler's \
                     autolimits=\"true\""
                        .into(),
                ));
            }
            range[0] < range[1]
        }
    } && kind != MjcfJointKind::Free;
    if limited {
        if range[0] >= range[1] && kind != MjcfJointKind::Ball {
            return Err(r.invalid(e, "range[0] must be smaller than range[1]".into()));
        }
        if range[0] != 0.0 && kind == MjcfJointKind::Ball {
            return Err(r.invalid(e, "a ball joint's range[0] must be 0".into()));
        }
        if c.degree && rotational {
            range = range.map(|x| if x != 0.0 { x.to_radians_mj() } else { x });
        }
    }
    let (pos, axis) = match kind {
        MjcfJointKind::Free => ([0.0; 3], [0.0, 0.0, 1.0]),
        MjcfJointKind::Ball => {
            let p = array(r, e, a, "pos", [0.0; 3])?;
            (
                add(&frame.pos, &orientation::rotate(&p, &frame.quat)),
                [0.0, 0.0, 1.0],
            )
        }
        _ => {
            let p = array(r, e, a, "pos", [0.0; 3])?;
            let mut ax =
                orientation::rotate(&array(r, e, a, "axis", [0.0, 0.0, 1.0])?, &frame.quat);
            if orientation::normalize(&mut ax) < orientation::EPS {
                return Err(r.invalid(e, "the joint axis is zero (or too long)".into()));
            }
            (add(&frame.pos, &orientation::rotate(&p, &frame.quat)), ax)
        }
    };
    let align = match keyword(r, e, a, "align", &["false", "true", "auto"], 2)? {
        0 => Some(false),
        1 => Some(true),
        _ => None,
    };
    Ok(Joint {
        name: e.attr("name").map(str::to_string),
        kind,
        pos,
        axis,
        reference: deg(scalar(r, e, a, "ref", 0.0)?),
        springref: deg(scalar(r, e, a, "springref", 0.0)?),
        stiffness: scalar(r, e, a, "stiffness", 0.0)?,
        damping: scalar(r, e, a, "damping", 0.0)?,
        frictionloss: scalar(r, e, a, "frictionloss", 0.0)?,
        armature: scalar(r, e, a, "armature", 0.0)?,
        range: limited.then_some(range),
        align,
        elem: e.clone(),
    })
}

fn add(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// MuJoCo's degree conversion of joint quantities, `x *= mjPI/180.0` (the constant first, so
/// that the rounding is MuJoCo's).
trait ToRadiansMj {
    fn to_radians_mj(self) -> f64;
}

impl ToRadiansMj for f64 {
    fn to_radians_mj(self) -> f64 {
        self * (std::f64::consts::PI / 180.0)
    }
}

/// A `<geom>` or `<site>`.
fn geom(
    e: &Element,
    a: &Attrs,
    frame: Pose,
    r: &Reader,
    doc: &Document,
) -> Result<Geom, MjcfError> {
    let is_site = e.tag == "site";
    let kind = TYPES[keyword(r, e, a, "type", &GEOM_TYPES, 2)?];
    let default_size = if is_site { [0.005; 3] } else { [0.0; 3] };
    let mut size = partial(r, e, a, "size", default_size)?;
    let mut pose = Pose {
        pos: [0.0; 3],
        quat: orientation::IDENTITY,
    };
    if let Some(v) = parse::numbers(r, e, a.get("fromto"), "fromto", 6, true)? {
        if !matches!(
            kind,
            GeomType::Capsule | GeomType::Cylinder | GeomType::Ellipsoid | GeomType::Box
        ) {
            return Err(r.invalid(
                e,
                "fromto needs a capsule, cylinder, box or ellipsoid".into(),
            ));
        }
        if array(r, e, a, "pos", [0.0; 3])? != [0.0; 3] {
            return Err(r.invalid(e, "both pos and fromto are given".into()));
        }
        let mut d = [v[0] - v[3], v[1] - v[4], v[2] - v[5]];
        size[1] = orientation::normalize(&mut d) / 2.0;
        if size[1] < orientation::EPS {
            return Err(r.invalid(e, "fromto has zero length (its two points coincide)".into()));
        }
        if matches!(kind, GeomType::Ellipsoid | GeomType::Box) {
            size[2] = size[1];
            size[1] = size[0];
        }
        pose.pos = [
            (v[0] + v[3]) / 2.0,
            (v[1] + v[4]) / 2.0,
            (v[2] + v[5]) / 2.0,
        ];
        pose.quat = orientation::z_to(&d);
    } else {
        pose.pos = array(r, e, a, "pos", [0.0; 3])?;
        pose.quat = orientation(r, e, a, &doc.compiler)?;
    }
    let needed = match kind {
        GeomType::Sphere => 1,
        GeomType::Capsule | GeomType::Cylinder => 2,
        GeomType::Ellipsoid | GeomType::Box => 3,
        GeomType::Plane | GeomType::Hfield | GeomType::Mesh | GeomType::Sdf => 0,
    };
    if let Some(k) = (0..needed).find(|&k| size[k] <= 0.0) {
        return Err(r.invalid(e, format!("size[{k}] = {} must be positive", size[k])));
    }
    if kind == GeomType::Plane && !is_site && size[2] <= 0.0 {
        return Err(r.invalid(e, "a plane's size[2] must be positive".into()));
    }
    let mass = parse::numbers(r, e, a.get("mass"), "mass", 1, true)?.map(|v| v[0]);
    let density = scalar(r, e, a, "density", 1000.0)?;
    if !is_site && (mass.is_some_and(|m| m < 0.0) || density < 0.0) {
        return Err(r.invalid(e, "a negative mass or density".into()));
    }
    let mesh = a.get("mesh").map(str::to_string);
    if mesh.is_some() && !matches!(kind, GeomType::Mesh | GeomType::Sdf) && !is_site {
        return Err(r.invalid(
            e,
            "a primitive geom fitted to a mesh is not supported; use type=\"mesh\"".into(),
        ));
    }
    if kind == GeomType::Mesh && mesh.is_none() && !is_site {
        return Err(r.invalid(e, "a mesh geom needs a mesh".into()));
    }
    Ok(Geom {
        kind,
        size,
        pose: frame.then(&pose),
        mass,
        density,
        shell: boolean(r, e, a, "shellinertia", false)?,
        group: int(r, e, a, "group", 0)?,
        contype: int(r, e, a, "contype", 1)?,
        conaffinity: int(r, e, a, "conaffinity", 1)?,
        friction: {
            let f = partial(r, e, a, "friction", [1.0, 0.005, 0.0001])?;
            if f.iter().any(|x| *x < 0.0) && !is_site {
                return Err(r.invalid(e, "a negative friction".into()));
            }
            f[0]
        },
        mesh,
        hfield: a.get("hfield").map(str::to_string),
        rgba: parse::numbers(r, e, a.get("rgba"), "rgba", 4, true)?
            .map(|v| [v[0], v[1], v[2], v[3]]),
        material: a.get("material").map(str::to_string),
        elem: e.clone(),
    })
}

/// An `<inertial>` (no defaults): `mass` and `pos` required, `diaginertia` or `fullinertia`.
fn inertial(e: &Element, r: &Reader, doc: &Document) -> Result<ExplicitInertial, MjcfError> {
    let a = own(e);
    let Some(mass) = parse::numbers(r, e, a.get("mass"), "mass", 1, true)? else {
        return Err(r.invalid(e, "<inertial> needs a \"mass\"".into()));
    };
    let Some(pos) = parse::numbers(r, e, a.get("pos"), "pos", 3, true)? else {
        return Err(r.invalid(e, "<inertial> needs a \"pos\"".into()));
    };
    if mass[0] < 0.0 {
        return Err(r.invalid(
            e,
            format!(
                "negative mass {} (MuJoCo raises it to boundmass and then refuses a massless \
                 moving body)",
                mass[0]
            ),
        ));
    }
    let full = parse::numbers(r, e, a.get("fullinertia"), "fullinertia", 6, true)?;
    let diag = parse::numbers(r, e, a.get("diaginertia"), "diaginertia", 3, true)?;
    let mut fullinertia = None;
    let (quat, diag) = match (full, diag) {
        (Some(_), Some(d)) if d.iter().any(|x| *x != 0.0) => {
            return Err(r.invalid(e, "fullinertia and diaginertia cannot both be given".into()))
        }
        (Some(f), _) => {
            if super::defaults::ALTERNATIVES
                .iter()
                .any(|k| a.get(k).is_some())
            {
                return Err(r.invalid(
                    e,
                    "fullinertia and an orientation cannot both be given".into(),
                ));
            }
            let f = [f[0], f[1], f[2], f[3], f[4], f[5]];
            super::inertia::check_positive(&f).map_err(|m| r.invalid(e, m))?;
            fullinertia = Some(f);
            (orientation::IDENTITY, [0.0; 3])
        }
        (None, d) => {
            let d = d.map_or([0.0; 3], |d| [d[0], d[1], d[2]]);
            if d.iter().any(|x| *x < 0.0) {
                return Err(r.invalid(e, format!("negative diaginertia {d:?}")));
            }
            (orientation(r, e, &a, &doc.compiler)?, d)
        }
    };
    Ok(ExplicitInertial {
        mass: mass[0],
        pos: [pos[0], pos[1], pos[2]],
        quat,
        diag,
        full: fullinertia,
        elem: e.clone(),
    })
}
