//! The doctor on an MJCF model: each body's `<inertial>` checked as a URDF link's is, against
//! the body's geoms (its collision geoms, those with a `contype` or `conaffinity`, make the solid;
//! the geoms of groups 0 to 2 are its visual shapes). MuJoCo ignores geoms for the inertia of a
//! body with an `<inertial>` (unless `inertiafromgeom="true"`), so a wrong `<inertial>` is the
//! body's inertia however its geoms look: the doctor compares the two.
//!
//! Ellipsoids, height fields and MSH meshes have no URDF counterpart: they are left out of the
//! geometry (a note). A mesh with a non-uniform `scale` and a `refquat` is left out too (its
//! placement is not a rigid transform followed by a scale).

use super::{Doctor, DoctorReport};
use crate::io::mjcf::{MjcfGeom, MjcfModel, MjcfShape};
use crate::io::urdf::{UrdfGeometry, UrdfInertial, UrdfLink, UrdfRobot, UrdfShape};
use crate::spatial::Transform;

/// The doctor's report on every body of `m` that has an `<inertial>`.
///
/// ```
/// use rigid::io::mjcf::load_mjcf_str;
/// // a 0.2 m box of 1 kg with 7.5 times the inertia it can hold
/// let m = load_mjcf_str(r#"<mujoco><worldbody><body name="b"><joint/>
///   <inertial pos="0 0 0" mass="1" diaginertia="0.05 0.05 0.05"/>
///   <geom type="box" size="0.1 0.1 0.1"/></body></worldbody></mujoco>"#,
///   std::path::Path::new(".")).unwrap();
/// let report = rigid::doctor::examine_mjcf(&m);
/// assert_eq!(report.bodies[0].name, "b");
/// assert_ne!(report.bodies[0].status, rigid::doctor::Status::Ok);
/// ```
#[must_use]
pub fn examine_mjcf(m: &MjcfModel) -> DoctorReport {
    let robot = as_robot(m);
    Doctor::new().examine(&robot)
}

/// The bodies of `m` as URDF links (the world and every body, joints left out: the doctor checks
/// one body at a time).
#[must_use]
pub fn as_robot(m: &MjcfModel) -> UrdfRobot {
    let mut links = Vec::with_capacity(m.bodies.len());
    for (k, b) in m.bodies.iter().enumerate() {
        let geoms: Vec<&MjcfGeom> = m.geoms.iter().filter(|g| g.body == k).collect();
        let to_body = b.placement.inverse();
        let shapes = |keep: &dyn Fn(&MjcfGeom) -> bool| -> Vec<UrdfGeometry> {
            geoms
                .iter()
                .filter(|g| keep(g))
                .filter_map(|g| urdf_geometry(g, &to_body))
                .collect()
        };
        let inertial = b.given.as_ref().map(|i| UrdfInertial {
            origin: i.frame,
            // the axes the inertia is written in (`quat`, `axisangle`, ..., or `fullinertia`'s)
            rpy: {
                let (r, p, y) = crate::spatial::so3::to_rpy(&i.frame.rotation);
                [r, p, y]
            },
            mass: i.mass,
            inertia: i.inertia,
            line: i.line,
            text: i.text.clone(),
            span: 0..0,
        });
        links.push(UrdfLink {
            name: b.name.clone(),
            line: b.line,
            span: 0..0,
            inertial,
            visuals: shapes(&|g| (0..3).contains(&g.group)),
            collisions: shapes(&|g| g.contype != 0 || g.conaffinity != 0),
        });
    }
    UrdfRobot {
        name: m.model.name().to_string(),
        path: m.path.clone(),
        children: vec![Vec::new(); links.len()],
        links,
        joints: Vec::new(),
        root: 0,
        warnings: Vec::new(),
    }
}

/// A geom as a URDF shape in its body's frame (`None` for the shapes URDF has not).
fn urdf_geometry(g: &MjcfGeom, to_body: &Transform) -> Option<UrdfGeometry> {
    let mut origin = *to_body * g.placement;
    let shape = match &g.shape {
        MjcfShape::Sphere { radius } => UrdfShape::Sphere { radius: *radius },
        MjcfShape::Box { half } => UrdfShape::Box { size: half * 2.0 },
        MjcfShape::Cylinder {
            radius,
            half_length,
        } => UrdfShape::Cylinder {
            radius: *radius,
            length: 2.0 * half_length,
        },
        MjcfShape::Capsule {
            radius,
            half_length,
        } => UrdfShape::Capsule {
            radius: *radius,
            length: 2.0 * half_length,
        },
        MjcfShape::Mesh { file, scale, .. } => {
            // none for a mesh given by its vertices (no file for a URDF to name), or turned and
            // scaled unevenly
            origin = origin * g.shape.mesh_file_frame()?;
            UrdfShape::Mesh {
                filename: file.display().to_string(),
                scale: *scale,
            }
        }
        MjcfShape::Plane { .. } | MjcfShape::Ellipsoid { .. } | MjcfShape::Hfield { .. } => {
            return None
        }
    };
    Some(UrdfGeometry {
        origin,
        shape,
        rgba: Some(g.rgba),
        line: g.line,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_inertial_that_fits_its_geoms_is_ok() {
        let m = crate::io::mjcf::load_mjcf_str(
            r#"<mujoco><worldbody><body name="b"><joint/>
               <inertial pos="0 0 0" mass="1" diaginertia="0.00666667 0.00666667 0.00666667"/>
               <geom type="box" size="0.1 0.1 0.1"/></body></worldbody></mujoco>"#,
            std::path::Path::new("."),
        )
        .unwrap();
        let r = examine_mjcf(&m);
        assert_eq!(r.bodies.len(), 1);
        assert_eq!(
            r.bodies[0].status,
            super::super::Status::Ok,
            "{:?}",
            r.bodies[0]
        );
    }

    #[test]
    fn geoms_are_placed_in_their_body_frame() {
        let m = crate::io::mjcf::load_mjcf_str(
            r#"<mujoco><worldbody><body><joint pos="0.5 0 0"/>
               <geom type="box" size="0.1 0.2 0.3" pos="1 0 0"/></body></worldbody></mujoco>"#,
            std::path::Path::new("."),
        )
        .unwrap();
        let robot = as_robot(&m);
        let g = &robot.links[1].collisions[0];
        assert!((g.origin.translation - crate::spatial::Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
    }
}
