//! A multibody [`Model`] read as symbols: per joint its axis and placement rotation (numbers,
//! snapped to exact `0, ±1` within 1e-14), its placement offset, its body's standard inertial
//! parameters, its armature (symbols, see [`Parameters`]), and gravity.

use super::expr::{Expr, Space, MAX_JOINTS};
use super::params::{ParamKind, Parameters};
use super::sym::{SymInertia, SymTransform, M3, V3};
use super::ExplicitError;
use crate::multibody::joint::Shape;
use crate::multibody::{JointId, Model};
use crate::spatial::Vec3;

/// One moving joint and its body, symbolically.
#[derive(Clone, Debug)]
pub(crate) struct ChainJoint {
    pub name: String,
    pub parent: Option<usize>,
    pub prismatic: bool,
    /// Unit axis in the joint frame.
    pub axis: [f64; 3],
    /// Rotation of the placement `X_T` (the joint frame at `q = 0` in the parent frame).
    pub rot: [[f64; 3]; 3],
    /// Parameters of the placement's translation, per component.
    pub offset: [Option<usize>; 3],
    pub mass: Option<usize>,
    pub first_moment: [Option<usize>; 3],
    /// Parameters of the inertia about the joint origin (symmetric: `[r][c]` and `[c][r]` share).
    pub inertia: [[Option<usize>; 3]; 3],
    pub armature: Option<usize>,
}

/// The symbolic chain (or tree) of a fixed-base model of revolute and prismatic joints.
#[derive(Clone, Debug)]
pub(crate) struct Chain {
    pub model_name: String,
    pub space: Space,
    pub joints: Vec<ChainJoint>,
    pub params: Parameters,
    /// Unit direction of gravity in the world (snapped).
    pub gravity_dir: [f64; 3],
    /// The gravity magnitude parameter (`None`: no gravity).
    pub gravity: Option<usize>,
    pub lower: Vec<f64>,
    pub upper: Vec<f64>,
}

/// `x` with values within 1e-14 of `0`, `1`, `-1` made exact (the round-off of `cos(π/2)`).
pub(crate) fn snap(x: f64) -> f64 {
    for t in [0.0, 1.0, -1.0] {
        if (x - t).abs() <= super::params::ZERO {
            return t;
        }
    }
    x
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl Chain {
    /// Reads `model`.
    ///
    /// # Errors
    /// A joint that is not revolute, continuous or prismatic; more than [`MAX_JOINTS`] joints.
    pub fn new(model: &Model) -> Result<Chain, ExplicitError> {
        // the revolute and prismatic joints: one angle's sine and cosine, or one displacement
        let axes: Vec<(Vec3, bool)> = model
            .joints()
            .iter()
            .map(|j| match j.kind.shape() {
                Shape::Revolute(axis) => Ok((axis, false)),
                Shape::Prismatic(axis) => Ok((axis, true)),
                Shape::FreeFlyer | Shape::General => Err(ExplicitError::UnsupportedJoint {
                    joint: j.name.clone(),
                    kind: j.kind.name(),
                }),
            })
            .collect::<Result<_, _>>()?;
        let n = model.njoints();
        if n > MAX_JOINTS {
            return Err(ExplicitError::TooManyJoints { n });
        }
        if n == 0 {
            return Err(ExplicitError::NoJoints);
        }
        let mut params = Parameters::default();
        let mut joints = Vec::with_capacity(n);
        let mut prismatic = 0u16;
        for (j, mj) in model.joints().iter().enumerate() {
            let (axis, is_prismatic) = axes[j];
            if is_prismatic {
                prismatic |= 1 << j;
            }
            let k = j + 1;
            let rot = std::array::from_fn(|r| {
                std::array::from_fn(|c| snap(mj.placement.rotation[(r, c)]))
            });
            let offset = std::array::from_fn(|c| {
                params.add(
                    format!("p{}{k}", AXES[c]),
                    mj.placement.translation[c],
                    ParamKind::Offset { joint: j, axis: c },
                )
            });
            let g = model.inertia(JointId(j));
            let mass = params.add(format!("M{k}"), g.mass(), ParamKind::Mass { body: j });
            let h = g.first_moment();
            let first_moment = std::array::from_fn(|c| {
                params.add(
                    format!("M{}{k}", AXES[c].to_uppercase()),
                    h[c],
                    ParamKind::FirstMoment { body: j, axis: c },
                )
            });
            let io = g.inertia_origin();
            let im = io.matrix();
            let mut inertia = [[None; 3]; 3];
            for r in 0..3 {
                for c in r..3 {
                    let name = format!("{}{}{k}", AXES[r].to_uppercase(), AXES[c].to_uppercase());
                    let p = params.add(
                        name,
                        im[(r, c)],
                        ParamKind::Inertia {
                            body: j,
                            row: r,
                            col: c,
                        },
                    );
                    inertia[r][c] = p;
                    inertia[c][r] = p;
                }
            }
            let armature = params.add(
                format!("IA{k}"),
                model.armature()[j],
                ParamKind::Armature { joint: j },
            );
            joints.push(ChainJoint {
                name: mj.name.clone(),
                parent: mj.parent.map(|p| p.0),
                prismatic: is_prismatic,
                axis: [snap(axis.x), snap(axis.y), snap(axis.z)],
                rot,
                offset,
                mass,
                first_moment,
                inertia,
                armature,
            });
        }
        let gw = model.gravity();
        let norm = gw.norm();
        let gravity = params.add("g".into(), norm, ParamKind::Gravity);
        let gravity_dir = if gravity.is_some() {
            [snap(gw.x / norm), snap(gw.y / norm), snap(gw.z / norm)]
        } else {
            [0.0; 3]
        };
        Ok(Chain {
            model_name: model.name().to_string(),
            space: Space { n, prismatic },
            joints,
            params,
            gravity_dir,
            gravity,
            lower: model.lower_limits().to_vec(),
            upper: model.upper_limits().to_vec(),
        })
    }

    /// The number of joints.
    pub fn n(&self) -> usize {
        self.space.n
    }

    fn param_or_zero(&self, p: Option<usize>) -> Expr {
        p.map_or_else(
            || Expr::zero(self.space),
            |p| Expr::param(self.space, p, 1.0),
        )
    }

    /// The pose of joint `j`'s moved frame in its parent's frame, `X_T X_J(q_j)`:
    /// `R = R_T exp([a] q)` with `exp([a] q) = a aᵀ + cos q (1 - a aᵀ) + sin q [a]`
    /// (Lynch & Park Prop. 3.11), `p = p_T`; prismatic: `R = R_T`, `p = p_T + R_T a q`.
    pub fn transform(&self, j: usize) -> SymTransform {
        let cj = &self.joints[j];
        let s = self.space;
        let rt = cj.rot;
        let a = cj.axis;
        let p_t: V3 = cj.offset.map(|p| self.param_or_zero(p));
        if cj.prismatic {
            let r: M3 =
                std::array::from_fn(|r| std::array::from_fn(|c| Expr::constant(s, rt[r][c])));
            let p = std::array::from_fn(|r| {
                let ra = snap((0..3).map(|k| rt[r][k] * a[k]).sum());
                p_t[r].add(&Expr::joint(s, j, false, ra))
            });
            return SymTransform { r, p };
        }
        // R_T (a aᵀ), R_T (1 - a aᵀ), R_T [a]
        let skew = [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]];
        let r = std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                let (mut k0, mut kc, mut ks) = (0.0, 0.0, 0.0);
                for l in 0..3 {
                    let aa = a[l] * a[c];
                    let id = if l == c { 1.0 } else { 0.0 };
                    k0 += rt[r][l] * aa;
                    kc += rt[r][l] * (id - aa);
                    ks += rt[r][l] * skew[l][c];
                }
                Expr::constant(s, snap(k0))
                    .add(&Expr::joint(s, j, false, snap(kc)))
                    .add(&Expr::joint(s, j, true, snap(ks)))
            })
        });
        SymTransform { r, p: p_t }
    }

    /// Body `j`'s spatial inertia in its joint frame, by its standard parameters.
    pub fn body_inertia(&self, j: usize) -> SymInertia {
        let cj = &self.joints[j];
        SymInertia {
            m: self.param_or_zero(cj.mass),
            h: cj.first_moment.map(|p| self.param_or_zero(p)),
            i: cj.inertia.map(|row| row.map(|p| self.param_or_zero(p))),
        }
    }

    /// The motion subspace `S_j = (ω, v)` of joint `j` in its frame: `(a, 0)` or `(0, a)`.
    pub fn subspace(&self, j: usize) -> ([f64; 3], [f64; 3]) {
        let a = self.joints[j].axis;
        if self.joints[j].prismatic {
            ([0.0; 3], a)
        } else {
            (a, [0.0; 3])
        }
    }
}
