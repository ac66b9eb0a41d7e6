//! The doctor on an SDF model: each link's `<inertial>` checked as a URDF link's is, against the
//! link's collision shapes when they are all boxes, cylinders, spheres or capsules (SDF meshes are
//! read as their convex hulls, without a file for the doctor's solid, and ellipsoids have no URDF
//! counterpart: a link with one of them gets the physical checks only, not a part of its solid).
//! `--fix` rewrites the `<inertial>` elements of the file read; a link from an `<include>`d file
//! is reported and left alone.

use super::{Doctor, DoctorReport};
use crate::collision::Shape;
use crate::io::sdf::SdfModel;
use crate::io::urdf::{UrdfGeometry, UrdfInertial, UrdfLink, UrdfRobot, UrdfShape};

/// The doctor's report on every link of `m` that has an `<inertial>`.
///
/// ```
/// use rigid::io::sdf::load_sdf_str;
/// // a 0.2 m box of 1 kg with 7.5 times the inertia it can hold
/// let m = load_sdf_str(r#"<sdf version="1.9"><model name="m"><link name="b"><inertial>
///   <mass>1</mass><inertia><ixx>0.05</ixx><iyy>0.05</iyy><izz>0.05</izz></inertia></inertial>
///   <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
///   </link></model></sdf>"#, ".".as_ref()).unwrap();
/// let report = rigid::doctor::examine_sdf(&m);
/// assert_eq!(report.bodies[0].name, "b");
/// assert_ne!(report.bodies[0].status, rigid::doctor::Status::Ok);
/// ```
#[must_use]
pub fn examine_sdf(m: &SdfModel) -> DoctorReport {
    Doctor::new().examine(&sdf_as_robot(m))
}

/// The links of `m` as URDF links (joints left out: the doctor checks one body at a time).
#[must_use]
pub fn sdf_as_robot(m: &SdfModel) -> UrdfRobot {
    let links: Vec<UrdfLink> = m
        .links
        .iter()
        .map(|l| UrdfLink {
            name: l.name.clone(),
            line: l.line,
            span: 0..0,
            inertial: l.inertial.as_ref().map(|i| UrdfInertial {
                origin: i.pose,
                rpy: {
                    let (r, p, y) = crate::spatial::so3::to_rpy(&i.pose.rotation);
                    [r, p, y]
                },
                mass: i.mass,
                inertia: i.inertia,
                line: i.line,
                text: i.text.clone(),
                span: 0..0,
            }),
            visuals: Vec::new(),
            // all of the link's shapes or none (the physical checks only): a part of its solid
            // would misjudge where its mass can be
            collisions: (l.collisions.iter())
                .map(|(origin, shape)| {
                    let shape = match *shape {
                        Shape::Box { size } => UrdfShape::Box { size },
                        Shape::Sphere { radius } => UrdfShape::Sphere { radius },
                        Shape::Cylinder { radius, length } => {
                            UrdfShape::Cylinder { radius, length }
                        }
                        Shape::Capsule { radius, length } => UrdfShape::Capsule { radius, length },
                        _ => return None,
                    };
                    Some(UrdfGeometry {
                        origin: *origin,
                        shape,
                        rgba: None,
                        line: l.line,
                    })
                })
                .collect::<Option<Vec<_>>>()
                .unwrap_or_default(),
        })
        .collect();
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

/// `text` (the SDF file `m` was read from) with each repaired link's `<inertial>` replaced by
/// one written from its repair (`<pose>` the centre of mass and the inertia's axes, `<mass>`,
/// `<inertia>` about the centre of mass), a comment before it giving the cause and the original
/// element; everything else is left byte for byte. Returns the text and the notes: a repaired
/// link written in an `<include>`d file is left alone.
///
/// # Errors
/// The text is not XML.
pub fn fixed_sdf(
    text: &str,
    m: &SdfModel,
    report: &DoctorReport,
) -> Result<(String, Vec<String>), String> {
    use crate::io::shortest as num;
    use crate::io::urdf::indent_at;
    let doc = roxmltree::Document::parse(text).map_err(|e| e.to_string())?;
    let mut notes = Vec::new();
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for b in &report.bodies {
        let Some(r) = &b.repaired else { continue };
        let Some(link) = m.links.iter().find(|l| l.name == b.name) else {
            continue;
        };
        if let Some(file) = &link.file {
            notes.push(format!(
                "link \"{}\": its <inertial> is in {}, an <include>d file: not repaired",
                b.name,
                file.display()
            ));
            continue;
        }
        let Some(range) = link.inertial.as_ref().map(|i| i.span.clone()) else {
            continue;
        };
        // the element the reader read, in the same text (not another that shares its line)
        let found = doc
            .descendants()
            .any(|n| n.has_tag_name("inertial") && n.range() == range);
        if !found {
            notes.push(format!(
                "link \"{}\": its <inertial> is not where the file read had it: not repaired",
                b.name
            ));
            continue;
        }
        let indent = indent_at(text, range.start);
        let e = r.inertia.entries();
        let moments = ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"]
            .iter()
            .zip(e)
            .map(|(t, x)| format!("<{t}>{}</{t}>", num(x)))
            .collect::<String>();
        let pose = [r.com.x, r.com.y, r.com.z, r.rpy[0], r.rpy[1], r.rpy[2]]
            .iter()
            .map(|x| num(*x))
            .collect::<Vec<_>>()
            .join(" ");
        let cause = b.likely_cause.map_or("unknown", |c| c.code());
        let element = format!(
            "<!-- rigid doctor: {cause}: {} -->\n{indent}<!-- was: {} -->\n{indent}<inertial>\
             <pose>{pose}</pose><mass>{}</mass><inertia>{moments}</inertia></inertial>",
            b.explanation.replace("--", "- -"),
            text[range.clone()].replace("--", "- -"),
            num(r.mass),
        );
        edits.push((range, element));
    }
    Ok((super::fix::splice(text, edits), notes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::doctor::Status;

    const BOX: &str = r#"<collision name="c"><pose>0.1 0 0 0 0 0</pose><geometry><box><size>0.2 0.4 0.6</size></box></geometry></collision>"#;

    fn model(inertia: &str) -> String {
        format!(
            r#"<?xml version="1.0"?>
<sdf version="1.9">
  <model name="m">
    <link name="b">
      <inertial><pose>0.1 0 0 0 0 0</pose><mass>48</mass>
        <inertia>{inertia}</inertia></inertial>
      {BOX}
    </link>
  </model>
</sdf>
"#
        )
    }

    /// A 48 kg box (water's density) of 0.2 x 0.4 x 0.6 m: `m (b² + c²)/12` and so on.
    const RIGHT: &str = "<ixx>2.08</ixx><iyy>1.6</iyy><izz>0.8</izz>";

    #[test]
    fn an_inertial_that_fits_its_box_is_ok_and_one_that_breaks_the_triangle_is_repaired() {
        let ok = crate::io::sdf::load_sdf_str(&model(RIGHT), ".".as_ref()).unwrap();
        let r = examine_sdf(&ok);
        assert_eq!(r.bodies.len(), 1);
        assert_eq!(r.bodies[0].status, Status::Ok, "{:?}", r.bodies[0]);
        // izz > ixx + iyy: no body has it
        let text = model("<ixx>2.08</ixx><iyy>1.6</iyy><izz>8</izz>");
        let bad = crate::io::sdf::load_sdf_str(&text, ".".as_ref()).unwrap();
        let r = examine_sdf(&bad);
        assert_eq!(r.bodies[0].status, Status::Invalid, "{:?}", r.bodies[0]);
        let (fixed, notes) = fixed_sdf(&text, &bad, &r).unwrap();
        assert!(notes.is_empty(), "{notes:?}");
        assert!(fixed.contains("<!-- rigid doctor:") && fixed.contains("<!-- was: <inertial>"));
        // the repaired file reads, and its link passes
        let again = crate::io::sdf::load_sdf_str(&fixed, ".".as_ref()).unwrap();
        let r = examine_sdf(&again);
        assert_ne!(r.bodies[0].status, Status::Invalid, "{:?}", r.bodies[0]);
        assert!(fixed.ends_with("  </model>\n</sdf>\n"));
    }

    /// Two links written on one line, both with `izz` ten times too large: each `<inertial>`
    /// is found by its own place in the text, not by its line.
    #[test]
    fn two_inertials_on_one_line_are_each_repaired() {
        let bad = "<inertial><mass>48</mass><inertia><ixx>2.08</ixx><iyy>1.6</iyy>\
                   <izz>8</izz></inertia></inertial>";
        let geom = r#"<collision name="c"><geometry><box><size>0.2 0.4 0.6</size></box></geometry></collision>"#;
        let text = format!(
            r#"<sdf version="1.9"><model name="m"><link name="a">{bad}{geom}</link><link name="b"><pose>1 0 0 0 0 0</pose>{bad}{geom}</link></model></sdf>"#
        );
        let m = crate::io::sdf::load_sdf_str(&text, ".".as_ref()).unwrap();
        let r = examine_sdf(&m);
        assert!(r.bodies.iter().all(|b| b.status == Status::Invalid));
        let (fixed, notes) = fixed_sdf(&text, &m, &r).unwrap();
        assert!(notes.is_empty(), "{notes:?}");
        assert_eq!(fixed.matches("<izz>0.8</izz>").count(), 2, "{fixed}");
        let again = crate::io::sdf::load_sdf_str(&fixed, ".".as_ref()).unwrap();
        assert!(examine_sdf(&again)
            .bodies
            .iter()
            .all(|b| b.status == Status::Ok));
    }
}
