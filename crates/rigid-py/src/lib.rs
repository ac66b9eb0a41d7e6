//! The Python module `rigid`: rigid's multibody and single-body dynamics with Pinocchio's verbs
//! and numpy arrays. Built by maturin (`pip install ./crates/rigid-py`); the Python-side
//! documentation is `rigid.pyi` beside this crate's `Cargo.toml`.
//!
//! | file | what |
//! | --- | --- |
//! | `convert.rs` | array-likes in (zero-copy for contiguous float64), fresh arrays out, errors |
//! | `model.rs` | `Model`, the layouts (rigid's, Pinocchio's, MuJoCo's) |
//! | `data.rs` | `Data`: the workspace, and its fields (`oMi`, `M`, `nle`, `J`, `com`, ...) in the model's layout |
//! | `dynamics.rs` | `rnea`, `crba`, `aba`, `nle`, `gravity`, `minverse`, `coriolis_matrix`, `forward_kinematics`, `jacobian`, `com`, energies |
//! | `configuration.rs` | `neutral`, `random_configuration`, `seed`, `integrate`, `difference` |
//! | `derivatives.rs` | `rnea_derivatives`, `aba_derivatives`, `gravity_derivatives` |
//! | `constraints.rs` | `ConstraintModel`, `ConstraintData`, `constraint_dynamics`, `impulse_dynamics`, `contact_inverse_dynamics` (and Pinocchio's names) |
//! | `outputs.rs` | the batch verbs' fresh outputs, from a cache of the arrays they returned, `set_output_cache` |
//! | `batch.rs` | `rnea_batch`, `aba_batch`, `crba_batch`, `rnea_derivatives_batch` (all cores, GIL released) |
//! | `simulation.rs` | `simulate` (robot simulation, built-in or Python control laws), `replay_html` |
//! | `simulator.rs` | `Simulator`: one step at a time from any state with an open-loop torque, and `step_derivatives` |
//! | `pinocchio.rs` | what the Pinocchio layer `rigid.pinocchio` needs: `compute_joint_jacobians`, `update_frame_placements`, `com_jacobian`, `centroidal_momentum(_matrix)`, `kinematics_derivatives`, `interpolate`, `normalize`, the Jacobians kept in a `Data` |
//! | `geometry.rs` | `urdf_link_geometries`, `Collider`, `proximity`, `read_srdf` (the Pinocchio layer's geometry models, collisions and SRDF) |
//! | `inverse_kinematics.rs` | `inverse_kinematics` (`rigid::kinematics::inverse`: targets in, a dict out) |
//! | `lie.rs` | SE(3)/SO(3) `exp`, `log` and their Jacobians for `rigid.pinocchio` (`_exp6`, `_log6`, `_jexp6`, `_jlog6` and the SO(3) four) |
//! | `scale.rs` | `threads=` pools, `regressor_batch`, `simulate_batch`, `Model.with_dynamic_parameters`, the refusal of dask arrays |
//! | `body.rs` | `mass_properties`, shapes, `spatial_inertia`, `simulate_body`, `doctor` |
//! | `mobile.rs` | `rigid.mobile`: `Base`, `MobileManipulator`, `Feedback`, `pick_and_place`, `capstone`, `fkin_body`/`fkin_space`/`jacobian_body`/`jacobian_space` (the native `_mobile`, re-exported by `python/rigid/mobile.py`); `mobile_tasks.rs` its runs (`pick_and_place`, `capstone`, `drive`) and `fkin_*`/`jacobian_*` |

mod batch;
mod body;
mod configuration;
mod constraints;
mod convert;
mod data;
mod derivatives;
mod dynamics;
mod geometry;
mod identification;
mod inverse_kinematics;
mod lie;
mod mimic;
mod mobile;
mod mobile_tasks;
mod model;
mod outputs;
mod pinocchio;
mod scale;
mod simulation;
mod simulator;

use pyo3::prelude::*;

/// Pinocchio's names of the verbs whose signature is the same, so that porting a script is a
/// search-and-replace of `pin.` by `rigid.`.
const PINOCCHIO_ALIASES: [(&str, &str); 13] = [
    ("computeJointTorqueRegressor", "regressor"),
    ("computeRNEADerivatives", "rnea_derivatives"),
    ("computeABADerivatives", "aba_derivatives"),
    (
        "computeGeneralizedGravityDerivatives",
        "gravity_derivatives",
    ),
    ("nonLinearEffects", "nle"),
    ("computeGeneralizedGravity", "gravity"),
    ("computeMinverse", "minverse"),
    ("computeCoriolisMatrix", "coriolis_matrix"),
    ("forwardKinematics", "forward_kinematics"),
    ("centerOfMass", "com"),
    ("computeKineticEnergy", "kinetic_energy"),
    ("computePotentialEnergy", "potential_energy"),
    ("randomConfiguration", "random_configuration"),
];

/// rigid: rigid-body dynamics (RNEA, CRBA, ABA, Jacobians, mass properties) with Pinocchio's
/// verbs and numpy arrays. SI units; twists angular first; quaternions x-y-z-w; joints
/// depth-first. `layout="pinocchio"` models read and write Pinocchio's raw arrays. See the stubs
/// (`rigid.pyi`) for every verb's formula, units and conventions.
// `gil_used`: a free-threaded CPython enables the GIL when it imports rigid (with a warning
// that names the module); the batch verbs' output cache and the pyclasses' state are not
// written for threads running Python at once
#[pymodule(gil_used = true)]
#[pyo3(name = "rigid")]
fn rigid_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // the optional capabilities this build has (`sdp`: the physically consistent identification)
    let features: Vec<&str> = [("sdp", cfg!(feature = "sdp"))]
        .into_iter()
        .filter_map(|(name, on)| on.then_some(name))
        .collect();
    m.add("features", pyo3::types::PyTuple::new(m.py(), features)?)?;
    m.add_class::<model::Model>()?;
    m.add_class::<model::Data>()?;
    m.add_class::<mimic::MimicModel>()?;
    m.add("UrdfWarning", m.py().get_type::<model::UrdfWarning>())?;
    m.add("MjcfWarning", m.py().get_type::<model::MjcfWarning>())?;
    m.add("SdfWarning", m.py().get_type::<model::SdfWarning>())?;
    m.add_function(wrap_pyfunction!(dynamics::rnea, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::aba, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::jacobian_dynamics, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::jacobian_dynamics_from_terms, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::crba, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::nle, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::gravity, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::minverse, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::coriolis_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::forward_kinematics, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::jacobian, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::com, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::kinetic_energy, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::potential_energy, m)?)?;
    m.add_function(wrap_pyfunction!(configuration::seed, m)?)?;
    m.add_function(wrap_pyfunction!(configuration::neutral, m)?)?;
    m.add_function(wrap_pyfunction!(configuration::random_configuration, m)?)?;
    m.add_function(wrap_pyfunction!(configuration::integrate, m)?)?;
    m.add_function(wrap_pyfunction!(configuration::difference, m)?)?;
    m.add_function(wrap_pyfunction!(derivatives::rnea_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(derivatives::aba_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(derivatives::gravity_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::simulate, m)?)?;
    m.add_class::<simulator::Simulator>()?;
    m.add_function(wrap_pyfunction!(simulation::replay_html, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::urdf_link_geometries, m)?)?;
    m.add_class::<geometry::Collider>()?;
    m.add_function(wrap_pyfunction!(geometry::proximity, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::read_srdf, m)?)?;
    m.add_function(wrap_pyfunction!(geometry::_urdf_welded_inertia, m)?)?;
    m.add_function(wrap_pyfunction!(batch::rnea_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::aba_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::crba_batch, m)?)?;
    m.add_function(wrap_pyfunction!(batch::rnea_derivatives_batch, m)?)?;
    m.add_function(wrap_pyfunction!(outputs::set_output_cache, m)?)?;
    m.add_function(wrap_pyfunction!(identification::regressor, m)?)?;
    m.add_function(wrap_pyfunction!(identification::dynamic_parameters, m)?)?;
    m.add_function(wrap_pyfunction!(identification::excite, m)?)?;
    m.add_function(wrap_pyfunction!(identification::identify, m)?)?;
    m.add_function(wrap_pyfunction!(body::mass_properties, m)?)?;
    m.add_function(wrap_pyfunction!(body::spatial_inertia, m)?)?;
    m.add_function(wrap_pyfunction!(body::simulate_body, m)?)?;
    m.add_function(wrap_pyfunction!(body::doctor, m)?)?;
    m.add_function(wrap_pyfunction!(body::r#box, m)?)?;
    m.add_function(wrap_pyfunction!(body::cylinder, m)?)?;
    m.add_function(wrap_pyfunction!(body::sphere, m)?)?;
    m.add_function(wrap_pyfunction!(body::ellipsoid, m)?)?;
    m.add_function(wrap_pyfunction!(body::capsule, m)?)?;
    m.add_function(wrap_pyfunction!(body::cone, m)?)?;
    m.add_function(wrap_pyfunction!(body::rod, m)?)?;
    m.add_function(wrap_pyfunction!(body::point, m)?)?;
    m.add_function(wrap_pyfunction!(body::mesh, m)?)?;
    constraints::register(m)?;
    pinocchio::register(m)?;
    scale::register(m)?;
    mobile::register(m)?;
    for (alias, name) in PINOCCHIO_ALIASES {
        m.add(alias, m.getattr(name)?)?;
    }
    Ok(())
}
