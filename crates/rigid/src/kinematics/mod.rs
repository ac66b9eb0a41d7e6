//! Kinematics as verbs: [`inverse()`] finds joint positions that put a frame of a
//! [`Model`](crate::multibody::Model) at a target (Lynch & Park, *Modern Robotics*, ch. 6). The
//! forward kinematics and Jacobians it iterates on are those of [`multibody`](crate::multibody);
//! [`poe`] has them for a chain given by its screw axes alone, as the textbook's code library.
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `θ ← θ + J_b† V_b`, `[V_b] = log(T_sb⁻¹(θ) T_sd)` | [`inverse()`] with [`ErrorTwist::Body`], `damping = 0` | Lynch & Park §6.2, Algorithm `IKinBody` |
//! | `θ ← θ + J_s† V_s`, `V_s = [Ad_{T_sb}] V_b` | [`ErrorTwist::Space`] | `IKinSpace` |
//! | `Δθ = Jᵀ (J Jᵀ + λ² I)⁻¹ V`, λ adapted | `damping > 0` (the default) | Levenberg 1944, Marquardt 1963; Wampler 1986 (damped least squares) |
//! | position only: `e = p_d - p`, the 3 linear rows of the world-aligned Jacobian | [`Target::Position`] | Lynch & Park §6.2 |
//! | `T = M e^{[B_1]θ_1} ⋯ e^{[B_n]θ_n}`, `J_b`, `J_s` of a chain given by screw axes alone | [`poe`] | Lynch & Park eq. 4.14–4.16, 5.11, 5.18 |

pub mod inverse;
pub mod poe;

pub use inverse::{inverse, ErrorTwist, IkError, Options, Site, Solution, Target};
