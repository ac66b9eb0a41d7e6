//! Reading files: triangle meshes (STL, OBJ, COLLADA), the body specs of `rigid mass` (TOML),
//! URDF robots, MuJoCo's MJCF models, constraint files, and finding the robot files of
//! example-robot-data ([`robots`]).

pub mod cases;
pub mod collada;
pub mod constraints;
pub mod mesh_file;
pub mod mjcf;
pub mod robots;
pub mod spec;
pub mod urdf;
