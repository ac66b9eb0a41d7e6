//! The 3D replay of `rigid simulate --html`, `rigid view` and Python's `rigid.replay_html`: one
//! self-contained HTML file (WebGL, our own ~400-line renderer in `assets/`, embedded with
//! `include_str!`; nothing is fetched when the page is viewed, a
//! strict Content-Security-Policy forbids it). The scene is a list of nodes, each fixed in a
//! body frame and carrying shapes (URDF or MJCF boxes, cylinders, spheres, capsules and meshes, or a
//! stick figure when a model has no geometry), and the world pose of every node at 60 frames per
//! second, with the centre of mass for the trail.
//!
//! Why our own renderer rather than three.js: the page needs flat-shaded triangles, lines, an
//! orbit camera and a slider; that is ~400 lines of plain WebGL 1, reviewed here, against
//! ~600 kB of a vendored bundle (and a JavaScript build step) for the same picture.

#![warn(missing_docs)]

mod ground;
mod mjcf;
mod shapes;

pub use ground::{collision_nodes, CONTACT_MARKERS, WEIGHT_ARROW};
pub use shapes::{body_box, robot_nodes, robot_nodes_of_urdf};

use base64::Engine;
use rigid::multibody::{Data, JointId, Model};
use rigid::spatial::{so3, Transform, Vec3};

/// Frames per second of the recorded trajectory.
pub const FPS: f64 = 60.0;

/// One drawable shape in its node's frame.
#[derive(Clone, Debug)]
pub struct Shape {
    /// `box` (size = edges), `cylinder` (radius, length; axis z), `sphere` (radius), `capsule`
    /// (radius, cylinder length; axis z), `mesh`.
    pub kind: &'static str,
    /// Dimensions (see `kind`).
    pub size: [f64; 3],
    /// Index into [`Scene::meshes`] for a mesh.
    pub mesh: Option<usize>,
    /// Mesh scale.
    pub scale: [f64; 3],
    /// The shape's frame in the node's frame.
    pub origin: Transform,
    /// Colour, RGBA in [0, 1].
    pub color: [f64; 4],
}

/// Something drawn: shapes fixed in a body (or the world) at `placement`.
#[derive(Clone, Debug)]
pub struct Node {
    /// A name (the link).
    pub name: String,
    /// The body it is fixed in (`None`: the world).
    pub parent: Option<JointId>,
    /// Its pose in that body's frame.
    pub placement: Transform,
    /// Its shapes.
    pub shapes: Vec<Shape>,
}

/// A triangle mesh for the page (positions in the mesh file's units, before `scale`).
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// `x, y, z` per vertex.
    pub positions: Vec<f32>,
    /// Three vertex indices per triangle.
    pub indices: Vec<u32>,
}

/// What the page shows.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// Heading.
    pub title: String,
    /// Lines under the heading (model, integrator, ...).
    pub info: String,
    /// What could not be drawn as asked, and how it was drawn instead.
    pub warnings: Vec<String>,
    /// The nodes.
    pub nodes: Vec<Node>,
    /// Meshes referenced by the shapes.
    pub meshes: Vec<Mesh>,
    /// A size (m) for the camera margin.
    pub extent: f64,
    /// Metres of arrow per newton of contact force (0: no force arrows; set by
    /// [`add_ground`](Self::add_ground)).
    pub force_scale: f64,
    /// The pushing contacts of the frame to be recorded next: the point (m) and the force on the
    /// body (N, world axes), at most [`CONTACT_MARKERS`] (set by
    /// [`set_contacts`](Self::set_contacts)).
    pub contact_forces: Vec<(Vec3, Vec3)>,
}

/// The recorded trajectory: times, the pose of every node at each frame, the CoM, and with a
/// ground the contact forces ([`CONTACT_MARKERS`] slots of point and force per frame).
#[derive(Clone, Debug, Default)]
pub struct Recording {
    times: Vec<f32>,
    poses: Vec<f32>,
    com: Vec<f32>,
    forces: Vec<f32>,
    next: f64,
}

impl Recording {
    /// Whether a frame is due at time `t` (frames every `1/FPS` s; the first at 0).
    #[must_use]
    pub fn due(&self, t: f64) -> bool {
        t + 1e-9 >= self.next
    }

    /// Append a frame at `t` with the world pose of each node and the CoM.
    pub fn push(&mut self, t: f64, poses: impl IntoIterator<Item = Transform>, com: Vec3) {
        self.times.push(t as f32);
        for p in poses {
            let [qx, qy, qz, qw] = so3::to_quaternion(&p.rotation);
            let x = p.translation;
            self.poses
                .extend([x.x, x.y, x.z, qx, qy, qz, qw].map(|v| v as f32));
        }
        self.com.extend([com.x, com.y, com.z].map(|v| v as f32));
        self.next = (self.times.len() as f64) / FPS;
    }

    /// Append the frame of configuration `q` at `t` if one is due: the nodes' poses from
    /// forward kinematics of `model` (placements in `data`), the CoM, and when the scene draws
    /// force arrows (`force_scale > 0`) its [`contact_forces`](Scene::contact_forces).
    ///
    /// # Errors
    /// A bad `q`.
    pub fn record_model(
        &mut self,
        scene: &Scene,
        model: &Model,
        data: &mut Data,
        t: f64,
        q: &[f64],
        force: bool,
    ) -> Result<(), String> {
        if !(force || self.due(t)) {
            return Ok(());
        }
        let com = rigid::multibody::center_of_mass(model, data, q).map_err(|e| e.to_string())?;
        let poses = scene.nodes.iter().map(|n| match n.parent {
            Some(j) => data.placements[j.0] * n.placement,
            None => n.placement,
        });
        let poses: Vec<Transform> = poses.collect();
        self.push(t, poses, com);
        if scene.force_scale > 0.0 {
            let none = (Vec3::zeros(), Vec3::zeros());
            for k in 0..CONTACT_MARKERS {
                let (p, f) = scene.contact_forces.get(k).copied().unwrap_or(none);
                self.forces
                    .extend([p.x, p.y, p.z, f.x, f.y, f.z].map(|v| v as f32));
            }
        }
        Ok(())
    }
}

fn b64(bytes: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

fn f32_bytes(x: &[f32]) -> Vec<u8> {
    x.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn mat4(t: &Transform) -> [f64; 16] {
    let (r, p) = (&t.rotation, &t.translation);
    [
        r[(0, 0)],
        r[(1, 0)],
        r[(2, 0)],
        0.0,
        r[(0, 1)],
        r[(1, 1)],
        r[(2, 1)],
        0.0,
        r[(0, 2)],
        r[(1, 2)],
        r[(2, 2)],
        0.0,
        p.x,
        p.y,
        p.z,
        1.0,
    ]
}

fn escape_html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const HTML: &str = include_str!("../assets/replay.html");
const CSS: &str = include_str!("../assets/replay.css");
const JS: &str = include_str!("../assets/replay.js");

impl Scene {
    /// The page: the template with the style, the renderer and the scene JSON inlined.
    #[must_use]
    pub fn html(&self, rec: &Recording) -> String {
        let nodes: Vec<serde_json::Value> = self
            .nodes
            .iter()
            .map(|n| {
                serde_json::json!({
                    "name": n.name,
                    "shapes": n.shapes.iter().map(|s| serde_json::json!({
                        "kind": s.kind,
                        "size": s.size,
                        "mesh": s.mesh,
                        "scale": s.scale,
                        "origin": mat4(&s.origin),
                        "color": s.color,
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        let meshes: Vec<serde_json::Value> = self
            .meshes
            .iter()
            .map(|m| {
                let idx: Vec<u8> = m.indices.iter().flat_map(|v| v.to_le_bytes()).collect();
                serde_json::json!({"positions": b64(&f32_bytes(&m.positions)), "indices": b64(&idx)})
            })
            .collect();
        let info = match self.force_note() {
            Some(note) if self.info.is_empty() => note,
            Some(note) => format!("{}\n{note}", self.info),
            None => self.info.clone(),
        };
        let json = serde_json::json!({
            "title": self.title,
            "info": info,
            "warnings": self.warnings,
            "nodes": nodes,
            "meshes": meshes,
            "extent": self.extent,
            "times": b64(&f32_bytes(&rec.times)),
            "poses": b64(&f32_bytes(&rec.poses)),
            "com": b64(&f32_bytes(&rec.com)),
            "forces": b64(&f32_bytes(&rec.forces)),
            "force_scale": self.force_scale,
            "force_slots": CONTACT_MARKERS,
        });
        // inside <script>, "</" would end the element
        let json = json.to_string().replace("</", "<\\/");
        HTML.replace("{{TITLE}}", &escape_html(&self.title))
            .replace("{{CSS}}", CSS)
            .replace("{{JS}}", JS)
            .replace("{{SCENE}}", &json)
    }
}
