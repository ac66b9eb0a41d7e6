//! `rigid doctor --fix`: the URDF text with only the `<inertial>` blocks that needed a repair
//! replaced, each preceded by a comment saying what was done and why.

use super::{BodyReport, DoctorReport, InertialParams};
use crate::io::urdf::UrdfRobot;

/// `text` (the URDF that `robot` was parsed from) with each repaired body's `<inertial>` element
/// rewritten from its repair, and a comment before it giving the cause, what was changed and the
/// original numbers. Everything else is left byte for byte.
#[must_use]
pub fn fixed_urdf(text: &str, robot: &UrdfRobot, report: &DoctorReport) -> String {
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for b in &report.bodies {
        let (Some(r), Some(link)) = (&b.repaired, robot.link(&b.name)) else {
            continue;
        };
        let Some(i) = &link.inertial else { continue };
        let span = i.span.clone();
        if span.end > text.len() || !text.is_char_boundary(span.start) {
            continue;
        }
        let line_start = text[..span.start].rfind('\n').map_or(0, |k| k + 1);
        let indent: String = text[line_start..span.start]
            .chars()
            .take_while(|c| c.is_whitespace())
            .collect();
        let original = InertialParams::from_urdf(i);
        edits.push((span, block(b, r, &original, &indent)));
    }
    edits.sort_by_key(|(s, _)| s.start);
    let mut out = String::with_capacity(text.len() + 512 * edits.len());
    let mut at = 0;
    for (span, new) in edits {
        out.push_str(&text[at..span.start]);
        out.push_str(&new);
        at = span.end;
    }
    out.push_str(&text[at..]);
    out
}

fn triple(v: [f64; 3]) -> String {
    format!("{} {} {}", v[0], v[1], v[2])
}

/// `--` may not appear inside an XML comment.
fn comment_safe(s: &str) -> String {
    s.replace("--", "- -")
}

fn block(b: &BodyReport, r: &InertialParams, was: &InertialParams, indent: &str) -> String {
    let cause = b.likely_cause.map_or("unknown", |c| c.code());
    let e = r.entries();
    let w = was.entries();
    format!(
        "<!-- rigid doctor: {cause}: {} -->\n{indent}<!-- was: mass {} xyz {} rpy {} ixx {} iyy {} \
         izz {} ixy {} ixz {} iyz {} -->\n{indent}<inertial>\n{indent}  <origin xyz=\"{}\" \
         rpy=\"{}\"/>\n{indent}  <mass value=\"{}\"/>\n{indent}  <inertia ixx=\"{}\" ixy=\"{}\" \
         ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n{indent}</inertial>",
        comment_safe(&b.explanation),
        was.mass,
        triple([was.com.x, was.com.y, was.com.z]),
        triple(was.rpy),
        w[0],
        w[1],
        w[2],
        w[3],
        w[4],
        w[5],
        triple([r.com.x, r.com.y, r.com.z]),
        triple(r.rpy),
        r.mass,
        e[0],
        e[3],
        e[4],
        e[1],
        e[5],
        e[2],
    )
}
