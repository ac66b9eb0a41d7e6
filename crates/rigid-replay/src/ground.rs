//! The ground of a simulation with contact: a plane under the scene, markers at the contact
//! points moved frame by frame, and the contact forces recorded for the page's arrows.

use crate::shapes::shape;
use crate::{Node, Scene};
use rigid::collision::{CollisionModel, Shape as Solid};
use rigid::spatial::{Transform, Vec3};

/// How many contact points the page marks (and draws the force of) at most per frame.
pub const CONTACT_MARKERS: usize = 16;

/// The length of the arrow of a force equal to the weight, as a share of the scene's
/// [`extent`](Scene::extent).
pub const WEIGHT_ARROW: f64 = 0.5;

impl Scene {
    /// Adds the ground plane `z = height` (a grey slab centred under `center`, 2 mm thick, its
    /// top at the height) and [`CONTACT_MARKERS`] red markers, parked under the ground until
    /// [`set_contacts`](Self::set_contacts) places them, and sets
    /// [`force_scale`](Self::force_scale) so that a force equal to `weight` (N; taken as 1 N
    /// when not positive) is drawn [`WEIGHT_ARROW`] × `extent` long. Returns the index of the
    /// first marker node.
    pub fn add_ground(&mut self, height: f64, center: Vec3, weight: f64) -> usize {
        let weight = if weight > 0.0 { weight } else { 1.0 };
        self.force_scale = WEIGHT_ARROW * self.extent.max(0.1) / weight;
        let side = 4.0 * self.extent.max(0.5);
        let slab = Transform::from_translation(Vec3::new(center.x, center.y, height - 1e-3));
        self.nodes.push(Node {
            name: "ground".into(),
            parent: None,
            placement: slab,
            shapes: vec![shape(
                "box",
                [side, side, 2e-3],
                Transform::identity(),
                [0.78, 0.78, 0.75, 1.0],
            )],
        });
        let first = self.nodes.len();
        let radius = (0.01 * self.extent).clamp(0.004, 0.02);
        // parked just under the slab: hidden from above
        let parked =
            Transform::from_translation(Vec3::new(center.x, center.y, height - 3e-3 - radius));
        for i in 0..CONTACT_MARKERS {
            self.nodes.push(Node {
                name: format!("contact {i}"),
                parent: None,
                placement: parked,
                shapes: vec![shape(
                    "sphere",
                    [radius; 3],
                    Transform::identity(),
                    [0.85, 0.15, 0.1, 1.0],
                )],
            });
        }
        first
    }

    /// For the next recorded frame: puts the markers from node `first` (see
    /// [`add_ground`](Self::add_ground)) at the points of `contacts` (point in the world, m;
    /// force on the body, N, world axes; the first [`CONTACT_MARKERS`]), the others back under
    /// the ground, and keeps the contacts as [`contact_forces`](Self::contact_forces).
    pub fn set_contacts(&mut self, first: usize, contacts: &[(Vec3, Vec3)], height: f64) {
        let ground = self.nodes[first - 1].placement.translation;
        let radius = self.nodes[first].shapes[0].size[0];
        let parked = Vec3::new(ground.x, ground.y, height - 3e-3 - radius);
        for i in 0..CONTACT_MARKERS {
            let at = contacts.get(i).map_or(parked, |c| c.0);
            self.nodes[first + i].placement = Transform::from_translation(at);
        }
        self.contact_forces = contacts.iter().take(CONTACT_MARKERS).copied().collect();
    }

    /// The page's statement of the arrows' scale (`None` without force arrows): millimetres per
    /// newton, and the length of the weight's arrow.
    #[must_use]
    pub fn force_note(&self) -> Option<String> {
        (self.force_scale > 0.0).then(|| {
            let weight = WEIGHT_ARROW * self.extent.max(0.1) / self.force_scale;
            format!(
                "green arrows: contact forces on the body, {:.4} mm per N (the weight, {weight:.4} N, would be {:.4} m)",
                1e3 * self.force_scale,
                WEIGHT_ARROW * self.extent.max(0.1)
            )
        })
    }
}

/// The nodes that draw a collision model's geometries on their bodies (a body spec on the
/// ground, which has no visual of its own), and a warning for each shape drawn approximately:
/// an ellipsoid as its bounding box, a cone as a cylinder, a convex hull as its bounding box.
#[must_use]
pub fn collision_nodes(cm: &CollisionModel) -> (Vec<Node>, Vec<String>) {
    let color = [0.3, 0.5, 0.85, 1.0];
    let mut warnings = Vec::new();
    let nodes = cm
        .geometries
        .iter()
        .map(|g| {
            let (kind, size, origin) = match &g.shape {
                Solid::Sphere { radius } => ("sphere", [*radius; 3], Transform::identity()),
                Solid::Box { size } => ("box", [size.x, size.y, size.z], Transform::identity()),
                Solid::Cylinder { radius, length } => {
                    ("cylinder", [*radius, *length, 0.0], Transform::identity())
                }
                Solid::Capsule { radius, length } => {
                    ("capsule", [*radius, *length, 0.0], Transform::identity())
                }
                Solid::Cone { radius, height } => {
                    warnings.push(format!("{}: a cone, drawn as a cylinder", g.name));
                    // the cone's base at z = −h/4, apex at 3h/4: the cylinder spans the same
                    let mid = Transform::from_translation(Vec3::new(0.0, 0.0, 0.25 * height));
                    ("cylinder", [*radius, *height, 0.0], mid)
                }
                Solid::Ellipsoid { semi_axes } => {
                    warnings.push(format!(
                        "{}: an ellipsoid, drawn as its bounding box",
                        g.name
                    ));
                    let s = semi_axes * 2.0;
                    ("box", [s.x, s.y, s.z], Transform::identity())
                }
                Solid::ConvexHull { points } => {
                    warnings.push(format!(
                        "{}: a convex hull, drawn as its bounding box",
                        g.name
                    ));
                    let (lo, hi) = points.iter().fold(
                        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
                        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
                    );
                    let s = hi - lo;
                    let mid = Transform::from_translation((hi + lo) * 0.5);
                    ("box", [s.x, s.y, s.z], mid)
                }
            };
            Node {
                name: g.name.clone(),
                parent: g.body,
                placement: g.placement,
                shapes: vec![shape(kind, size, origin, color)],
            }
        })
        .collect();
    (nodes, warnings)
}
