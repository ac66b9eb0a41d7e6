//! `rigid doctor`: what is wrong with a URDF's inertial data (or an MJCF model's `<inertial>`
//! elements, [`examine_mjcf`], or an SDF model's, [`examine_sdf`]; any of the three by the file's
//! extension, [`examine_file`]), the likely cause, and the nearest valid value.
//!
//! For every link with an `<inertial>`, [`Doctor::examine`] runs the checks of
//! [`checks::Evaluation`]:
//!
//! | check | finding codes |
//! | --- | --- |
//! | mass positive and finite | `mass` |
//! | inertia about the CoM positive semi-definite | `not_psd` |
//! | triangle inequalities of the principal moments | `triangle` |
//! | pseudo-inertia `J = [[Σ, h], [hᵀ, m]]` positive definite (Wensing, Kim & Slotine 2017), [`crate::mass::Consistency`] | `pseudo_inertia`, `degenerate` |
//! | failing only by round-off | `round_off` |
//! | CoM inside (or near) the link's visual and collision shapes | `com_outside_geometry` |
//! | second moment within what the shapes can hold (Bhatia–Davis bound per direction) | `inertia_exceeds_geometry` |
//! | density `m / V` of the shapes' solid within 100–25 000 kg/m³ | `density` |
//! | no inertia at all on a massive link | `zero_inertia` |
//! | the same six numbers as another link of a different mass or size | `copied` |
//!
//! A body that passes them all is `ok` and is never repaired. Otherwise a **diagnosis**
//! ([`diagnose`]) undoes each known fault (`units_grams`, `units_millimetres`,
//! `about_link_origin`, `product_sign`, `rotation_lost`, `digit_typo`) and names the one after
//! which every check passes (`unknown` when none does, with what each undoing still fails), and
//! a **repair** proposes the parameters: the fault undone; for `zero_inertia` and `copied` the
//! inertia of a uniform solid filling the link's geometry (mass and CoM kept); otherwise, for a
//! physically inconsistent body, the nearest consistent one ([`nearest_consistent`]: mass and
//! CoM kept, the second moment about the CoM projected onto the positive-definite cone in the
//! Frobenius norm, a metric that does not depend on the frame the parameters are written in).
//! A consistent body whose only fault is being implausible for its geometry is reported, not
//! repaired, when no cause is found.
//!
//! Geometry: meshes are read from disk (STL, OBJ, COLLADA; `package://` resolved by
//! [`resolve_mesh_path`](crate::io::urdf::resolve_mesh_path)); a mesh that cannot be found is noted and
//! skipped, and a link without readable shapes gets the physical checks only.

pub mod checks;
pub mod diagnose;
mod file;
mod fix;
pub mod geometry;
#[cfg(feature = "mjcf")]
mod mjcf;
#[cfg(feature = "collision")]
mod sdf;

pub use checks::{Evaluation, Finding, InertialParams};
pub use diagnose::{Cause, Diagnosis, Hypothesis};
pub use file::{examine_file, DoctorFileError, FileReport};
pub use fix::{fixed_mjcf, fixed_urdf};
#[cfg(feature = "mjcf")]
pub use mjcf::{as_robot, examine_mjcf};
#[cfg(feature = "collision")]
pub use sdf::{examine_sdf, fixed_sdf, sdf_as_robot};

use crate::io::urdf::UrdfRobot;
use crate::mass::{nearest_consistent, RotationalInertia, Verdict};
use crate::spatial::{Mat3, Vec3};
use geometry::{link_geometry, LinkGeometry, MeshCache};
use serde::Serialize;

/// The verdict on one body.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Every check passes.
    Ok,
    /// Physically possible, but something is off (degenerate, round-off, implausible for its
    /// geometry, no inertia, copied).
    Warning,
    /// No mass distribution has these parameters.
    Invalid,
}

/// The doctor's proposal for a body: mass, CoM in the link frame, inertia about the CoM in the
/// link frame's axes (row-major).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Repair {
    /// Mass (kg).
    pub mass: f64,
    /// CoM in the link frame (m).
    pub com: [f64; 3],
    /// Inertia about the CoM, link axes (kg·m²).
    pub inertia: [[f64; 3]; 3],
}

/// The report on one link.
#[derive(Clone, Debug, Serialize)]
pub struct BodyReport {
    /// The link's name.
    pub name: String,
    /// Line of its `<inertial>`.
    pub line: u32,
    /// The verdict.
    pub status: Status,
    /// What the checks found.
    pub findings: Vec<Finding>,
    /// The likely cause (`None` for an `ok` body).
    pub likely_cause: Option<Cause>,
    /// Why: the fault undone, or for `unknown` what rules out each cause.
    pub explanation: String,
    /// The proposed parameters (`None`: `ok`, or no repair can be justified).
    pub repair: Option<Repair>,
    /// The proposed parameters as the URDF writes them (for `--fix`).
    #[serde(skip)]
    pub repaired: Option<InertialParams>,
    /// The numbers the checks decided on (for the given parameters).
    pub metrics: Metrics,
}

/// The numbers behind the checks of one body (`None` where a check did not apply).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    /// Principal moments of the inertia about the CoM, ascending (kg·m²).
    pub principal_moments: [f64; 3],
    /// Whether readable geometry was found, and what was used or skipped.
    pub geometry: Vec<String>,
    /// How far the CoM is outside the geometry, as a fraction of its extent.
    pub com_outside: Option<f64>,
    /// The second moment over the most the geometry can hold, worst direction (≤ 1 inside).
    pub variance_ratio: Option<f64>,
    /// `m / V` (kg/m³).
    pub density: Option<f64>,
    /// `tr Σ_c` over that of a uniform solid filling the geometry.
    pub size_ratio: Option<f64>,
    /// Cosine between the anisotropies of the body and of the geometry.
    pub axes_cosine: Option<f64>,
    /// Cosine between the products of inertia of the body and of the geometry.
    pub products_cosine: Option<f64>,
}

impl Metrics {
    fn of(e: &Evaluation, geometry: Option<&LinkGeometry>) -> Self {
        let l = e.consistency.principal_moments;
        Self {
            principal_moments: [l[0], l[1], l[2]],
            geometry: geometry
                .map_or_else(|| vec!["no readable geometry".into()], |g| g.notes.clone()),
            com_outside: e.com_outside,
            variance_ratio: e.variance_ratio,
            density: e.density.map(|d| d.0),
            size_ratio: e.size_ratio,
            axes_cosine: e.shape_agreement.map(|s| s.0),
            products_cosine: e.products_agreement.map(|s| s.0),
        }
    }
}

/// The report on a robot.
#[derive(Clone, Debug, Serialize)]
pub struct DoctorReport {
    /// The robot's name.
    pub robot: String,
    /// One report per link with an `<inertial>`, in file order.
    pub bodies: Vec<BodyReport>,
}

impl DoctorReport {
    /// The report on link `name`.
    #[must_use]
    pub fn body(&self, name: &str) -> Option<&BodyReport> {
        self.bodies.iter().find(|b| b.name == name)
    }
}

/// Examines robots, keeping the meshes it has read (a robot's legs share their meshes, and so do
/// the variants of one robot).
#[derive(Default)]
pub struct Doctor {
    cache: MeshCache,
}

/// Six inertia entries as bit patterns, for finding copies.
fn entries_key(p: &InertialParams) -> [u64; 6] {
    p.entries().map(|x| if x == 0.0 { 0 } else { x.to_bits() })
}

/// A uniform solid filling the geometry with mass `m` at `com` (`None` without geometry: a
/// sphere of density 1000 kg/m³ when `sphere`).
fn solid_estimate(
    m: f64,
    com: Vec3,
    geometry: Option<&LinkGeometry>,
    sphere: bool,
) -> Option<InertialParams> {
    let i = match geometry {
        Some(g) => {
            let s = g.second_moment_of_mass(m);
            Mat3::identity() * s.trace() - s
        }
        None if sphere => {
            let r = (3.0 * m / (4.0 * std::f64::consts::PI * 1000.0)).cbrt();
            Mat3::identity() * (0.4 * m * r * r)
        }
        None => return None,
    };
    Some(InertialParams {
        mass: m,
        com,
        rpy: [0.0; 3],
        inertia: RotationalInertia::from_matrix_unchecked(&i),
    })
}

impl Doctor {
    /// A doctor with an empty mesh cache.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The geometry of link `l` of `robot`.
    pub fn geometry(&mut self, robot: &UrdfRobot, l: usize) -> Option<LinkGeometry> {
        link_geometry(&robot.links[l], robot.path.as_deref(), &mut self.cache)
    }

    /// Examines every link of `robot` that has an `<inertial>`.
    ///
    /// ```
    /// use rigid::doctor::{Cause, Doctor, Status};
    /// use rigid::io::urdf::parse_urdf_str;
    /// // a 2 kg box 0.2 x 0.1 x 0.1 m whose mass was written in grams
    /// let robot = parse_urdf_str(r#"<robot name="r"><link name="box">
    ///   <inertial><mass value="2000"/>
    ///     <inertia ixx="0.003333" iyy="0.008333" izz="0.008333" ixy="0" ixz="0" iyz="0"/></inertial>
    ///   <collision><geometry><box size="0.2 0.1 0.1"/></geometry></collision></link></robot>"#).unwrap();
    /// let report = Doctor::new().examine(&robot);
    /// let b = &report.bodies[0];
    /// assert_eq!((b.status, b.likely_cause), (Status::Warning, Some(Cause::UnitsGrams)));
    /// assert!((b.repair.as_ref().unwrap().mass - 2.0).abs() < 1e-12);
    /// ```
    pub fn examine(&mut self, robot: &UrdfRobot) -> DoctorReport {
        let bodies = (0..robot.links.len())
            .filter_map(|l| self.examine_link(robot, l))
            .collect();
        DoctorReport {
            robot: robot.name.clone(),
            bodies,
        }
    }

    /// Examines link `l` of `robot` (`None` if it has no `<inertial>`).
    pub fn examine_link(&mut self, robot: &UrdfRobot, l: usize) -> Option<BodyReport> {
        let link = &robot.links[l];
        let inertial = link.inertial.as_ref()?;
        let p = InertialParams::from_urdf(inertial);
        let geometry = self.geometry(robot, l);
        let copy = self.copied_from(robot, l, &p, geometry.as_ref());
        Some(examine_body(
            &link.name,
            inertial.line,
            &p,
            &inertial.text,
            geometry.as_ref(),
            copy.as_deref(),
        ))
    }

    /// Another link with the same six inertia numbers (not all zero) and a mass differing by
    /// more than 10 %, or a geometry volume differing by more than a factor 2, from which this
    /// link's numbers were likely copied: this link fails a check, or else the other passes
    /// them all and fits its own mass and geometry better than this one does (of two twins
    /// whose masses differ, the one that fits is not the copy).
    fn copied_from(
        &mut self,
        robot: &UrdfRobot,
        l: usize,
        p: &InertialParams,
        geometry: Option<&LinkGeometry>,
    ) -> Option<String> {
        if p.entries().iter().all(|x| *x == 0.0) {
            return None;
        }
        let key = entries_key(p);
        let mine = Evaluation::of(p, geometry);
        for (o, other) in robot.links.iter().enumerate() {
            let Some(q) = other.inertial.as_ref().map(InertialParams::from_urdf) else {
                continue;
            };
            if o == l || entries_key(&q) != key {
                continue;
            }
            let theirs_geometry = self.geometry(robot, o);
            let mass_differs = (q.mass - p.mass).abs() > 0.1 * q.mass.abs().max(p.mass.abs());
            let size_differs = !mass_differs
                && match (geometry, theirs_geometry.as_ref()) {
                    (Some(a), Some(b)) => !(0.5..=2.0).contains(&(a.volume / b.volume)),
                    _ => false,
                };
            if !(mass_differs || size_differs) {
                continue;
            }
            if !mine.plausible() {
                return Some(other.name.clone());
            }
            let theirs = Evaluation::of(&q, theirs_geometry.as_ref());
            if theirs.plausible() && mine.oddness() > theirs.oddness() {
                return Some(other.name.clone());
            }
        }
        None
    }
}

/// The report on one body with parameters `p` (`text`: the numbers as written), its geometry, and
/// `copied_from`, a link with the same inertia numbers and a different mass or size.
#[must_use]
pub fn examine_body(
    name: &str,
    line: u32,
    p: &InertialParams,
    text: &[String; 7],
    geometry: Option<&LinkGeometry>,
    copied_from: Option<&str>,
) -> BodyReport {
    let e = Evaluation::of(p, geometry);
    let mut findings = e.findings(p);
    let verdict = e.consistency.verdict();
    let zero = p.mass > 0.0
        && (p.entries().iter().all(|x| *x == 0.0) || e.size_ratio.is_some_and(|r| r < 1e-6));
    if zero {
        findings.retain(|f| f.code != "degenerate");
        findings.push(Finding {
            code: "zero_inertia",
            message: format!("a {} kg link with no rotational inertia", p.mass),
        });
    }
    if let Some(other) = copied_from {
        findings.push(Finding {
            code: "copied",
            message: format!(
                "the same six inertia numbers as link \"{other}\", of a different mass or size"
            ),
        });
    }
    let invalid = matches!(
        verdict,
        Verdict::NonFinite
            | Verdict::BadMass
            | Verdict::NotPositiveSemiDefinite
            | Verdict::TriangleInequality
    );
    let status = if invalid {
        Status::Invalid
    } else if findings.is_empty() {
        Status::Ok
    } else {
        Status::Warning
    };
    let mut report = BodyReport {
        name: name.into(),
        line,
        status,
        findings,
        likely_cause: None,
        explanation: String::new(),
        repair: None,
        repaired: None,
        metrics: Metrics::of(&e, geometry),
    };
    if status == Status::Ok {
        return report;
    }
    let size = geometry.map(LinkGeometry::size);
    let diagnosis = (!zero).then(|| diagnose::diagnose(p, text, geometry, &e));
    let (cause, explanation, repaired) = if zero {
        let r = solid_estimate(p.mass, p.com, geometry, true);
        let how = if geometry.is_some() {
            "inertia of a uniform solid filling the link's geometry, mass and CoM kept"
        } else {
            "inertia of a uniform sphere of density 1000 kg/m³, mass and CoM kept"
        };
        (Cause::ZeroInertia, how.to_string(), r)
    } else if verdict == Verdict::RoundOff && e.plausible_but_consistency() {
        // raised just past the round-off allowance, so that the repair is strictly consistent
        let delta = 4.0 * e.consistency.round_off;
        let r = nearest(p, Some(delta));
        let how = format!("second moments below {delta:.1e} kg·m² raised to it (round-off)");
        (Cause::RoundOff, how, r)
    } else if let Some(h) = diagnosis
        .as_ref()
        .and_then(|d| d.undone.clone())
        // six equal numbers are a copy, unless the cause found is a mass in grams (a twin link
        // whose mass alone was mis-scaled)
        .filter(|h| copied_from.is_none() || h.cause == Cause::UnitsGrams)
    {
        (h.cause, h.detail, Some(h.params))
    } else if let Some(other) = copied_from {
        let r = solid_estimate(p.mass, p.com, geometry, false);
        let how = format!(
            "numbers copied from link \"{other}\"; {}",
            if r.is_some() {
                "repaired as a uniform solid filling the link's geometry, mass and CoM kept"
            } else {
                "no geometry to estimate the inertia from"
            }
        );
        (Cause::Copied, how, r)
    } else {
        let r = if invalid {
            nearest(p, size.map(|s| p.mass * (s / 100.0).powi(2)))
        } else {
            None
        };
        let mut why = diagnosis
            .map(|d| d.ruled_out.join("; "))
            .unwrap_or_default();
        if invalid {
            why.push_str(if r.is_some() {
                "; repaired as the nearest physically consistent inertia (mass and CoM kept)"
            } else {
                "; no repair: the mass must be measured"
            });
        } else {
            why.push_str("; not repaired: the body is physically possible");
        }
        (Cause::Unknown, why, r)
    };
    if cause == Cause::UnitsGrams {
        // the mass was the fault: the numbers are a twin's, not a copy
        report.findings.retain(|f| f.code != "copied");
    }
    report.likely_cause = Some(cause);
    report.explanation = explanation;
    report.repair = repaired.as_ref().map(|r| {
        let i = r.inertia_link_axes();
        Repair {
            mass: r.mass,
            com: [r.com.x, r.com.y, r.com.z],
            inertia: i.to_rows(),
        }
    });
    report.repaired = repaired;
    report
}

/// [`nearest_consistent`] of `p`, written in `p`'s own axes.
fn nearest(p: &InertialParams, delta: Option<f64>) -> Option<InertialParams> {
    let g = nearest_consistent(&p.spatial_inertia(), delta)?;
    let r = p.rotation();
    Some(InertialParams {
        inertia: g.inertia_com().in_rotated_frame(&r),
        ..p.clone()
    })
}
