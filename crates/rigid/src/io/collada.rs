//! COLLADA (`.dae`) meshes, the other common format of robot description packages: the
//! triangles of every geometry instanced by the visual scene, placed by the scene graph's node
//! transforms and scaled to metres by `<asset><unit meter>`.
//!
//! Read: `<triangles>`, `<polylist>` and `<polygons>` (polygons as fans), `<matrix>`,
//! `<translate>`, `<rotate>` and `<scale>` node transforms, `<instance_geometry>` and
//! `<instance_node>`. Ignored: materials, normals, texture coordinates, lines, animations, and
//! `<up_axis>`: ROS tools (rviz, the URDF toolchain) draw a mesh's coordinates as they are, and
//! the Y-up files of example-robot-data (TIAGo's arm) only line up with their STL twins that way.
//! A file without a visual scene gives every geometry once, untransformed.

use super::mesh_file::MeshFileError;
use crate::mass::TriMesh;
use crate::spatial::{so3, Vec3};
use nalgebra::Matrix4;
use roxmltree::{Document, Node};
use std::collections::HashMap;

type Mat4 = Matrix4<f64>;

fn err(msg: impl Into<String>) -> MeshFileError {
    MeshFileError::Dae(msg.into())
}

/// Reads the triangles of a COLLADA document (text) in metres; duplicate vertices are merged.
///
/// ```
/// let dae = r##"<COLLADA><asset><unit meter="0.001"/></asset>
///   <library_geometries><geometry id="g"><mesh>
///     <source id="p"><float_array id="pa" count="9">0 0 0 1000 0 0 0 1000 0</float_array>
///       <technique_common><accessor source="#pa" count="3" stride="3"/></technique_common></source>
///     <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
///     <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
///   </mesh></geometry></library_geometries></COLLADA>"##;
/// let mesh = rigid::io::collada::parse_dae(dae).unwrap();
/// assert_eq!(mesh.triangles.len(), 1);
/// assert!((mesh.vertices[1].x - 1.0).abs() < 1e-12); // millimetres to metres
/// ```
///
/// # Errors
/// [`MeshFileError::Dae`] for XML that is not COLLADA or a geometry that cannot be read.
pub fn parse_dae(text: &str) -> Result<TriMesh, MeshFileError> {
    let opts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    let doc = Document::parse_with_options(text, opts).map_err(|e| err(e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "COLLADA" {
        return Err(err(format!(
            "root element <{}> is not <COLLADA>",
            root.tag_name().name()
        )));
    }
    let by_id: HashMap<&str, Node> = root
        .descendants()
        .filter_map(|n| n.attribute("id").map(|id| (id, n)))
        .collect();
    let unit = descend(root, &["asset", "unit"])
        .and_then(|u| u.attribute("meter"))
        .and_then(|m| m.trim().parse::<f64>().ok())
        .filter(|m| m.is_finite() && *m > 0.0)
        .unwrap_or(1.0);

    let mut geometries: HashMap<&str, TriMesh> = HashMap::new();
    for g in root
        .descendants()
        .filter(|n| n.has_tag_name("geometry"))
        .filter(|n| n.attribute("id").is_some())
    {
        if let Some(mesh) = child(g, "mesh") {
            geometries.insert(
                g.attribute("id").unwrap_or_default(),
                read_mesh(mesh, &by_id)?,
            );
        }
    }

    let mut out = TriMesh::default();
    let scene = descend(root, &["scene", "instance_visual_scene"])
        .and_then(|i| i.attribute("url"))
        .and_then(|u| by_id.get(u.trim_start_matches('#')).copied())
        .or_else(|| root.descendants().find(|n| n.has_tag_name("visual_scene")));
    match scene {
        Some(scene) => {
            let mut stack: Vec<(Node, Mat4, usize)> = scene
                .children()
                .filter(|n| n.has_tag_name("node"))
                .map(|n| (n, Mat4::identity(), 0))
                .collect();
            while let Some((node, parent, depth)) = stack.pop() {
                if depth > 64 {
                    return Err(err("scene graph deeper than 64 nodes (a cycle?)"));
                }
                let t = parent * node_transform(node)?;
                for c in node.children().filter(|c| c.is_element()) {
                    match c.tag_name().name() {
                        "node" => stack.push((c, t, depth + 1)),
                        "instance_node" => {
                            if let Some(n) = c
                                .attribute("url")
                                .and_then(|u| by_id.get(u.trim_start_matches('#')))
                            {
                                stack.push((*n, t, depth + 1));
                            }
                        }
                        "instance_geometry" => {
                            let url = c.attribute("url").unwrap_or_default();
                            if let Some(g) = geometries.get(url.trim_start_matches('#')) {
                                append(&mut out, g, &t);
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
        None => {
            for g in geometries.values() {
                append(&mut out, g, &Mat4::identity());
            }
        }
    }
    for v in &mut out.vertices {
        *v *= unit;
    }
    out.merge_duplicate_vertices();
    Ok(out)
}

fn child<'a, 'i>(n: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.has_tag_name(tag))
}

fn descend<'a, 'i>(n: Node<'a, 'i>, path: &[&str]) -> Option<Node<'a, 'i>> {
    path.iter().try_fold(n, |n, tag| child(n, tag))
}

fn numbers(node: Node) -> Result<Vec<f64>, MeshFileError> {
    node.text()
        .unwrap_or_default()
        .split_whitespace()
        .map(|w| {
            w.parse::<f64>().map_err(|_| {
                err(format!(
                    "<{}>: \"{w}\" is not a number",
                    node.tag_name().name()
                ))
            })
        })
        .collect()
}

fn indices(node: Node) -> Result<Vec<usize>, MeshFileError> {
    node.text()
        .unwrap_or_default()
        .split_whitespace()
        .map(|w| {
            w.parse::<usize>().map_err(|_| {
                err(format!(
                    "<{}>: \"{w}\" is not an index",
                    node.tag_name().name()
                ))
            })
        })
        .collect()
}

/// The local transform of a `<node>`: its transform elements composed in document order.
fn node_transform(node: Node) -> Result<Mat4, MeshFileError> {
    let mut t = Mat4::identity();
    for c in node.children().filter(|c| c.is_element()) {
        let x = match c.tag_name().name() {
            "matrix" | "translate" | "rotate" | "scale" => numbers(c)?,
            _ => continue,
        };
        let m = match (c.tag_name().name(), x.as_slice()) {
            ("matrix", x) if x.len() == 16 => Mat4::from_row_slice(x),
            ("translate", [a, b, z]) => Mat4::new_translation(&Vec3::new(*a, *b, *z)),
            ("rotate", [a, b, z, deg]) => {
                let axis = Vec3::new(*a, *b, *z);
                let r = if axis.norm() > 0.0 {
                    so3::exp(&(axis.normalize() * deg.to_radians()))
                } else {
                    crate::spatial::Mat3::identity()
                };
                r.to_homogeneous()
            }
            ("scale", [a, b, z]) => Mat4::new_nonuniform_scaling(&Vec3::new(*a, *b, *z)),
            (tag, _) => return Err(err(format!("<{tag}> has the wrong number of values"))),
        };
        t *= m;
    }
    Ok(t)
}

fn append(out: &mut TriMesh, g: &TriMesh, t: &Mat4) {
    let offset = out.vertices.len();
    out.vertices.extend(
        g.vertices
            .iter()
            .map(|v| t.transform_point(&(*v).into()).coords),
    );
    out.triangles
        .extend(g.triangles.iter().map(|tri| tri.map(|i| i + offset)));
}

/// The positions of a `<source>` (through its accessor's stride) as 3-vectors.
fn positions(source: Node) -> Result<Vec<Vec3>, MeshFileError> {
    let array =
        child(source, "float_array").ok_or_else(|| err("<source> without <float_array>"))?;
    let x = numbers(array)?;
    let accessor = descend(source, &["technique_common", "accessor"]);
    let stride = accessor
        .and_then(|a| a.attribute("stride"))
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(3)
        .max(3);
    Ok(x.chunks_exact(stride)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect())
}

/// One `<mesh>`: its triangles, indexing the positions of its `<vertices>`.
fn read_mesh(mesh: Node, by_id: &HashMap<&str, Node>) -> Result<TriMesh, MeshFileError> {
    let resolve = |url: &str| by_id.get(url.trim_start_matches('#')).copied();
    let vertices_node = child(mesh, "vertices").ok_or_else(|| err("<mesh> without <vertices>"))?;
    let pos_source = vertices_node
        .children()
        .find(|i| i.has_tag_name("input") && i.attribute("semantic") == Some("POSITION"))
        .and_then(|i| i.attribute("source"))
        .and_then(resolve)
        .ok_or_else(|| err("<vertices> without a POSITION source"))?;
    let vertices = positions(pos_source)?;
    let n = vertices.len();
    let mut triangles = Vec::new();
    for prim in mesh.children().filter(|c| c.is_element()) {
        let tag = prim.tag_name().name();
        if !matches!(tag, "triangles" | "polylist" | "polygons") {
            continue;
        }
        let inputs: Vec<Node> = prim
            .children()
            .filter(|c| c.has_tag_name("input"))
            .collect();
        let max_offset = inputs
            .iter()
            .filter_map(|i| i.attribute("offset").and_then(|o| o.parse::<usize>().ok()))
            .max()
            .unwrap_or(0);
        if max_offset > 64 {
            return Err(err(format!(
                "<{tag}> input offset {max_offset} is too large"
            )));
        }
        let stride = max_offset + 1;
        let vertex_offset = inputs
            .iter()
            .find(|i| i.attribute("semantic") == Some("VERTEX"))
            .and_then(|i| i.attribute("offset"))
            .and_then(|o| o.parse::<usize>().ok())
            .unwrap_or(0);
        // One polygon's vertex indices, as a fan of triangles.
        let mut fan = |poly: &[usize]| -> Result<(), MeshFileError> {
            let idx: Vec<usize> = poly
                .chunks_exact(stride)
                .map(|c| c[vertex_offset])
                .collect();
            if let Some(&bad) = idx.iter().find(|&&i| i >= n) {
                return Err(err(format!(
                    "<{tag}> index {bad} out of range ({n} vertices)"
                )));
            }
            for k in 1..idx.len().saturating_sub(1) {
                triangles.push([idx[0], idx[k], idx[k + 1]]);
            }
            Ok(())
        };
        match tag {
            "triangles" => {
                for p in prim.children().filter(|c| c.has_tag_name("p")) {
                    for tri in indices(p)?.chunks_exact(3 * stride) {
                        fan(tri)?;
                    }
                }
            }
            "polylist" => {
                let counts = child(prim, "vcount").map(indices).transpose()?;
                let p = child(prim, "p")
                    .map(indices)
                    .transpose()?
                    .unwrap_or_default();
                let mut at = 0;
                for c in counts.unwrap_or_default() {
                    let end = c
                        .checked_mul(stride)
                        .and_then(|n| n.checked_add(at))
                        .unwrap_or(usize::MAX);
                    let poly = p
                        .get(at..end)
                        .ok_or_else(|| err("<polylist> <p> shorter than <vcount> says"))?;
                    fan(poly)?;
                    at = end;
                }
            }
            _ => {
                for p in prim.children().filter(|c| c.has_tag_name("p")) {
                    fan(&indices(p)?)?;
                }
            }
        }
    }
    Ok(TriMesh::new(vertices, triangles))
}
