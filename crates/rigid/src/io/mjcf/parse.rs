//! The sections of an MJCF document other than the body tree: `<compiler>`, `<option>`,
//! `<asset>` (meshes, height fields, materials), `<equality>`, `<tendon>`, and a warning for each
//! kind of element rigid reads past.

use super::attrs::shown;
pub(super) use super::attrs::{
    array, boolean, int, keyword, numbers, orientation, own, partial, scalar,
};
use super::defaults::{Defaults, MAIN};
use super::mesh::{MeshData, MeshInertia};
use super::orientation::{self, Quat};
use super::xml::Element;
use super::{
    MjcfContact, MjcfEquality, MjcfEqualityKind, MjcfError, MjcfExclude, MjcfPair, MjcfTendon,
    MjcfTendonKind, Reader,
};
use crate::spatial::Vec3;
use std::collections::HashMap;
use std::path::PathBuf;

/// `<compiler>` settings (MuJoCo's defaults, `mjs_defaultSpec`).
#[derive(Clone, Debug)]
pub(super) struct Compiler {
    /// `angle="degree"` (the default) or `"radian"`.
    pub degree: bool,
    /// `eulerseq`.
    pub eulerseq: [u8; 3],
    /// `inertiafromgeom`: `Some(true)` true, `Some(false)` false, `None` auto.
    pub inertiafromgeom: Option<bool>,
    /// `inertiagrouprange`.
    pub group_range: [i32; 2],
    /// `settotalmass` (negative: off).
    pub settotalmass: f64,
    /// `boundmass`.
    pub boundmass: f64,
    /// `boundinertia`.
    pub boundinertia: f64,
    /// `balanceinertia`.
    pub balanceinertia: bool,
    /// `alignfree`.
    pub alignfree: bool,
    /// `autolimits`.
    pub autolimits: bool,
    /// `meshdir` (else `assetdir`).
    pub meshdir: Option<String>,
    /// `strippath`: mesh file names lose their folders.
    pub strippath: bool,
}

impl Default for Compiler {
    fn default() -> Self {
        Self {
            degree: true,
            eulerseq: *b"xyz",
            inertiafromgeom: None,
            group_range: [0, 5],
            settotalmass: -1.0,
            boundmass: 0.0,
            boundinertia: 0.0,
            balanceinertia: false,
            alignfree: false,
            autolimits: true,
            meshdir: None,
            strippath: false,
        }
    }
}

/// A `<mesh>` asset.
#[derive(Clone, Debug)]
pub(super) struct MeshAsset {
    pub name: String,
    /// The file (empty for a mesh given in the XML).
    pub file: PathBuf,
    /// The mesh given by `vertex` (and `face`) instead of a file: float32 vertices as MuJoCo
    /// stores them, and the triangles (the convex hull's when `face` is absent).
    pub inline: Option<MeshData>,
    pub scale: [f64; 3],
    pub refpos: [f64; 3],
    pub refquat: Quat,
    pub rule: MeshInertia,
    /// The element (for messages).
    pub elem: Element,
}

/// The document-level sections, read.
pub(super) struct Document {
    pub compiler: Compiler,
    pub gravity: Vec3,
    /// `<option timestep>`, if given.
    pub timestep: Option<f64>,
    /// `<contact>`'s `<exclude>` and `<pair>` elements.
    pub contact: MjcfContact,
    pub defaults: Defaults,
    pub meshes: Vec<MeshAsset>,
    /// Height field name → `size` (for a height-field geom's box).
    pub hfields: HashMap<String, [f64; 4]>,
    /// Material name → `rgba`.
    pub materials: HashMap<String, [f64; 4]>,
    pub equalities: Vec<MjcfEquality>,
    pub tendons: Vec<MjcfTendon>,
}

// ---------------------------------------------------------------------------------------------
// sections

/// Reads every section but the bodies.
///
/// # Errors
/// A malformed compiler setting, default class, asset, equality or tendon.
pub(super) fn document(root: &Element, r: &mut Reader) -> Result<Document, MjcfError> {
    let mut c = Compiler::default();
    for e in root.children_named("compiler") {
        compiler(e, r, &mut c)?;
    }
    let (gravity, timestep) = option(root, r)?;
    let defaults = Defaults::read(root, r)?;
    let mut doc = Document {
        compiler: c,
        gravity,
        timestep,
        contact: MjcfContact::default(),
        defaults,
        meshes: Vec::new(),
        hfields: HashMap::new(),
        materials: HashMap::new(),
        equalities: Vec::new(),
        tendons: Vec::new(),
    };
    for section in root.children_named("asset") {
        assets(section, r, &mut doc)?;
    }
    for section in root.children_named("equality") {
        for e in &section.children {
            let eq = equality(e, r, &doc)?;
            doc.equalities.push(eq);
        }
    }
    for section in root.children_named("contact") {
        for e in &section.children {
            contact(e, r, &mut doc.contact)?;
        }
    }
    for section in root.children_named("tendon") {
        for e in &section.children {
            let t = tendon(e, r, &doc)?;
            doc.tendons.push(t);
        }
    }
    ignored_sections(root, r);
    Ok(doc)
}

fn compiler(e: &Element, r: &mut Reader, c: &mut Compiler) -> Result<(), MjcfError> {
    let a = own(e);
    if a.get("coordinate") == Some("global") {
        return Err(r.invalid(
            e,
            "coordinate=\"global\" is no longer supported by MuJoCo (convert the model with \
             MuJoCo 2.3.3 or older)"
                .into(),
        ));
    }
    c.degree = keyword(
        r,
        e,
        &a,
        "angle",
        &["radian", "degree"],
        usize::from(c.degree),
    )? == 1;
    if let Some(seq) = a.get("eulerseq") {
        let b = seq.as_bytes();
        if b.len() != 3 || !b.iter().all(|x| b"xyzXYZ".contains(x)) {
            return Err(r.invalid(
                e,
                format!(
                    "eulerseq \"{}\" must be three of x, y, z, X, Y, Z",
                    shown(seq)
                ),
            ));
        }
        c.eulerseq = [b[0], b[1], b[2]];
    }
    if a.get("inertiafromgeom").is_some() {
        c.inertiafromgeom =
            match keyword(r, e, &a, "inertiafromgeom", &["false", "true", "auto"], 2)? {
                0 => Some(false),
                1 => Some(true),
                _ => None,
            };
    }
    if let Some(v) = numbers(
        r,
        e,
        a.get("inertiagrouprange"),
        "inertiagrouprange",
        2,
        true,
    )? {
        c.group_range = [v[0] as i32, v[1] as i32];
    }
    c.settotalmass = scalar(r, e, &a, "settotalmass", c.settotalmass)?;
    c.boundmass = scalar(r, e, &a, "boundmass", c.boundmass)?;
    c.boundinertia = scalar(r, e, &a, "boundinertia", c.boundinertia)?;
    c.balanceinertia = boolean(r, e, &a, "balanceinertia", c.balanceinertia)?;
    c.alignfree = boolean(r, e, &a, "alignfree", c.alignfree)?;
    c.autolimits = boolean(r, e, &a, "autolimits", c.autolimits)?;
    if let Some(d) = a.get("assetdir") {
        c.meshdir = Some(d.to_string());
    }
    if let Some(d) = a.get("meshdir") {
        c.meshdir = Some(d.to_string());
    }
    c.strippath = boolean(r, e, &a, "strippath", c.strippath)?;
    // read above, or without effect on the dynamics (rendering, threads, statistics)
    const KNOWN: [&str; 22] = [
        "angle",
        "eulerseq",
        "inertiafromgeom",
        "inertiagrouprange",
        "settotalmass",
        "boundmass",
        "boundinertia",
        "balanceinertia",
        "alignfree",
        "autolimits",
        "assetdir",
        "meshdir",
        "strippath",
        "coordinate",
        "texturedir",
        "discardvisual",
        "fusestatic",
        "usethread",
        "fitaabb",
        "saveinertial",
        "convexhull",
        "conflict",
    ];
    for (k, _) in &e.attrs {
        if !KNOWN.contains(&k.as_str()) {
            r.warn(
                e,
                format!("compiler attribute \"{k}\" is not read by rigid"),
            );
        }
    }
    if c.settotalmass > 0.0 {
        r.warn(
            e,
            format!(
                "settotalmass=\"{}\": every body's mass and inertia are scaled so that the \
                 total is this (as MuJoCo does)",
                c.settotalmass
            ),
        );
    }
    Ok(())
}

/// `<option gravity timestep>` and `<flag gravity="disable">`.
fn option(root: &Element, r: &mut Reader) -> Result<(Vec3, Option<f64>), MjcfError> {
    let mut g = [0.0, 0.0, -9.81];
    let mut enabled = true;
    let mut timestep = None;
    for e in root.children_named("option") {
        let a = own(e);
        g = array(r, e, &a, "gravity", g)?;
        if let Some(v) = numbers(r, e, a.get("timestep"), "timestep", 1, true)? {
            if v[0] <= 0.0 {
                return Err(r.invalid(e, format!("timestep = {} must be positive", v[0])));
            }
            timestep = Some(v[0]);
        }
        for f in e.children_named("flag") {
            let fa = own(f);
            if fa.get("gravity").is_some() {
                enabled = keyword(r, f, &fa, "gravity", &["disable", "enable"], 1)? == 1;
            }
        }
    }
    let g = if enabled {
        Vec3::from(g)
    } else {
        Vec3::zeros()
    };
    Ok((g, timestep))
}

/// One element of `<contact>`: `<exclude body1 body2>` or `<pair geom1 geom2 [friction]>` (the
/// names are resolved with the geometry, `rigid::io::collision`).
fn contact(e: &Element, r: &mut Reader, out: &mut MjcfContact) -> Result<(), MjcfError> {
    let a = own(e);
    let name = |key: &str| {
        a.get(key)
            .map(str::to_string)
            .ok_or_else(|| r.invalid(e, format!("<{}> needs \"{key}\"", e.tag)))
    };
    match e.tag.as_str() {
        "exclude" => out.excludes.push(MjcfExclude {
            body1: name("body1")?,
            body2: name("body2")?,
            line: e.line,
        }),
        "pair" => {
            let friction = numbers(r, e, a.get("friction"), "friction", 5, false)?
                .and_then(|v| v.first().copied());
            if friction.is_some_and(|f| f < 0.0) {
                return Err(r.invalid(e, "a negative friction".into()));
            }
            out.pairs.push(MjcfPair {
                geom1: name("geom1")?,
                geom2: name("geom2")?,
                friction,
                line: e.line,
            });
        }
        _ => r.warn(e, format!("<contact><{}> is not read", e.tag)),
    }
    Ok(())
}

fn assets(section: &Element, r: &mut Reader, doc: &mut Document) -> Result<(), MjcfError> {
    for e in &section.children {
        match e.tag.as_str() {
            "mesh" => {
                let m = mesh_asset(e, r, doc)?;
                doc.meshes.push(m);
            }
            "hfield" => {
                let a = own(e);
                let size = array(r, e, &a, "size", [0.0; 4])?;
                if let Some(n) = a.get("name").or(a.get("file")) {
                    doc.hfields.insert(stem(n), size);
                }
            }
            "material" => {
                let a = doc.defaults.resolve(e, MAIN, r)?;
                let rgba = array(r, e, &a, "rgba", [1.0; 4])?;
                if let Some(n) = e.attr("name") {
                    doc.materials.insert(n.to_string(), rgba);
                }
            }
            "texture" | "skin" | "model" => {}
            _ => r.warn(e, format!("unknown asset <{}> ignored", e.tag)),
        }
    }
    Ok(())
}

/// The file name without folder and extension (MuJoCo's default asset name).
fn stem(file: &str) -> String {
    let base = file.rsplit(['/', '\\']).next().unwrap_or(file);
    match base.rfind('.') {
        Some(i) if i > 0 => base[..i].to_string(),
        _ => base.to_string(),
    }
}

fn mesh_asset(e: &Element, r: &mut Reader, doc: &Document) -> Result<MeshAsset, MjcfError> {
    let a = doc.defaults.resolve(e, MAIN, r)?;
    if a.get("builtin").is_some() || a.get("plugin").is_some() {
        return Err(r.invalid(
            e,
            "built-in and plugin meshes are not supported (give a file)".into(),
        ));
    }
    let inline = match (a.get("file"), a.get("vertex")) {
        (Some(_), Some(_)) => {
            return Err(r.invalid(e, "a mesh has a file or vertices, not both".into()))
        }
        (None, None) => {
            return Err(r.invalid(e, "a mesh needs a file or vertices (\"vertex\")".into()))
        }
        (None, Some(vertex)) => Some(inline_mesh(r, e, vertex, a.get("face"))?),
        (Some(_), None) => None,
    };
    let file = a.get("file").unwrap_or_default();
    let name = match (e.attr("name"), &inline) {
        (Some(n), _) => n.to_string(),
        (None, None) => stem(file),
        (None, Some(_)) => return Err(r.invalid(e, "a mesh given by vertices needs a name".into())),
    };
    let rule = match keyword(
        r,
        e,
        &a,
        "inertia",
        &["legacy", "exact", "convex", "shell"],
        0,
    )? {
        0 => MeshInertia::Legacy,
        1 => MeshInertia::Exact,
        2 => MeshInertia::Convex,
        _ => MeshInertia::Shell,
    };
    let mut refquat = array(r, e, &a, "refquat", orientation::IDENTITY)?;
    if orientation::normalize(&mut refquat) == 0.0 {
        return Err(r.invalid(e, "zero refquat (or too long to normalise)".into()));
    }
    let file = if doc.compiler.strippath {
        file.rsplit(['/', '\\']).next().unwrap_or(file)
    } else {
        file
    };
    Ok(MeshAsset {
        name,
        file: if inline.is_some() {
            PathBuf::new()
        } else {
            mesh_path(r, e, file, &doc.compiler)
        },
        inline,
        scale: array(r, e, &a, "scale", [1.0; 3])?,
        refpos: array(r, e, &a, "refpos", [0.0; 3])?,
        refquat,
        rule,
        elem: e.clone(),
    })
}

/// A mesh given in the XML: `vertex` (x y z per vertex, at least 4, stored as float32 as
/// MuJoCo does) and `face` (three 0-based vertex indices per triangle); without `face`, the
/// triangles of the vertices' convex hull (MuJoCo's rule for a mesh without faces).
fn inline_mesh(
    r: &Reader,
    e: &Element,
    vertex: &str,
    face: Option<&str>,
) -> Result<MeshData, MjcfError> {
    let v = numbers(r, e, Some(vertex), "vertex", usize::MAX, false)?.unwrap_or_default();
    if v.len() % 3 != 0 || v.len() < 12 {
        return Err(r.invalid(
            e,
            format!(
                "attribute \"vertex\" has {} numbers: 3 per vertex, at least 4 vertices",
                v.len()
            ),
        ));
    }
    let vertices: Vec<[f32; 3]> = v
        .chunks_exact(3)
        .map(|c| [c[0] as f32, c[1] as f32, c[2] as f32])
        .collect();
    if vertices.iter().flatten().any(|x| !x.is_finite()) {
        return Err(r.invalid(
            e,
            "attribute \"vertex\": a number beyond float32's range (MuJoCo stores vertices as \
             float32)"
                .into(),
        ));
    }
    let faces = match face {
        Some(text) => {
            let f = numbers(r, e, Some(text), "face", usize::MAX, false)?.unwrap_or_default();
            let index = |x: f64| {
                (x.fract() == 0.0 && x >= 0.0 && x < vertices.len() as f64).then_some(x as usize)
            };
            let faces: Option<Vec<[usize; 3]>> = (f.len() % 3 == 0 && !f.is_empty())
                .then(|| {
                    f.chunks_exact(3)
                        .map(|c| Some([index(c[0])?, index(c[1])?, index(c[2])?]))
                        .collect()
                })
                .flatten();
            faces.ok_or_else(|| {
                r.invalid(
                    e,
                    format!(
                        "attribute \"face\": 3 vertex indices (0 to {}) per triangle",
                        vertices.len() - 1
                    ),
                )
            })?
        }
        #[cfg(feature = "collision")]
        None => {
            let points: Vec<Vec3> = vertices
                .iter()
                .map(|p| Vec3::new(p[0].into(), p[1].into(), p[2].into()))
                .collect();
            let (hull, faces) = crate::collision::hull_triangles(&points).ok_or_else(|| {
                r.invalid(
                    e,
                    "the convex hull of its vertices is flat or degenerate".into(),
                )
            })?;
            // the hull's vertices are some of the float32 ones: exact
            let vertices = hull.iter().map(|p| [p.x as f32, p.y as f32, p.z as f32]);
            return Ok(MeshData {
                vertices: vertices.collect(),
                faces,
            });
        }
        #[cfg(not(feature = "collision"))]
        None => {
            return Err(r.invalid(
                e,
                "a mesh without \"face\" is its vertices' convex hull, which needs the \
                 `collision` feature"
                    .into(),
            ))
        }
    };
    Ok(MeshData { vertices, faces })
}

/// Where a mesh file is: `meshdir/file` from the main file's folder if it exists there, else
/// next to the file that names it (MuJoCo's `ResolveFilePath`).
fn mesh_path(r: &Reader, e: &Element, file: &str, c: &Compiler) -> PathBuf {
    let f = std::path::Path::new(file);
    if f.is_absolute() {
        return f.to_path_buf();
    }
    let dir = r.sources.dir.join(c.meshdir.as_deref().unwrap_or(""));
    let main = dir.join(f);
    if main.is_file() || e.file == 0 {
        return main;
    }
    let near = r.sources.folder(e.file).join(f);
    if near.is_file() {
        near
    } else {
        main
    }
}

fn target(e: &Element, name: &str) -> Option<String> {
    e.attr(name).map(str::to_string)
}

fn equality(e: &Element, r: &mut Reader, doc: &Document) -> Result<MjcfEquality, MjcfError> {
    // MuJoCo keeps the defaults of every equality kind under the tag `equality`
    let a = doc.defaults.resolve_as(e, MAIN, "equality", r)?;
    let sites = e.attr("site1").is_some();
    let pair = |n1: &str, n2: &str| [target(e, n1), target(e, n2)];
    let kind = match e.tag.as_str() {
        "connect" => MjcfEqualityKind::Connect {
            targets: if sites {
                pair("site1", "site2")
            } else {
                pair("body1", "body2")
            },
            sites,
            anchor: Vec3::from(array(r, e, &a, "anchor", [0.0; 3])?),
        },
        "weld" => MjcfEqualityKind::Weld {
            targets: if sites {
                pair("site1", "site2")
            } else {
                pair("body1", "body2")
            },
            sites,
            anchor: Vec3::from(array(r, e, &a, "anchor", [0.0; 3])?),
            relpose: numbers(r, e, a.get("relpose"), "relpose", 7, true)?.map(|v| {
                let mut p = [0.0; 7];
                p.copy_from_slice(&v);
                p
            }),
            torquescale: scalar(r, e, &a, "torquescale", 1.0)?,
        },
        "joint" => MjcfEqualityKind::Joint {
            joints: pair("joint1", "joint2"),
            polycoef: partial(r, e, &a, "polycoef", [0.0, 1.0, 0.0, 0.0, 0.0])?,
        },
        "tendon" => MjcfEqualityKind::Tendon {
            tendons: pair("tendon1", "tendon2"),
            polycoef: partial(r, e, &a, "polycoef", [0.0, 1.0, 0.0, 0.0, 0.0])?,
        },
        other => {
            r.warn(
                e,
                format!("equality <{other}> kept by tag only (rigid has no constraints yet)"),
            );
            MjcfEqualityKind::Other(other.to_string())
        }
    };
    Ok(MjcfEquality {
        name: target(e, "name"),
        kind,
        active: boolean(r, e, &a, "active", true)?,
        line: e.line,
    })
}

fn tendon(e: &Element, r: &mut Reader, doc: &Document) -> Result<MjcfTendon, MjcfError> {
    let a = doc.defaults.resolve_as(e, MAIN, "tendon", r)?;
    let kind = match e.tag.as_str() {
        "fixed" => {
            let mut joints = Vec::new();
            for j in e.children_named("joint") {
                let ja = own(j);
                let name = j.attr("joint").unwrap_or_default().to_string();
                joints.push((name, scalar(r, j, &ja, "coef", 0.0)?));
            }
            MjcfTendonKind::Fixed(joints)
        }
        "spatial" => MjcfTendonKind::Spatial(
            e.children
                .iter()
                .map(|c| {
                    let t = c
                        .attr("site")
                        .or(c.attr("geom"))
                        .or(c.attr("divisor"))
                        .unwrap_or_default();
                    (c.tag.clone(), t.to_string())
                })
                .collect(),
        ),
        other => {
            return Err(r.invalid(e, format!("unknown tendon <{other}>")));
        }
    };
    let armature = scalar(r, e, &a, "armature", 0.0)?;
    if armature != 0.0 {
        r.warn(
            e,
            format!(
                "tendon armature {armature}: MuJoCo adds the tendon's inertia to the mass matrix \
                 and the bias; rigid models no tendons, so its M and bias leave it out"
            ),
        );
    }
    let range = array(r, e, &a, "range", [0.0; 2])?;
    let limited = match keyword(r, e, &a, "limited", &["false", "true", "auto"], 2)? {
        0 => false,
        1 => true,
        _ => range[0] < range[1],
    };
    Ok(MjcfTendon {
        name: target(e, "name"),
        kind,
        stiffness: scalar(r, e, &a, "stiffness", 0.0)?,
        damping: scalar(r, e, &a, "damping", 0.0)?,
        frictionloss: scalar(r, e, &a, "frictionloss", 0.0)?,
        armature,
        range: limited.then_some(range),
        line: e.line,
    })
}

/// What rigid reads past: one warning per kind of element, at its first occurrence.
fn ignored_sections(root: &Element, r: &mut Reader) {
    const KNOWN: [&str; 9] = [
        "contact",
        "compiler",
        "option",
        "default",
        "asset",
        "worldbody",
        "equality",
        "tendon",
        "size",
    ];
    const SKIPPED: [(&str, &str); 8] = [
        ("actuator", "actuators are not modelled by rigid"),
        ("sensor", "sensors are not modelled by rigid"),
        ("keyframe", "keyframes are not read"),
        ("visual", "rendering settings"),
        ("statistic", "rendering statistics"),
        ("custom", "custom numeric and text data are not read"),
        ("extension", "plugins are not supported"),
        (
            "deformable",
            "deformable bodies (flex, skin) are not modelled by rigid",
        ),
    ];
    let mut seen: Vec<&str> = Vec::new();
    for e in &root.children {
        if KNOWN.contains(&e.tag.as_str()) || seen.contains(&e.tag.as_str()) {
            continue;
        }
        seen.push(&e.tag);
        let why = SKIPPED
            .iter()
            .find(|(t, _)| *t == e.tag)
            .map_or("unknown section", |(_, w)| *w);
        let n: usize = root
            .children_named(&e.tag)
            .map(|s| s.children.len().max(1))
            .sum();
        r.warn(e, format!("{why}: {n} element(s) ignored"));
    }
}
