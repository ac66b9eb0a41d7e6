//! Mass properties of one rigid body: rotational inertia (point masses, primitive solids,
//! triangle meshes, compounds of parts), principal axes, Steiner, validity, and the 6x6 spatial
//! inertia `G`, the pseudo-inertia and physical consistency, the ten inertial parameters `π`,
//! and `G`'s principal form (cheap to rotate, for the multibody algorithms).

mod compound;
mod consistency;
mod inertia;
mod mesh;
mod parameters;
mod principal_form;
mod shapes;
mod spatial_inertia;

pub use compound::{
    Compound, CompoundError, Geometry, MassOrDensity, MassProperties, Part, PartError,
};
pub use consistency::{nearest_consistent, Consistency, Mat4, Verdict, ROUND_OFF_ULPS};
pub use inertia::{RotationalInertia, DEFAULT_INERTIA_TOLERANCE};
pub use mesh::{MeshError, MeshMassProperties, TriMesh};
pub use parameters::PARAMETER_NAMES;
pub use principal_form::PrincipalForm;
pub use shapes::{Shape, ShapeError};
pub use spatial_inertia::SpatialInertia;
