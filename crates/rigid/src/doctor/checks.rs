//! The checks of one body: its inertial parameters as the URDF writes them, tested for physical
//! consistency and against the link's geometry.

use super::geometry::{directions, LinkGeometry};
use crate::io::urdf::UrdfInertial;
use crate::mass::{Consistency, RotationalInertia, SpatialInertia, Verdict};
use crate::spatial::{so3, Mat3, Vec3};
use serde::Serialize;

/// Lowest plausible density (kg/m³): cork and foams are above it.
pub const DENSITY_MIN: f64 = 100.0;
/// Highest plausible density (kg/m³): tungsten is 19 300, osmium 22 600.
pub const DENSITY_MAX: f64 = 25_000.0;
/// How far (as a fraction of the geometry's extent, plus [`COM_SLACK`]) the CoM may lie outside
/// the geometry before it is reported: shapes are simplified, cables and covers are missing.
pub const COM_MARGIN: f64 = 0.1;
/// Absolute slack on the CoM position (m).
pub const COM_SLACK: f64 = 0.002;
/// How much the second moment may exceed what the geometry can hold (the Bhatia–Davis bound
/// below) before it is reported.
pub const VARIANCE_MARGIN: f64 = 1.05;
/// Anisotropy `‖dev Σ‖ / tr Σ` above which a body's and its geometry's principal axes are
/// compared (a sphere has 0, a thin rod 0.82).
pub const ANISOTROPY_MIN: f64 = 0.2;
/// Lowest cosine between the deviatoric second moments of the body and of its geometry before
/// their principal axes are said to disagree.
pub const AXES_COS_MIN: f64 = 0.0;
/// Size of the off-diagonal part of `Σ` (relative to `tr Σ`) above which the signs of the
/// products of inertia are compared with the geometry's.
pub const PRODUCTS_MIN: f64 = 0.05;
/// Lowest cosine between the off-diagonal parts of `Σ_c` and `Σ_g` before the products of inertia
/// are said to have the wrong sign.
pub const PRODUCTS_COS_MIN: f64 = -0.5;

/// A link's inertial parameters as a URDF writes them.
#[derive(Clone, Debug, PartialEq)]
pub struct InertialParams {
    /// `<mass value>` (kg).
    pub mass: f64,
    /// `<origin xyz>`: the CoM in the link frame (m).
    pub com: Vec3,
    /// `<origin rpy>`: the axes in which `inertia` is written.
    pub rpy: [f64; 3],
    /// `<inertia>` about the CoM in the `rpy` axes (kg·m²).
    pub inertia: RotationalInertia,
}

impl InertialParams {
    /// The parameters of a parsed `<inertial>`.
    #[must_use]
    pub fn from_urdf(i: &UrdfInertial) -> Self {
        Self {
            mass: i.mass,
            com: i.origin.translation,
            rpy: i.rpy,
            inertia: i.inertia,
        }
    }

    /// The rotation of the `rpy` axes in the link frame.
    #[must_use]
    pub fn rotation(&self) -> Mat3 {
        so3::from_rpy(self.rpy[0], self.rpy[1], self.rpy[2])
    }

    /// The inertia about the CoM in the link frame's axes, `R I Rᵀ`.
    #[must_use]
    pub fn inertia_link_axes(&self) -> RotationalInertia {
        self.inertia.rotated_by(&self.rotation())
    }

    /// The spatial inertia in the link frame.
    #[must_use]
    pub fn spatial_inertia(&self) -> SpatialInertia {
        SpatialInertia::from_com(self.mass, self.com, self.inertia_link_axes())
    }

    /// The six inertia entries in URDF order `ixx, iyy, izz, ixy, ixz, iyz`.
    #[must_use]
    pub fn entries(&self) -> [f64; 6] {
        self.inertia.entries()
    }

    /// The same parameters with the six entries `e` (URDF order).
    #[must_use]
    pub fn with_entries(&self, e: [f64; 6]) -> Self {
        Self {
            inertia: RotationalInertia::new(e[0], e[1], e[2], e[3], e[4], e[5]),
            ..self.clone()
        }
    }
}

/// One finding of the doctor on one body.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Finding {
    /// A stable code: `mass`, `not_psd`, `triangle`, `pseudo_inertia`, `degenerate`,
    /// `round_off`, `com_outside_geometry`, `inertia_exceeds_geometry`, `density`,
    /// `zero_inertia`, `copied`.
    pub code: &'static str,
    /// What was found, with the numbers.
    pub message: String,
}

/// Everything the checks measure on one set of parameters.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// The physical-consistency tests.
    pub consistency: Consistency,
    /// How far the CoM lies outside the geometry, as a fraction of the extent in the worst
    /// direction (0 inside); `None` without geometry.
    pub com_outside: Option<f64>,
    /// `max_u uᵀ Σ_c u / (m b_u (−a_u))` over the directions `u`, where `[a_u, b_u]` is the
    /// geometry's extent along `u` relative to the CoM: a distribution on an interval has at
    /// most that variance (Bhatia & Davis 2000), so a body inside its geometry has at most 1.
    pub variance_ratio: Option<f64>,
    /// `m / V` (kg/m³), with whether `V` is exact (else an upper bound, so a lower bound).
    pub density: Option<(f64, bool)>,
    /// `tr Σ_c / tr(m Σ_g / V)`: the body's second moment relative to a uniform solid filling
    /// its geometry (typically 0.3 to 10 for real links).
    pub size_ratio: Option<f64>,
    /// Cosine between the deviatoric parts of `Σ_c` and of the geometry's `Σ_g` (1: the same
    /// orientation and shape of anisotropy), with the anisotropies `‖dev Σ‖ / tr Σ` of the
    /// body and of the geometry.
    pub shape_agreement: Option<(f64, f64, f64)>,
    /// Cosine between the off-diagonal parts `(Σ_xy, Σ_xz, Σ_yz)` of `Σ_c` and of `Σ_g` (the
    /// signs of the products of inertia against the geometry's), with their sizes relative to
    /// the traces.
    pub products_agreement: Option<(f64, f64, f64)>,
}

fn off_diagonal(s: &Mat3) -> Vec3 {
    Vec3::new(s[(0, 1)], s[(0, 2)], s[(1, 2)])
}

fn deviator(s: &Mat3) -> Mat3 {
    let t = s.trace();
    if t.abs() < f64::MIN_POSITIVE {
        return Mat3::zeros();
    }
    s / t - Mat3::identity() / 3.0
}

impl Evaluation {
    /// Checks `p` against `geometry` (if any).
    #[must_use]
    pub fn of(p: &InertialParams, geometry: Option<&LinkGeometry>) -> Self {
        let g = p.spatial_inertia();
        let consistency = Consistency::of(&g);
        let mut e = Self {
            consistency,
            com_outside: None,
            variance_ratio: None,
            density: None,
            size_ratio: None,
            shape_agreement: None,
            products_agreement: None,
        };
        let Some(geo) = geometry else { return e };
        if !consistency.finite || p.mass <= 0.0 {
            return e;
        }
        let sigma = g.second_moment_com();
        let (mut outside, mut ratio) = (0.0f64, 0.0f64);
        for (u, &(lo, hi)) in directions().iter().zip(&geo.extents) {
            let x = u.dot(&p.com);
            let span = (hi - lo).max(1e-9);
            let slack = COM_MARGIN * span + COM_SLACK;
            outside = outside.max(((x - hi).max(lo - x) - slack).max(0.0) / span);
            // Bhatia–Davis: a distribution on [lo, hi] with mean x has variance ≤ (hi−x)(x−lo)
            let room = (hi - x).max(0.0) * (x - lo).max(0.0);
            let var = (u.transpose() * sigma * u)[0];
            let r = if room > 0.0 {
                var / (p.mass * room)
            } else if var > 0.0 {
                f64::INFINITY
            } else {
                0.0
            };
            ratio = ratio.max(r);
        }
        e.com_outside = Some(outside);
        e.variance_ratio = Some(ratio);
        e.density = Some((p.mass / geo.volume, geo.volume_exact));
        let uniform = geo.second_moment_of_mass(p.mass);
        e.size_ratio = Some(sigma.trace() / uniform.trace().max(f64::MIN_POSITIVE));
        let (a, b) = (deviator(&sigma), deviator(&uniform));
        let cos = (a.component_mul(&b)).sum() / (a.norm() * b.norm()).max(f64::MIN_POSITIVE);
        e.shape_agreement = Some((cos, a.norm(), b.norm()));
        let (oa, ob) = (off_diagonal(&sigma), off_diagonal(&uniform));
        let ocos = oa.dot(&ob) / (oa.norm() * ob.norm()).max(f64::MIN_POSITIVE);
        e.products_agreement = Some((
            ocos,
            oa.norm() / sigma.trace().abs().max(f64::MIN_POSITIVE),
            ob.norm() / uniform.trace().abs().max(f64::MIN_POSITIVE),
        ));
        e
    }

    /// Physically consistent (beyond round-off) and not degenerate.
    #[must_use]
    pub fn consistent(&self) -> bool {
        matches!(self.consistency.verdict(), Verdict::Consistent)
    }

    /// The CoM lies in (or near) the geometry.
    #[must_use]
    pub fn com_ok(&self) -> bool {
        self.com_outside.is_none_or(|x| x == 0.0)
    }

    /// The second moment fits in the geometry (within [`VARIANCE_MARGIN`]).
    #[must_use]
    pub fn variance_ok(&self) -> bool {
        self.variance_ratio.is_none_or(|r| r <= VARIANCE_MARGIN)
    }

    /// The density is plausible (only the bound the volume estimate can support is tested).
    #[must_use]
    pub fn density_ok(&self) -> bool {
        self.density
            .is_none_or(|(d, exact)| d <= DENSITY_MAX && (d >= DENSITY_MIN || !exact))
    }

    /// The body's principal axes agree with its geometry's (when both are anisotropic enough to
    /// have axes).
    #[must_use]
    pub fn axes_ok(&self) -> bool {
        self.shape_agreement.is_none_or(|(cos, a, b)| {
            a < ANISOTROPY_MIN || b < ANISOTROPY_MIN || cos >= AXES_COS_MIN
        })
    }

    /// The signs of the products of inertia agree with the geometry's (when both are large
    /// enough to have a sign).
    #[must_use]
    pub fn products_ok(&self) -> bool {
        self.products_agreement.is_none_or(|(cos, a, b)| {
            a < PRODUCTS_MIN || b < PRODUCTS_MIN || cos >= PRODUCTS_COS_MIN
        })
    }

    /// Every check but physical consistency passes.
    #[must_use]
    pub fn plausible_but_consistency(&self) -> bool {
        self.com_ok()
            && self.variance_ok()
            && self.density_ok()
            && self.axes_ok()
            && self.products_ok()
    }

    /// Every check passes.
    #[must_use]
    pub fn plausible(&self) -> bool {
        self.consistent()
            && self.com_ok()
            && self.variance_ok()
            && self.density_ok()
            && self.axes_ok()
            && self.products_ok()
    }

    /// How unusual a body that passes every check still is, for ranking explanations (0 is a
    /// uniform solid filling its geometry): `|ln size_ratio| + (1 − cos) × anisotropy × 4`.
    #[must_use]
    pub fn oddness(&self) -> f64 {
        let size = self.size_ratio.map_or(0.0, |r| r.max(1e-300).ln().abs());
        let shape = self
            .shape_agreement
            .map_or(0.0, |(cos, _, aniso)| (1.0 - cos) * aniso.min(1.0) * 4.0);
        size + shape
    }

    /// The findings, one per failed check, with the numbers.
    #[must_use]
    pub fn findings(&self, p: &InertialParams) -> Vec<Finding> {
        let mut out = Vec::new();
        let c = &self.consistency;
        let l = c.principal_moments;
        let mut push = |code, message: String| out.push(Finding { code, message });
        match c.verdict() {
            Verdict::NonFinite => push("mass", "a parameter is not finite".into()),
            Verdict::BadMass => push(
                "mass",
                format!(
                    "mass {} kg must be positive (with a non-zero inertia)",
                    p.mass
                ),
            ),
            Verdict::NotPositiveSemiDefinite => {
                push(
                    "not_psd",
                    format!(
                        "inertia about the CoM is not positive semi-definite: principal moments \
                         {:.4e}, {:.4e}, {:.4e} kg·m²",
                        l[0], l[1], l[2]
                    ),
                );
                push(
                    "pseudo_inertia",
                    "no mass distribution has these parameters (pseudo-inertia not positive \
                     definite)"
                        .into(),
                );
            }
            Verdict::TriangleInequality => {
                push(
                    "triangle",
                    format!(
                        "principal moments violate the triangle inequality: {:.4e} + {:.4e} < \
                         {:.4e} kg·m²",
                        l[0], l[1], l[2]
                    ),
                );
                push(
                    "pseudo_inertia",
                    format!(
                        "no mass distribution has these parameters (pseudo-inertia eigenvalue \
                         (λ1 + λ2 − λ3)/2 = {:.4e} < 0)",
                        c.second_moments[0]
                    ),
                );
            }
            Verdict::Degenerate => push(
                "degenerate",
                format!(
                    "the mass lies on a point, a line or a plane (pseudo-inertia singular: \
                     smallest second moment {:.3e} kg·m²)",
                    c.second_moments[0]
                ),
            ),
            Verdict::RoundOff => push(
                "round_off",
                format!(
                    "fails the consistency tests by round-off only (smallest principal moment \
                     {:.3e}, allowance {:.3e} kg·m²)",
                    l[0], c.round_off
                ),
            ),
            Verdict::Consistent | Verdict::Massless => {}
        }
        if let Some(x) = self.com_outside.filter(|x| *x > 0.0) {
            push(
                "com_outside_geometry",
                format!(
                    "the CoM ({:.4}, {:.4}, {:.4}) m lies outside the link's geometry, by {:.0} % \
                     of its extent",
                    p.com.x,
                    p.com.y,
                    p.com.z,
                    x * 100.0
                ),
            );
        }
        let com_inside = self.com_ok();
        if let Some(r) = self
            .variance_ratio
            .filter(|r| *r > VARIANCE_MARGIN && com_inside)
        {
            push(
                "inertia_exceeds_geometry",
                format!(
                    "the inertia is too large for a mass inside the link's geometry: the second \
                     moment is {} times the most the geometry can hold in some direction",
                    sig(r, 3)
                ),
            );
        }
        if let (false, Some((cos, _, _))) = (self.axes_ok(), self.shape_agreement) {
            push(
                "axes_disagree_with_geometry",
                format!(
                    "the principal axes of the inertia disagree with the link's geometry (cosine \
                     {cos:.2} between their anisotropies)"
                ),
            );
        }
        if let (false, Some((cos, _, _))) = (self.products_ok(), self.products_agreement) {
            push(
                "products_disagree_with_geometry",
                format!(
                    "the products of inertia have the opposite signs to the link's geometry's \
                     (cosine {cos:.2})"
                ),
            );
        }
        if let Some((d, exact)) = self.density {
            if d > DENSITY_MAX || (exact && d < DENSITY_MIN) {
                let bound = if exact { "" } else { "at least " };
                push(
                    "density",
                    format!(
                        "mass over geometry volume is {bound}{} kg/m³, outside the \
                         plausible {DENSITY_MIN}–{DENSITY_MAX} kg/m³",
                        sig(d, 4)
                    ),
                );
            }
        }
        out
    }
}

/// `x` with `digits` significant digits, in plain notation between 10⁻³ and 10⁶.
#[must_use]
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if (-3..6).contains(&e) {
        let decimals = (digits as i32 - 1 - e).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.*e}", digits.saturating_sub(1))
    }
}
