//! The shapes of an MJCF model: every geom of groups 0 to 2 (those MuJoCo's viewer shows by
//! default; all the geoms of a body that has none there, such as a skinned animal's collision
//! capsules), at its frame in its body: boxes, spheres, capsules, cylinders, ellipsoids (a sphere
//! mesh scaled), meshes (STL, OBJ, MSH, with the asset's `scale`, `refpos` and `refquat` baked
//! in) and planes (a thin slab, the scene's size where the plane is infinite). Height fields are
//! not drawn (a warning).

use super::shapes::{shape, simplify};
use super::{Node, Scene, Shape};
use rigid::io::mjcf::{load_mjcf, mesh::read_trimesh, MjcfShape};
use rigid::mass::TriMesh;
use rigid::spatial::{Transform, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// The nodes of the MJCF file at `path`; `false` when it cannot be read (the caller draws a
/// stick figure).
pub(crate) fn nodes(scene: &mut Scene, path: &Path) -> bool {
    let m = match load_mjcf(path) {
        Ok(m) => m,
        Err(e) => {
            scene.warnings.push(format!("{e}: drawn as a stick figure"));
            return false;
        }
    };
    let mut meshes: HashMap<String, Option<usize>> = HashMap::new();
    let mut sphere: Option<usize> = None;
    let extent = scene.extent;
    let shown = |g: &rigid::io::mjcf::MjcfGeom| (0..3).contains(&g.group);
    let mut visible = vec![false; m.bodies.len()];
    m.geoms
        .iter()
        .filter(|g| shown(g))
        .for_each(|g| visible[g.body] = true);
    for g in m.geoms.iter().filter(|g| shown(g) || !visible[g.body]) {
        let c = g.rgba;
        let id = Transform::identity();
        let s: Shape = match &g.shape {
            MjcfShape::Sphere { radius } => shape("sphere", [*radius, 0.0, 0.0], id, c),
            MjcfShape::Capsule {
                radius,
                half_length,
            } => shape("capsule", [*radius, 2.0 * half_length, 0.0], id, c),
            MjcfShape::Cylinder {
                radius,
                half_length,
            } => shape("cylinder", [*radius, 2.0 * half_length, 0.0], id, c),
            MjcfShape::Box { half } => shape("box", (half * 2.0).into(), id, c),
            MjcfShape::Plane { half } => {
                let side = |h: f64| if h > 0.0 { 2.0 * h } else { 4.0 * extent };
                let below = Transform::from_translation(Vec3::new(0.0, 0.0, -0.001));
                shape("box", [side(half[0]), side(half[1]), 0.002], below, c)
            }
            MjcfShape::Ellipsoid { radii } => {
                let i = *sphere.get_or_insert_with(|| {
                    scene.meshes.push(simplify(&unit_sphere(16)));
                    scene.meshes.len() - 1
                });
                Shape {
                    kind: "mesh",
                    size: [0.0; 3],
                    mesh: Some(i),
                    scale: (*radii).into(),
                    origin: id,
                    color: c,
                }
            }
            MjcfShape::Mesh {
                name,
                file,
                inline,
                scale,
                refpos,
                refrot,
            } => {
                let index = *meshes.entry(name.clone()).or_insert_with(|| {
                    match inline.clone().map_or_else(|| read_trimesh(file), Ok) {
                        Ok(mut t) if !t.triangles.is_empty() => {
                            // v ← scale ∘ (Rᵀ (v - refpos)), as the importer places it
                            for v in &mut t.vertices {
                                *v = (refrot.transpose() * (*v - refpos)).component_mul(scale);
                            }
                            scene.meshes.push(simplify(&t));
                            Some(scene.meshes.len() - 1)
                        }
                        Ok(_) | Err(_) => None,
                    }
                });
                match index {
                    Some(i) => Shape {
                        kind: "mesh",
                        size: [0.0; 3],
                        mesh: Some(i),
                        scale: [1.0; 3],
                        origin: id,
                        color: c,
                    },
                    None => {
                        scene.warnings.push(format!(
                            "mesh \"{name}\" ({}) cannot be read: drawn as a 5 cm box",
                            file.display()
                        ));
                        shape("box", [0.05; 3], id, [0.9, 0.5, 0.4, 1.0])
                    }
                }
            }
            MjcfShape::Hfield { name } => {
                scene.warnings.push(format!(
                    "height field \"{name}\" (line {}) is not drawn",
                    g.line
                ));
                continue;
            }
        };
        let body = &m.bodies[g.body].name;
        scene.nodes.push(Node {
            name: g.name.clone().unwrap_or_else(|| body.clone()),
            parent: g.parent,
            placement: g.placement,
            shapes: vec![s],
        });
    }
    !scene.nodes.is_empty()
}

/// A sphere of radius 1: `n` rings of `2n` segments.
fn unit_sphere(n: usize) -> TriMesh {
    use std::f64::consts::PI;
    let mut vertices = vec![Vec3::z(), -Vec3::z()];
    for i in 1..n {
        let t = PI * i as f64 / n as f64;
        for k in 0..2 * n {
            let p = PI * k as f64 / n as f64;
            vertices.push(Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()));
        }
    }
    let at = |i: usize, k: usize| 2 + (i - 1) * 2 * n + k % (2 * n);
    let mut triangles = Vec::new();
    for k in 0..2 * n {
        triangles.push([0, at(1, k), at(1, k + 1)]);
        triangles.push([1, at(n - 1, k + 1), at(n - 1, k)]);
        for i in 1..n - 1 {
            triangles.push([at(i, k), at(i + 1, k), at(i + 1, k + 1)]);
            triangles.push([at(i, k), at(i + 1, k + 1), at(i, k + 1)]);
        }
    }
    TriMesh::new(vertices, triangles)
}
