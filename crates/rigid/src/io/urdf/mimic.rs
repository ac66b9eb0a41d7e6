//! URDF `<mimic>` joints as couplings ([`MimicModel`]), Pinocchio's
//! `buildModelFromUrdf(path, mimic=True)`: each mimic joint follows its source with no
//! coordinate of its own. A source may come later in the tree than its mimic (TALOS and Romeo
//! do this, and Pinocchio 4.1 refuses them: "The parent joint of the mimic joint is not in the
//! kinematic tree"); a chain of mimics is composed. A mimic of a joint the file does not define
//! is a warning of the parser, and the joint stays independent.

use super::{build_model_with, parse_urdf_file, UrdfError, UrdfOptions, UrdfRobot, UrdfWarning};
use crate::multibody::{Mimic, MimicError, MimicModel, Model};
use std::path::Path;

/// The couplings of `robot`'s `<mimic>` elements in `model` (built from `robot`), in the file's
/// order.
///
/// # Errors
/// [`UrdfError::Invalid`] naming the mimic joint and its line: a mimic or mimicked joint that is
/// not a moving joint of the model (a `fixed` joint, welded at import).
pub fn mimics(robot: &UrdfRobot, model: &Model) -> Result<Vec<Mimic>, UrdfError> {
    let mut out = Vec::new();
    for j in &robot.joints {
        let Some(m) = &j.mimic else { continue };
        let invalid = |message: String| UrdfError::Invalid {
            line: j.line,
            element: format!("joint \"{}\"", j.name),
            message,
        };
        let id = |name: &str| {
            model.joint_id(name).ok_or_else(|| {
                invalid(format!(
                    "mimic: joint \"{name}\" is fixed; a mimic joint and the joint it follows \
                     must move"
                ))
            })
        };
        out.push(Mimic::new(
            id(&j.name)?,
            id(&m.joint)?,
            m.multiplier,
            m.offset,
        ));
    }
    Ok(out)
}

/// Reads a URDF file and builds its model with the `<mimic>` joints as couplings; returns it
/// with every warning of [`load_urdf_with`](super::load_urdf_with).
///
/// ```
/// let dir = std::env::temp_dir().join("rigid_doc_mimic");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("gripper.urdf");
/// let link = |n: &str| format!(r#"<link name="{n}"><inertial><mass value="0.1"/>
///     <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>"#);
/// let finger = |n: &str, y: f64, mimic: &str| format!(r#"<joint name="{n}" type="prismatic">
///     <parent link="palm"/><child link="{n}_link"/><origin xyz="0 {y} 0"/><axis xyz="0 1 0"/>
///     <limit lower="0" upper="0.04" effort="20" velocity="0.2"/>{mimic}</joint>"#);
/// std::fs::write(&path, format!(r#"<robot name="gripper">{}{}{}{}{}</robot>"#,
///     link("palm"), link("left_link"), link("right_link"),
///     finger("left", 0.01, ""), finger("right", -0.01, r#"<mimic joint="left" multiplier="-1"/>"#))).unwrap();
/// let (mm, _) = rigid::io::urdf::load_urdf_mimic(&path, &Default::default())?;
/// assert_eq!((mm.model().nq(), mm.nq()), (2, 1)); // one finger drives both
/// # Ok::<(), rigid::io::urdf::UrdfError>(())
/// ```
///
/// # Errors
/// As [`load_urdf_with`](super::load_urdf_with), and [`UrdfError::Invalid`] naming the mimic
/// joint and its line for a coupling rigid cannot hold ([`mimics`], [`MimicModel::new`]).
pub fn load_urdf_mimic(
    path: impl AsRef<Path>,
    opts: &UrdfOptions,
) -> Result<(MimicModel, Vec<UrdfWarning>), UrdfError> {
    let robot = parse_urdf_file(path)?;
    let (model, warnings) = build_model_with(&robot, opts)?;
    Ok((mimic_model(&robot, model)?, warnings))
}

/// `model` (built from `robot`) with the robot's `<mimic>` joints as couplings.
///
/// # Errors
/// [`UrdfError::Invalid`] naming the mimic joint and its line for a coupling rigid cannot hold
/// ([`mimics`], [`MimicModel::new`]).
pub fn mimic_model(robot: &UrdfRobot, model: Model) -> Result<MimicModel, UrdfError> {
    let couplings = mimics(robot, &model)?;
    MimicModel::new(model, &couplings).map_err(|e| {
        // the mimic joint the error is about: named by it, or the joint it follows
        let mut with_mimic = robot.joints.iter().filter(|j| j.mimic.is_some());
        let j = match &e {
            MimicError::NotOneDof { joint, .. } | MimicError::NotFinite { joint } => with_mimic
                .find(|j| &j.name == joint || j.mimic.as_ref().is_some_and(|m| &m.joint == joint)),
            MimicError::OutOfRange { .. } | MimicError::Invalid(_) => {
                with_mimic.find(|j| e.to_string().contains(&format!("\"{}\"", j.name)))
            }
        };
        match j {
            Some(j) => UrdfError::Invalid {
                line: j.line,
                element: format!("joint \"{}\"", j.name),
                message: e.to_string(),
            },
            None => UrdfError::Model(e.to_string()),
        }
    })
}
