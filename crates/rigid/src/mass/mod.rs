//! Mass properties of one rigid body: rotational inertia (point masses, primitive solids,
//! triangle meshes, compounds of parts), principal axes, Steiner, validity, and the 6x6 spatial
//! inertia `G`.

mod inertia;
mod spatial_inertia;

pub use inertia::{RotationalInertia, DEFAULT_INERTIA_TOLERANCE};
pub use spatial_inertia::SpatialInertia;
