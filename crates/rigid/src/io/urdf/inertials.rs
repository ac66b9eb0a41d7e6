//! Rewriting the `<inertial>` blocks of a URDF text, everything else left byte for byte: the
//! doctor's repairs (`rigid doctor --fix`) and identified body inertias (`rigid identify --out`).

use super::{UrdfJointKind, UrdfRobot, ROOT_JOINT_NAME};
use crate::doctor::InertialParams;
use crate::mass::{RotationalInertia, SpatialInertia};
use crate::multibody::Model;
use crate::spatial::Vec3;

/// A new `<inertial>` for one link, with the comments written before it.
#[derive(Clone, Debug, PartialEq)]
pub struct InertialEdit {
    /// The link.
    pub link: String,
    /// Its new inertial parameters.
    pub params: InertialParams,
    /// One XML comment each, before the block (`--` is made safe).
    pub comments: Vec<String>,
}

fn triple(v: [f64; 3]) -> String {
    format!("{} {} {}", v[0], v[1], v[2])
}

/// `--` may not appear inside an XML comment.
fn comment_safe(s: &str) -> String {
    s.replace("--", "- -")
}

fn block(e: &InertialEdit, indent: &str) -> String {
    let r = &e.params;
    let i = r.inertia.matrix();
    let mut out = String::new();
    for c in &e.comments {
        out += &format!("<!-- {} -->\n{indent}", comment_safe(c));
    }
    out += &format!(
        "<inertial>\n{indent}  <origin xyz=\"{}\" rpy=\"{}\"/>\n{indent}  <mass value=\"{}\"/>\n\
         {indent}  <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n\
         {indent}</inertial>",
        triple([r.com.x, r.com.y, r.com.z]),
        triple(r.rpy),
        r.mass,
        i[(0, 0)],
        i[(0, 1)],
        i[(0, 2)],
        i[(1, 1)],
        i[(1, 2)],
        i[(2, 2)],
    );
    out
}

/// `was: mass … xyz … rpy … ixx … iyy … izz … ixy … ixz … iyz …`: the numbers an edit replaces.
#[must_use]
pub fn was_comment(w: &InertialParams) -> String {
    let e = w.entries();
    format!(
        "was: mass {} xyz {} rpy {} ixx {} iyy {} izz {} ixy {} ixz {} iyz {}",
        w.mass,
        triple([w.com.x, w.com.y, w.com.z]),
        triple(w.rpy),
        e[0],
        e[1],
        e[2],
        e[3],
        e[4],
        e[5]
    )
}

/// The whitespace before byte `at` on its line.
pub(crate) fn indent_at(text: &str, at: usize) -> String {
    let line_start = text[..at].rfind('\n').map_or(0, |k| k + 1);
    text[line_start..at]
        .chars()
        .take_while(|c| c.is_whitespace())
        .collect()
}

/// `text` (the URDF that `robot` was parsed from) with the `<inertial>` of each edited link
/// replaced by the edit's, preceded by its comments; a link without `<inertial>` gets one as
/// its first child (a self-closing `<link …/>` is opened). Edits of unknown links are skipped.
///
/// ```
/// use rigid::io::urdf::{edit_inertials, parse_urdf_str, InertialEdit};
/// use rigid::doctor::InertialParams;
/// use rigid::mass::RotationalInertia;
/// use rigid::spatial::Vec3;
/// let text = "<robot name=\"r\">\n  <link name=\"a\"/>\n</robot>\n";
/// let robot = parse_urdf_str(text).unwrap();
/// let params = InertialParams { mass: 2.0, com: Vec3::z(), rpy: [0.0; 3], inertia: RotationalInertia::diagonal(1.0, 1.0, 1.0) };
/// let out = edit_inertials(text, &robot, &[InertialEdit { link: "a".into(), params, comments: vec!["new".into()] }]);
/// let again = parse_urdf_str(&out).unwrap();
/// assert_eq!(again.links[0].inertial.as_ref().unwrap().mass, 2.0);
/// assert!(out.contains("<!-- new -->"));
/// ```
#[must_use]
pub fn edit_inertials(text: &str, robot: &UrdfRobot, edits: &[InertialEdit]) -> String {
    let mut spans: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for e in edits {
        let Some(link) = robot.link(&e.link) else {
            continue;
        };
        if let Some(i) = &link.inertial {
            let span = i.span.clone();
            if span.end > text.len() || !text.is_char_boundary(span.start) {
                continue;
            }
            spans.push((span.clone(), block(e, &indent_at(text, span.start))));
            continue;
        }
        let span = link.span.clone();
        if span.end > text.len() || !text.is_char_boundary(span.start) {
            continue;
        }
        let indent = indent_at(text, span.start);
        let element = &text[span.clone()];
        let inner = format!("\n{indent}  {}", block(e, &format!("{indent}  ")));
        if let Some(open) = element.strip_suffix("/>") {
            let new = format!("{}>{inner}\n{indent}</link>", open.trim_end());
            spans.push((span, new));
        } else if let Some(k) = element.find('>') {
            let at = span.start + k + 1;
            spans.push((at..at, inner));
        }
    }
    spans.sort_by_key(|(s, _)| s.start);
    let mut out = String::with_capacity(text.len() + 512 * spans.len());
    let mut at = 0;
    for (span, new) in spans {
        if span.start < at {
            continue; // two edits of one link: the first wins
        }
        out.push_str(&text[at..span.start]);
        out.push_str(&new);
        at = span.end;
    }
    out.push_str(&text[at..]);
    out
}

/// The links of each moving body of `model` (built from `robot`): its main link (the child of
/// its joint, or the root link for the free-flyer [`ROOT_JOINT_NAME`]) and the links welded to
/// it by fixed joints; `None` for a joint the URDF does not have.
fn body_links(robot: &UrdfRobot, model: &Model) -> Vec<Option<(usize, Vec<usize>)>> {
    model
        .joints()
        .iter()
        .map(|j| {
            let main = if j.name == ROOT_JOINT_NAME && j.parent.is_none() {
                robot.root
            } else {
                robot
                    .joint(&j.name)
                    .filter(|u| u.kind != UrdfJointKind::Fixed)?
                    .child
            };
            let mut welded = Vec::new();
            let mut stack = vec![main];
            while let Some(l) = stack.pop() {
                for &c in &robot.children[l] {
                    let u = &robot.joints[c];
                    if u.kind == UrdfJointKind::Fixed {
                        welded.push(u.child);
                        stack.push(u.child);
                    }
                }
            }
            Some((main, welded))
        })
        .collect()
}

/// `text` with the body inertias `inertias` (one per moving body of `model`, in its joint frame,
/// as [`Model::inertias`]) written back: a body's inertia is the composite of its main link and
/// the links welded to it by fixed joints, so it goes into the **main link's** `<inertial>` (mass,
/// CoM as the origin, the inertia about the CoM in the link's axes), and each welded link's
/// `<inertial>` is zeroed, with a comment naming where its mass went. `note` starts each comment
/// (`rigid identify: physically consistent estimate`). Links of bodies whose inertia is
/// unchanged (to round-off) are left alone.
///
/// # Errors
/// `inertias` of the wrong length.
pub fn with_body_inertials(
    text: &str,
    robot: &UrdfRobot,
    model: &Model,
    inertias: &[SpatialInertia],
    note: &str,
) -> Result<String, String> {
    if inertias.len() != model.njoints() {
        return Err(format!(
            "{} inertias for {} bodies",
            inertias.len(),
            model.njoints()
        ));
    }
    let mut edits = Vec::new();
    for ((links, g), old) in body_links(robot, model)
        .iter()
        .zip(inertias)
        .zip(model.inertias())
    {
        let Some((main, welded)) = links else {
            continue;
        };
        let scale = old.matrix().norm().max(g.matrix().norm());
        if (g.matrix() - old.matrix()).norm() <= 1e-14 * scale {
            continue;
        }
        let m = g.mass();
        let com = if m != 0.0 { g.com() } else { Vec3::zeros() };
        let names: Vec<&str> = welded
            .iter()
            .map(|&l| robot.links[l].name.as_str())
            .collect();
        let mut comments = vec![format!(
            "{note}: body of joint \"{}\"{}",
            robot
                .joints
                .iter()
                .find(|u| u.child == *main)
                .map_or(ROOT_JOINT_NAME, |u| u.name.as_str()),
            if names.is_empty() {
                String::new()
            } else {
                format!(
                    ", the composite of this link and the links welded to it ({})",
                    names.join(", ")
                )
            }
        )];
        if let Some(i) = &robot.links[*main].inertial {
            comments.push(was_comment(&InertialParams::from_urdf(i)));
        }
        edits.push(InertialEdit {
            link: robot.links[*main].name.clone(),
            params: InertialParams {
                mass: m,
                com,
                rpy: [0.0; 3],
                inertia: if m != 0.0 {
                    g.inertia_com()
                } else {
                    g.inertia_origin()
                },
            },
            comments,
        });
        for &l in welded {
            if robot.links[l].inertial.is_some() {
                edits.push(InertialEdit {
                    link: robot.links[l].name.clone(),
                    params: InertialParams {
                        mass: 0.0,
                        com: Vec3::zeros(),
                        rpy: [0.0; 3],
                        inertia: RotationalInertia::zero(),
                    },
                    comments: vec![format!(
                        "{note}: zeroed; this link is welded to \"{}\", whose <inertial> holds \
                         the identified composite",
                        robot.links[*main].name
                    )],
                });
            }
        }
    }
    Ok(edit_inertials(text, robot, &edits))
}
