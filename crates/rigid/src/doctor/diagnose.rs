//! The likely cause of a bad body: each known fault is undone in turn, and a cause is named when
//! undoing it leaves a body that passes every check (physically consistent, inside its geometry,
//! of plausible density). Among several, the one whose result looks most like a uniform solid
//! filling the geometry wins, with a small penalty for the less specific explanations.

use super::checks::{Evaluation, InertialParams};
use super::geometry::LinkGeometry;
use crate::mass::RotationalInertia;
use crate::spatial::{skew, so3, Mat3};
use serde::Serialize;

/// The diagnosis codes of `rigid doctor`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Cause {
    /// Fails only by round-off.
    RoundOff,
    /// The mass is in grams (×1000).
    UnitsGrams,
    /// Lengths in millimetres: the CoM ×1000, the inertia ×10⁶.
    UnitsMillimetres,
    /// The inertia is about the link frame's origin, not the CoM.
    AboutLinkOrigin,
    /// Products of inertia given as `+∫xy` instead of `−∫xy`.
    ProductSign,
    /// The inertial `rpy` dropped, or applied twice.
    RotationLost,
    /// One entry off by a power of ten, or with two digits swapped.
    DigitTypo,
    /// The same numbers as another link of a different size or mass.
    Copied,
    /// A link with mass but no inertia.
    ZeroInertia,
    /// None of the above explains it.
    Unknown,
}

impl Cause {
    /// The code, as in the JSON report.
    #[must_use]
    pub fn code(self) -> &'static str {
        match self {
            Self::RoundOff => "round_off",
            Self::UnitsGrams => "units_grams",
            Self::UnitsMillimetres => "units_millimetres",
            Self::AboutLinkOrigin => "about_link_origin",
            Self::ProductSign => "product_sign",
            Self::RotationLost => "rotation_lost",
            Self::DigitTypo => "digit_typo",
            Self::Copied => "copied",
            Self::ZeroInertia => "zero_inertia",
            Self::Unknown => "unknown",
        }
    }

    /// Every code, in the order of the issue that defines them.
    pub const ALL: [Cause; 10] = [
        Self::RoundOff,
        Self::UnitsGrams,
        Self::UnitsMillimetres,
        Self::AboutLinkOrigin,
        Self::ProductSign,
        Self::RotationLost,
        Self::DigitTypo,
        Self::Copied,
        Self::ZeroInertia,
        Self::Unknown,
    ];
}

/// One fault undone: the cause, the parameters it gives, and what was changed.
#[derive(Clone, Debug)]
pub struct Hypothesis {
    /// The cause.
    pub cause: Cause,
    /// The parameters with the fault undone.
    pub params: InertialParams,
    /// What undoing changed, for the report.
    pub detail: String,
}

/// A penalty added to the oddness of the less specific explanations, so that a structural
/// cause is preferred to a typo that happens to fit as well.
fn prior(cause: Cause) -> f64 {
    match cause {
        Cause::DigitTypo => 1.0,
        Cause::RotationLost => 0.25,
        _ => 0.0,
    }
}

const ENTRY_NAMES: [&str; 6] = ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"];

/// Every fault that can be undone from the numbers alone (and the geometry, for a lost
/// rotation), each as a [`Hypothesis`]. `text` is the `<inertial>`'s numbers as written (for
/// digit swaps).
#[must_use]
pub fn hypotheses(
    p: &InertialParams,
    text: &[String; 7],
    geometry: Option<&LinkGeometry>,
) -> Vec<Hypothesis> {
    let mut out = Vec::new();
    let mut add = |cause, params, detail: String| {
        out.push(Hypothesis {
            cause,
            params,
            detail,
        })
    };
    let e = p.entries();
    let scaled = |k: f64| p.with_entries(e.map(|x| x * k));

    // units: grams (mass alone, or mass and inertia in g·m²), millimetres
    add(
        Cause::UnitsGrams,
        InertialParams {
            mass: p.mass / 1000.0,
            ..p.clone()
        },
        "mass divided by 1000 (grams to kilograms)".into(),
    );
    add(
        Cause::UnitsGrams,
        InertialParams {
            mass: p.mass / 1000.0,
            ..scaled(1e-3)
        },
        "mass and inertia divided by 1000 (g and g·m² to kg and kg·m²)".into(),
    );
    add(
        Cause::UnitsMillimetres,
        InertialParams {
            com: p.com / 1000.0,
            ..scaled(1e-6)
        },
        "CoM divided by 1000 and inertia by 10⁶ (mm and kg·mm² to m and kg·m²)".into(),
    );
    add(
        Cause::UnitsMillimetres,
        scaled(1e-6),
        "inertia divided by 10⁶ (kg·mm² to kg·m²)".into(),
    );

    // about the link origin: Steiner back to the CoM, in the inertia's axes
    let c = p.com;
    let steiner = -skew(&c) * skew(&c) * p.mass; // m (|c|² 1 − c cᵀ), link axes
    let r = p.rotation();
    let back = p.inertia.matrix() - r.transpose() * steiner * r;
    add(
        Cause::AboutLinkOrigin,
        InertialParams {
            inertia: RotationalInertia::from_matrix_unchecked(&back),
            ..p.clone()
        },
        "inertia moved from the link origin to the CoM (Steiner: minus m(|c|²1 − c cᵀ))".into(),
    );

    // product signs
    if e[3] != 0.0 || e[4] != 0.0 || e[5] != 0.0 {
        add(
            Cause::ProductSign,
            p.with_entries([e[0], e[1], e[2], -e[3], -e[4], -e[5]]),
            "products of inertia negated (−∫xy convention)".into(),
        );
    }

    // a rotation applied twice: the matrix was already in link axes
    if p.rpy != [0.0; 3] {
        add(
            Cause::RotationLost,
            InertialParams {
                rpy: [0.0; 3],
                ..p.clone()
            },
            format!(
                "rpy {:?} dropped: the inertia was already in the link's axes (rotation applied \
                 twice)",
                p.rpy
            ),
        );
    }
    // a rotation dropped: a diagonal inertia whose axes should be the geometry's principal axes
    if let Some(geo) = geometry {
        if p.rpy == [0.0; 3] && e[3] == 0.0 && e[4] == 0.0 && e[5] == 0.0 {
            if let Some(rot) = rotation_from_geometry(p, geo) {
                add(Cause::RotationLost, rot.0, rot.1);
            }
        }
    }

    // one entry: ×10^k, or two digits swapped
    for (k, name) in ENTRY_NAMES.iter().enumerate() {
        if e[k] == 0.0 {
            continue;
        }
        for pow in [-3, -2, -1, 1, 2, 3] {
            let mut f = e;
            f[k] = e[k] * 10f64.powi(pow);
            add(
                Cause::DigitTypo,
                p.with_entries(f),
                format!("{name} {} -> {} (a factor 10^{pow})", e[k], f[k]),
            );
        }
        for swapped in digit_swaps(&text[k + 1]) {
            let mut f = e;
            f[k] = swapped;
            add(
                Cause::DigitTypo,
                p.with_entries(f),
                format!("{name} {} -> {} (two digits swapped)", text[k + 1], swapped),
            );
        }
    }
    out
}

/// Every number obtained by swapping two different digits of the mantissa of `text`.
fn digit_swaps(text: &str) -> Vec<f64> {
    let mantissa_end = text.find(['e', 'E']).unwrap_or(text.len());
    let digits: Vec<usize> = text[..mantissa_end]
        .char_indices()
        .filter(|(_, c)| c.is_ascii_digit())
        .map(|(i, _)| i)
        .collect();
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    for (a, &i) in digits.iter().enumerate() {
        for &j in &digits[a + 1..] {
            if bytes[i] == bytes[j] {
                continue;
            }
            let mut b = bytes.to_vec();
            b.swap(i, j);
            if let Some(x) = std::str::from_utf8(&b)
                .ok()
                .and_then(|s| s.parse::<f64>().ok())
            {
                if x.is_finite() && !out.contains(&x) {
                    out.push(x);
                }
            }
        }
    }
    out
}

/// The diagonal inertia turned onto the geometry's principal axes (largest second moment along
/// the geometry's longest direction), with the `rpy` that writes it.
fn rotation_from_geometry(
    p: &InertialParams,
    geo: &LinkGeometry,
) -> Option<(InertialParams, String)> {
    let eg = geo.second_moment.symmetric_eigen();
    let mut gi = [0usize, 1, 2];
    gi.sort_by(|&a, &b| eg.eigenvalues[a].total_cmp(&eg.eigenvalues[b]));
    // the geometry must be anisotropic enough to have principal axes (an axisymmetric one
    // still fixes its axis; the two equal axes may be any pair)
    let dev = geo.second_moment / geo.second_moment.trace() - Mat3::identity() / 3.0;
    if dev.norm() < super::checks::ANISOTROPY_MIN {
        return None;
    }
    let sigma = p.spatial_inertia().second_moment_com();
    let d = sigma.diagonal();
    let mut pi = [0usize, 1, 2];
    pi.sort_by(|&a, &b| d[a].total_cmp(&d[b]));
    // R maps the link axis pi[k] onto the geometry's k-th principal axis
    let mut r = Mat3::zeros();
    for k in 0..3 {
        let axis = eg.eigenvectors.column(gi[k]);
        r.set_column(pi[k], &axis);
    }
    if r.determinant() < 0.0 {
        let c = -r.column(pi[0]);
        r.set_column(pi[0], &c);
    }
    if (r - Mat3::identity()).amax() < 0.05 {
        return None;
    }
    let (a, b, c) = so3::to_rpy(&r);
    Some((
        InertialParams {
            rpy: [a, b, c],
            ..p.clone()
        },
        format!(
            "rpy ({a:.4}, {b:.4}, {c:.4}) restored: the principal axes turned onto the geometry's"
        ),
    ))
}

/// The outcome of [`diagnose`].
#[derive(Clone, Debug)]
pub struct Diagnosis {
    /// The likely cause.
    pub cause: Cause,
    /// The parameters with it undone, when a fault was undone.
    pub undone: Option<Hypothesis>,
    /// For `unknown`: why each cause was ruled out (the checks its undoing still fails).
    pub ruled_out: Vec<String>,
}

/// How much undoing changes the body: `‖ΔΣ_c‖_F / ‖Σ_c‖_F` plus the relative change of the mass.
fn change(p: &InertialParams, q: &InertialParams) -> f64 {
    let (a, b) = (p.spatial_inertia(), q.spatial_inertia());
    let (sa, sb) = (a.second_moment_com(), b.second_moment_com());
    (sa - sb).norm() / sa.norm().max(f64::MIN_POSITIVE)
        + (a.mass() - b.mass()).abs() / a.mass().abs().max(f64::MIN_POSITIVE)
}

/// A check of [`Evaluation`], for bookkeeping which a fault can affect.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Check {
    Consistency,
    Com,
    Variance,
    Density,
    Axes,
    Products,
}

impl Check {
    fn name(self) -> &'static str {
        match self {
            Self::Consistency => "consistency",
            Self::Com => "CoM inside the geometry",
            Self::Variance => "inertia within the geometry",
            Self::Density => "density",
            Self::Axes => "principal axes against the geometry",
            Self::Products => "signs of the products against the geometry",
        }
    }
}

/// The checks undoing `h` can change (the rest it leaves as they were).
fn affects(h: &Hypothesis, p: &InertialParams) -> &'static [Check] {
    const INERTIA: &[Check] = &[
        Check::Consistency,
        Check::Variance,
        Check::Axes,
        Check::Products,
    ];
    match h.cause {
        Cause::UnitsGrams => &[Check::Density, Check::Variance],
        Cause::UnitsMillimetres if h.params.com != p.com => &[
            Check::Consistency,
            Check::Com,
            Check::Variance,
            Check::Axes,
            Check::Products,
        ],
        _ => INERTIA,
    }
}

fn failed_checks(e: &Evaluation) -> Vec<Check> {
    let mut f = Vec::new();
    if !e.consistent() {
        f.push(Check::Consistency);
    }
    if !e.com_ok() {
        f.push(Check::Com);
    }
    if !e.variance_ok() {
        f.push(Check::Variance);
    }
    if !e.density_ok() {
        f.push(Check::Density);
    }
    if !e.axes_ok() {
        f.push(Check::Axes);
    }
    if !e.products_ok() {
        f.push(Check::Products);
    }
    f
}

/// A fault's undoing is believable only if the body it gives is not itself absurd: its second
/// moment within a factor 100 of a uniform solid filling its geometry.
const MAX_ODD_SIZE: f64 = 100.0;

/// Undoes each fault of [`hypotheses`] and keeps those after which every check passes; the one
/// with the least [`Evaluation::oddness`] (plus a penalty for typos) is the likely cause.
/// `original` is the evaluation of `p` itself.
#[must_use]
pub fn diagnose(
    p: &InertialParams,
    text: &[String; 7],
    geometry: Option<&LinkGeometry>,
    original: &Evaluation,
) -> Diagnosis {
    let failed_before = failed_checks(original);
    let mut best: Option<(f64, Hypothesis)> = None;
    let mut alternatives: Vec<Cause> = Vec::new();
    let mut ruled_out: Vec<(Cause, String)> = Vec::new();
    for h in hypotheses(p, text, geometry) {
        let can = affects(&h, p);
        if !failed_before.iter().any(|c| can.contains(c)) {
            continue; // it would explain nothing that is wrong
        }
        let e = Evaluation::of(&h.params, geometry);
        let still: Vec<Check> = failed_checks(&e)
            .into_iter()
            .filter(|c| can.contains(c) || !failed_before.contains(c))
            .collect();
        let absurd = e
            .size_ratio
            .is_some_and(|r| !(1.0 / MAX_ODD_SIZE..=MAX_ODD_SIZE).contains(&r));
        if still.is_empty() && !absurd {
            // the least odd result, then the smallest change (without geometry every result is
            // equally plausible, and a factor 10 is likelier than 1000)
            let cost = e.oddness() + prior(h.cause) + 0.1 * change(p, &h.params);
            if let Some((c, b)) = &best {
                if b.cause != h.cause && !alternatives.contains(&b.cause) {
                    alternatives.push(b.cause);
                }
                if cost >= *c {
                    if b.cause != h.cause && !alternatives.contains(&h.cause) {
                        alternatives.push(h.cause);
                    }
                    continue;
                }
            }
            best = Some((cost, h));
            continue;
        }
        let why = if still.is_empty() {
            format!(
                "undoing it gives a second moment {} times a uniform solid's",
                super::checks::sig(e.size_ratio.unwrap_or(f64::NAN), 3)
            )
        } else {
            let names: Vec<&str> = still.iter().map(|c| c.name()).collect();
            format!("undoing it still fails {}", names.join(", "))
        };
        if !ruled_out.iter().any(|(c, _)| *c == h.cause) {
            ruled_out.push((h.cause, why));
        }
    }
    match best {
        Some((_, mut h)) => {
            alternatives.retain(|c| *c != h.cause);
            if !alternatives.is_empty() {
                let also: Vec<&str> = alternatives.iter().map(|c| c.code()).collect();
                h.detail.push_str(&format!(
                    " (also consistent with the checks, but a worse fit: {})",
                    also.join(", ")
                ));
            }
            Diagnosis {
                cause: h.cause,
                undone: Some(h),
                ruled_out: Vec::new(),
            }
        }
        None => Diagnosis {
            cause: Cause::Unknown,
            undone: None,
            ruled_out: ruled_out
                .into_iter()
                .map(|(c, why)| format!("{}: {why}", c.code()))
                .collect(),
        },
    }
}
