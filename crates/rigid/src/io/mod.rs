//! Reading files: triangle meshes (STL, OBJ, COLLADA), the body specs of `rigid mass` (TOML),
//! URDF robots, the collision geometry they carry ([`collision`], feature `collision`), and finding the robot files of example-robot-data ([`robots`]).

pub mod cases;
pub mod collada;
#[cfg(feature = "collision")]
pub mod collision;
pub mod constraints;
pub mod mesh_file;
pub mod robots;
pub mod spec;
pub mod urdf;
