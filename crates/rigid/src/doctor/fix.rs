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

/// `text` (the MJCF file `report` was made from, [`examine_mjcf`](super::examine_mjcf)) with
/// each repaired body's `<inertial>` element replaced by `<inertial pos mass fullinertia>` from
/// its repair (the inertia about the centre of mass in the body frame, as `fullinertia` is), a
/// comment before it giving the cause and the original element; everything else is left byte for
/// byte. Returns the text and the notes: a repaired body that is not in this file (it comes from
/// an `<include>`), and a file whose `<compiler inertiafromgeom="true">` makes MuJoCo ignore
/// every `<inertial>`.
///
/// # Errors
/// The text is not XML.
pub fn fixed_mjcf(text: &str, report: &DoctorReport) -> Result<(String, Vec<String>), String> {
    use crate::io::shortest as num;
    use crate::io::urdf::indent_at;
    let nums = |xs: &[f64]| xs.iter().map(|x| num(*x)).collect::<Vec<_>>().join(" ");
    let doc = roxmltree::Document::parse(text).map_err(|e| e.to_string())?;
    let mut notes = Vec::new();
    let from_geoms = doc
        .descendants()
        .any(|n| n.has_tag_name("compiler") && n.attribute("inertiafromgeom") == Some("true"));
    if from_geoms {
        notes.push(
            "the file's <compiler inertiafromgeom=\"true\"> makes MuJoCo compute every body's \
             inertia from its geoms: the repaired <inertial> elements have no effect until it is \
             removed"
                .into(),
        );
    }
    // (byte range replaced, new text)
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for b in &report.bodies {
        let Some(r) = &b.repaired else { continue };
        let inertial = doc
            .descendants()
            .find(|n| n.has_tag_name("body") && n.attribute("name") == Some(b.name.as_str()))
            .and_then(|body| body.children().find(|c| c.has_tag_name("inertial")));
        let Some(inertial) = inertial else {
            notes.push(format!(
                "body \"{}\": its <inertial> is not in this file (an <include>d file): not \
                 repaired",
                b.name
            ));
            continue;
        };
        let range = inertial.range();
        let indent = indent_at(text, range.start);
        // `fullinertia` is in the body frame (MuJoCo allows no `quat` with it): rotate it there
        let rotation = crate::spatial::so3::from_rpy(r.rpy[0], r.rpy[1], r.rpy[2]);
        let e = r.inertia.rotated_by(&rotation).entries();
        let cause = b.likely_cause.map_or("unknown", |c| c.code());
        let element = format!(
            "<!-- rigid doctor: {cause}: {} -->\n{indent}<!-- was: {} -->\n{indent}<inertial \
             pos=\"{}\" mass=\"{}\" fullinertia=\"{}\"/>",
            b.explanation.replace("--", "- -"),
            text[range.clone()].replace("--", "- -"),
            nums(&[r.com.x, r.com.y, r.com.z]),
            num(r.mass),
            nums(&e)
        );
        edits.push((range, element));
    }
    Ok((splice(text, edits), notes))
}

/// `text` with each range of `edits` replaced by its new text (ranges of distinct elements,
/// which do not overlap; one that would overlap an earlier one is left out).
pub(super) fn splice(text: &str, mut edits: Vec<(std::ops::Range<usize>, String)>) -> String {
    edits.sort_by_key(|e| e.0.start);
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (range, new) in edits {
        if range.start < at {
            continue;
        }
        out.push_str(&text[at..range.start]);
        out.push_str(&new);
        at = range.end;
    }
    out.push_str(&text[at..]);
    out
}
