//! The shapes of a replay: a URDF's visual geometry (its collision geometry for a link with no
//! visual), a stick figure for a model without geometry, the inertia-equivalent box of one body.

use super::{Mesh, Node, Scene, Shape};
use rigid::io::mesh_file::read_mesh;
use rigid::io::urdf::{parse_urdf_file, resolve_mesh_path, UrdfGeometry, UrdfRobot, UrdfShape};
use rigid::mass::{RotationalInertia, TriMesh};
use rigid::multibody::{FrameKind, JointId, Model};
use rigid::spatial::{Mat3, Transform, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Most triangles kept per mesh (larger meshes are simplified by vertex clustering).
const MESH_TRIANGLES: usize = 12_000;

const GREY: [f64; 4] = [0.72, 0.73, 0.76, 1.0];

pub(crate) fn shape(
    kind: &'static str,
    size: [f64; 3],
    origin: Transform,
    color: [f64; 4],
) -> Shape {
    Shape {
        kind,
        size,
        mesh: None,
        scale: [1.0; 3],
        origin,
        color,
    }
}

/// Vertex clustering (Rossignac & Borrel 1993): vertices snapped to a grid of `cells` cells along
/// the largest extent and merged, degenerate and repeated triangles dropped.
fn cluster(mesh: &TriMesh, cells: f64) -> Mesh {
    let (lo, hi) = mesh.vertices.iter().fold(
        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.inf(v), hi.sup(v)),
    );
    let size = (hi - lo).max().max(1e-12) / cells;
    let mut ids: HashMap<[i64; 3], u32> = HashMap::new();
    let mut sums: Vec<(Vec3, f64)> = Vec::new();
    let remap: Vec<u32> = mesh
        .vertices
        .iter()
        .map(|v| {
            let key = [0, 1, 2].map(|k| ((v[k] - lo[k]) / size).floor() as i64);
            let id = *ids.entry(key).or_insert_with(|| {
                sums.push((Vec3::zeros(), 0.0));
                (sums.len() - 1) as u32
            });
            sums[id as usize].0 += v;
            sums[id as usize].1 += 1.0;
            id
        })
        .collect();
    let mut seen = std::collections::HashSet::new();
    let mut indices = Vec::new();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| remap[i]);
        if a == b || b == c || a == c {
            continue;
        }
        let mut key = [a, b, c];
        key.sort_unstable();
        if seen.insert(key) {
            indices.extend([a, b, c]);
        }
    }
    let positions = sums
        .iter()
        .flat_map(|(s, n)| {
            let p = s / *n;
            [p.x as f32, p.y as f32, p.z as f32]
        })
        .collect();
    Mesh { positions, indices }
}

/// The mesh for the page: as read, or simplified to at most [`MESH_TRIANGLES`] triangles.
pub(crate) fn simplify(mesh: &TriMesh) -> Mesh {
    if mesh.triangles.len() <= MESH_TRIANGLES {
        return Mesh {
            positions: mesh
                .vertices
                .iter()
                .flat_map(|v| [v.x as f32, v.y as f32, v.z as f32])
                .collect(),
            indices: mesh.triangles.iter().flatten().map(|&i| i as u32).collect(),
        };
    }
    let mut cells = 400.0;
    loop {
        let m = cluster(mesh, cells);
        if m.indices.len() / 3 <= MESH_TRIANGLES || cells < 8.0 {
            return m;
        }
        cells *= 0.75;
    }
}

/// Reads meshes once each.
struct Meshes<'a> {
    urdf: &'a Path,
    cache: HashMap<PathBuf, Option<usize>>,
}

impl Meshes<'_> {
    /// The index of the mesh `filename` in `scene.meshes`, or a warning.
    fn get(&mut self, scene: &mut Scene, filename: &str) -> Result<usize, String> {
        let path = resolve_mesh_path(filename, Some(self.urdf))
            .ok_or_else(|| format!("mesh {filename:?} not found"))?;
        if let Some(hit) = self.cache.get(&path) {
            return hit.ok_or_else(|| format!("mesh {filename:?} cannot be read"));
        }
        let read = read_mesh(&path);
        let result = match read {
            Ok(m) if !m.triangles.is_empty() => {
                scene.meshes.push(simplify(&m));
                Ok(scene.meshes.len() - 1)
            }
            Ok(_) => Err(format!("mesh {filename:?} has no triangles")),
            Err(e) => Err(format!("mesh {filename:?}: {e}")),
        };
        self.cache.insert(path, result.as_ref().ok().copied());
        result
    }
}

/// The shapes of one link's geometries; a mesh that cannot be read becomes a 5 cm box (and a
/// warning).
fn link_shapes(
    scene: &mut Scene,
    meshes: &mut Meshes,
    link: &str,
    geoms: &[UrdfGeometry],
) -> Vec<Shape> {
    let mut out = Vec::new();
    for g in geoms {
        let color = g.rgba.unwrap_or(GREY);
        let s = match &g.shape {
            UrdfShape::Box { size } => shape("box", [size.x, size.y, size.z], g.origin, color),
            UrdfShape::Cylinder { radius, length } => {
                shape("cylinder", [*radius, *length, 0.0], g.origin, color)
            }
            UrdfShape::Sphere { radius } => shape("sphere", [*radius, 0.0, 0.0], g.origin, color),
            UrdfShape::Capsule { radius, length } => {
                shape("capsule", [*radius, *length, 0.0], g.origin, color)
            }
            UrdfShape::Mesh { filename, scale } => match meshes.get(scene, filename) {
                Ok(i) => Shape {
                    kind: "mesh",
                    size: [0.0; 3],
                    mesh: Some(i),
                    scale: [scale.x, scale.y, scale.z],
                    origin: g.origin,
                    color,
                },
                Err(e) => {
                    scene
                        .warnings
                        .push(format!("link \"{link}\": {e}; drawn as a 5 cm box"));
                    shape("box", [0.05; 3], g.origin, [0.9, 0.5, 0.4, 1.0])
                }
            },
        };
        out.push(s);
    }
    out
}

/// The nodes of `model`: the visual (else collision) geometry of each link of the URDF at
/// `urdf`, placed at the link's body frame, or for an MJCF file (`.xml`) its geoms
/// (the MJCF drawing); a stick figure when there is no file or no link has any geometry.
pub fn robot_nodes(model: &Model, urdf: Option<&Path>) -> Scene {
    let mut scene = Scene {
        extent: model_extent(model),
        ..Scene::default()
    };
    let mjcf = urdf.filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("xml")));
    if let Some(path) = mjcf {
        if !super::mjcf::nodes(&mut scene, path) {
            scene.nodes.clear();
            stick_figure(model, &mut scene);
        }
        return scene;
    }
    if let Some(path) = urdf {
        match parse_urdf_file(path) {
            Ok(robot) => urdf_nodes(&mut scene, model, &robot, path),
            Err(e) => scene.warnings.push(format!("{e}: drawn as a stick figure")),
        }
    }
    if scene.nodes.is_empty() {
        stick_figure(model, &mut scene);
    }
    scene
}

/// The nodes of the links of a parsed URDF (its meshes resolved beside `path`, which need not
/// exist when the file has none), as [`robot_nodes`] draws a URDF file.
pub fn robot_nodes_of_urdf(model: &Model, robot: &UrdfRobot, path: &Path) -> Scene {
    let mut scene = Scene {
        extent: model_extent(model),
        ..Scene::default()
    };
    urdf_nodes(&mut scene, model, robot, path);
    if scene.nodes.is_empty() {
        stick_figure(model, &mut scene);
    }
    scene
}

fn urdf_nodes(scene: &mut Scene, model: &Model, robot: &UrdfRobot, path: &Path) {
    let mut meshes = Meshes {
        urdf: path,
        cache: HashMap::new(),
    };
    for link in &robot.links {
        let geoms = if link.visuals.is_empty() {
            &link.collisions
        } else {
            &link.visuals
        };
        if geoms.is_empty() {
            continue;
        }
        let Some(f) = model.frame_id_of_kind(&link.name, FrameKind::Body) else {
            continue;
        };
        let frame = &model.frames()[f.0];
        let shapes = link_shapes(scene, &mut meshes, &link.name, geoms);
        scene.nodes.push(Node {
            name: link.name.clone(),
            parent: frame.parent,
            placement: frame.placement,
            shapes,
        });
    }
}

/// The largest distance from the world origin to a joint origin at `q = neutral`, plus 0.1 m.
fn model_extent(model: &Model) -> f64 {
    let mut data = rigid::multibody::Data::new(model);
    let q = rigid::multibody::neutral(model);
    if rigid::multibody::forward_kinematics_q(model, &mut data, &q).is_err() {
        return 1.0;
    }
    data.placements
        .iter()
        .map(|p| p.translation.norm())
        .fold(0.0, f64::max)
        + 0.1
}

/// A frame whose z axis runs from `a` to `b`, centred between them.
fn segment(a: Vec3, b: Vec3) -> (Transform, f64) {
    let d = b - a;
    let l = d.norm();
    let z = d / l.max(1e-12);
    let helper = if z.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::y()
    };
    let x = helper.cross(&z).normalize();
    let y = z.cross(&x);
    (
        Transform::new(Mat3::from_columns(&[x, y, z]), (a + b) * 0.5),
        l,
    )
}

/// Each body as a sphere at its joint and capsules to its children's joints (or to its CoM).
fn stick_figure(model: &Model, scene: &mut Scene) {
    let r = (0.03 * scene.extent).clamp(0.005, 0.05);
    let colors = [[0.25, 0.45, 0.8, 1.0], [0.85, 0.55, 0.2, 1.0]];
    for (i, j) in model.joints().iter().enumerate() {
        let color = colors[i % 2];
        let mut shapes = vec![shape(
            "sphere",
            [1.3 * r, 0.0, 0.0],
            Transform::identity(),
            [0.3, 0.3, 0.3, 1.0],
        )];
        let mut ends: Vec<Vec3> = model
            .joints()
            .iter()
            .filter(|c| c.parent == Some(JointId(i)))
            .map(|c| c.placement.translation)
            .collect();
        let com = model.inertias()[i].com();
        if ends.is_empty() && com.norm() > r {
            ends.push(com * 2.0);
        }
        for e in ends {
            if e.norm() > 1e-6 {
                let (origin, l) = segment(Vec3::zeros(), e);
                shapes.push(shape("capsule", [r, l, 0.0], origin, color));
            }
        }
        scene.nodes.push(Node {
            name: j.name.clone(),
            parent: Some(JointId(i)),
            placement: Transform::identity(),
            shapes,
        });
    }
}

/// One node: the box with the body's mass and principal moments (edges
/// `a² = 6 (I₂ + I₃ - I₁)/m`, …), in the principal axes at the CoM, for a body whose frame is
/// at its CoM.
pub fn body_box(mass: f64, inertia: &RotationalInertia) -> Scene {
    let (l, axes) = inertia.principal();
    let edge = |a: f64, b: f64, c: f64| (6.0 * (b + c - a) / mass.max(1e-300)).max(0.0).sqrt();
    let mut size = [
        edge(l[0], l[1], l[2]),
        edge(l[1], l[2], l[0]),
        edge(l[2], l[0], l[1]),
    ];
    let big = size.iter().copied().fold(0.0, f64::max).max(1e-3);
    for s in &mut size {
        *s = s.max(0.02 * big); // a rod or a plate still shows
    }
    Scene {
        extent: big,
        nodes: vec![Node {
            name: "body".into(),
            parent: None,
            placement: Transform::identity(),
            shapes: vec![shape(
                "box",
                size,
                Transform::new(axes, Vec3::zeros()),
                [0.3, 0.5, 0.85, 1.0],
            )],
        }],
        ..Scene::default()
    }
}
