//! `rigid doctor`: what is wrong with a URDF's inertial data, the likely cause, and a repair.

use super::UrdfRobot;
use crate::mass::{nearest_consistent, SpatialInertia};

/// The repair of link `link` (index in `robot.links`) used by the `repair` inertia policy: its
/// inertia in the link frame and a sentence saying what was done.
#[must_use]
pub fn repair_link(robot: &UrdfRobot, link: usize) -> Option<(SpatialInertia, String)> {
    let g = robot.link_inertia(link);
    nearest_consistent(&g, None).map(|r| {
        (
            r,
            "nearest physically consistent inertia (mass and CoM kept)".to_string(),
        )
    })
}
