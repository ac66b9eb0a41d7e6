//! `rigid doctor --fix`: the URDF text with only the `<inertial>` blocks that needed a repair
//! replaced, each preceded by a comment saying what was done and why.

use super::{DoctorReport, InertialParams};
use crate::io::urdf::{edit_inertials, was_comment, InertialEdit, UrdfRobot};

/// `text` (the URDF that `robot` was parsed from) with each repaired body's `<inertial>` element
/// rewritten from its repair, and a comment before it giving the cause, what was changed and the
/// original numbers. Everything else is left byte for byte.
#[must_use]
pub fn fixed_urdf(text: &str, robot: &UrdfRobot, report: &DoctorReport) -> String {
    let mut edits = Vec::new();
    for b in &report.bodies {
        let (Some(r), Some(link)) = (&b.repaired, robot.link(&b.name)) else {
            continue;
        };
        let Some(i) = &link.inertial else { continue };
        let cause = b.likely_cause.map_or("unknown", |c| c.code());
        edits.push(InertialEdit {
            link: b.name.clone(),
            params: r.clone(),
            comments: vec![
                format!("rigid doctor: {cause}: {}", b.explanation),
                was_comment(&InertialParams::from_urdf(i)),
            ],
        });
    }
    edit_inertials(text, robot, &edits)
}
