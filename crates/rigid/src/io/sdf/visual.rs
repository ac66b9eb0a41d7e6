//! A link's `<visual>` elements: what `rigid convert` draws (`io::write::visuals::sdf_visuals`).

use super::parse::{child, children, Reader};
use super::{SdfError, SdfVisual};
use crate::io::write::VisualShape;
use roxmltree::Node;

impl Reader<'_> {
    /// The `<visual>`s of link `l`: each pose (relative to the link), shape (a primitive, or a
    /// mesh by its file), and colour (`<material>`'s `<diffuse>`, else `<ambient>`). Read as
    /// best it can: a visual that cannot be drawn (a mesh not found, an `<empty>`, plane or
    /// height map, a shape of zero size, a malformed pose) is skipped, a colour that is not 3 or
    /// 4 numbers left out, each with a warning; a visual never stops the model loading.
    pub(super) fn visuals(&mut self, l: Node, what: &str) -> Result<Vec<SdfVisual>, SdfError> {
        let mut out = Vec::new();
        for (k, v) in children(l, "visual").enumerate() {
            let name = v.attribute("name").map_or_else(
                || format!("{}/visual/{k}", l.attribute("name").unwrap_or("")),
                str::to_string,
            );
            let what = format!("{what} visual \"{name}\"");
            let pose = match self.pose(v, &what) {
                Ok(p) => p,
                Err(e) => {
                    self.warn(v, what, format!("{e}: the visual is skipped"));
                    continue;
                }
            };
            if pose.relative_to.is_some() {
                self.warn(
                    v,
                    what.clone(),
                    "a visual's pose relative_to another frame is read as relative to its link",
                );
            }
            let Some(g) = child(v, "geometry") else {
                continue;
            };
            let kind = g
                .children()
                .find(Node::is_element)
                .map(|s| s.tag_name().name());
            if !matches!(
                kind,
                Some("box" | "sphere" | "cylinder" | "capsule" | "ellipsoid" | "mesh")
            ) {
                let kind = kind.map_or("no geometry".to_string(), |k| format!("<{k}>"));
                self.warn(
                    g,
                    what,
                    format!("{kind} is not drawn: the visual is skipped"),
                );
                continue;
            }
            let shape = match child(g, "mesh") {
                Some(mesh) => match self.mesh_file(mesh, &what) {
                    Ok((Ok((_, file)), scale)) => VisualShape::Mesh {
                        file: std::fs::canonicalize(&file).unwrap_or(file),
                        scale,
                    },
                    Ok((Err(e), _)) => {
                        self.warn(mesh, what, format!("{e}: the visual is skipped"));
                        continue;
                    }
                    Err(e) => {
                        self.warn(mesh, what, format!("{e}: the visual is skipped"));
                        continue;
                    }
                },
                None => match self.shape(g, &what) {
                    Ok(Some(s)) => VisualShape::Primitive(s),
                    Ok(None) => continue,
                    Err(e) => {
                        self.warn(g, what, format!("{e}: the visual is skipped"));
                        continue;
                    }
                },
            };
            let colour = child(v, "material")
                .and_then(|m| child(m, "diffuse").or_else(|| child(m, "ambient")));
            let rgba = match colour {
                None => None,
                Some(c) => {
                    let n = self.numbers(c, &what, None).unwrap_or_default();
                    match n.as_slice() {
                        [r, g, b] => Some([*r, *g, *b, 1.0]),
                        [r, g, b, a] => Some([*r, *g, *b, *a]),
                        _ => {
                            self.warn(
                                c,
                                what,
                                "a colour of 3 or 4 numbers: the colour is left out",
                            );
                            None
                        }
                    }
                }
            };
            out.push(SdfVisual {
                name,
                pose: pose.t,
                shape,
                rgba,
            });
        }
        Ok(out)
    }
}
