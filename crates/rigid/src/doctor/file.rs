//! The doctor on a robot file of any format rigid reads, chosen by its extension: `.xml` MJCF
//! (each body's `<inertial>` against its geoms), `.sdf` SDF (each link's against its collision
//! shapes), anything else URDF. `rigid doctor` and Python's `rigid.doctor` call this.

use super::{Doctor, DoctorReport};
use crate::io::urdf::UrdfRobot;
use std::path::Path;

/// A robot file that could not be read for the doctor.
#[derive(Debug, thiserror::Error)]
pub enum DoctorFileError {
    /// The URDF.
    #[error(transparent)]
    Urdf(#[from] crate::io::urdf::UrdfError),
    /// The MJCF file.
    #[cfg(feature = "mjcf")]
    #[error(transparent)]
    Mjcf(#[from] crate::io::mjcf::MjcfError),
    /// The SDF file.
    #[cfg(feature = "collision")]
    #[error(transparent)]
    Sdf(#[from] crate::io::sdf::SdfError),
    /// A format rigid was built without (its cargo feature).
    #[error("{0}: rigid was built without this format's feature")]
    Unsupported(String),
}

/// What was read: the links as the doctor sees them, and the model, for `--fix`.
enum Read {
    Urdf,
    #[cfg(feature = "mjcf")]
    Mjcf,
    #[cfg(feature = "collision")]
    Sdf(Box<crate::io::sdf::SdfModel>),
}

/// The doctor's report on a robot file ([`examine_file`]).
pub struct FileReport {
    /// The report, one entry per link (body) with an `<inertial>`.
    pub report: DoctorReport,
    /// The file's links (bodies), as URDF links.
    pub robot: UrdfRobot,
    read: Read,
}

/// The doctor's report on the robot file at `path`, by its extension (`.xml` MJCF, `.sdf` SDF,
/// else URDF).
///
/// # Errors
/// The file cannot be read or parsed.
pub fn examine_file(path: &Path) -> Result<FileReport, DoctorFileError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let (robot, read) = match ext.as_deref() {
        #[cfg(feature = "mjcf")]
        Some("xml") => {
            let m = crate::io::mjcf::load_mjcf(path)?;
            (super::as_robot(&m), Read::Mjcf)
        }
        #[cfg(feature = "collision")]
        Some("sdf") => {
            let m = crate::io::sdf::load_sdf(path)?;
            (super::sdf_as_robot(&m), Read::Sdf(Box::new(m)))
        }
        #[cfg(not(all(feature = "mjcf", feature = "collision")))]
        Some(e @ ("xml" | "sdf")) => return Err(DoctorFileError::Unsupported(format!(".{e}"))),
        _ => (crate::io::urdf::parse_urdf_file(path)?, Read::Urdf),
    };
    let report = Doctor::new().examine(&robot);
    Ok(FileReport {
        report,
        robot,
        read,
    })
}

impl FileReport {
    /// The file's text (`text`, as read from the path examined) with only the repaired
    /// `<inertial>` elements rewritten, in its own format, each after a comment saying what was
    /// done and why; and the notes (a repaired body in an included file, left alone; MJCF's
    /// `inertiafromgeom`).
    ///
    /// # Errors
    /// The text is not XML.
    pub fn fixed(&self, text: &str) -> Result<(String, Vec<String>), String> {
        match &self.read {
            Read::Urdf => Ok((
                super::fixed_urdf(text, &self.robot, &self.report),
                Vec::new(),
            )),
            #[cfg(feature = "mjcf")]
            Read::Mjcf => super::fixed_mjcf(text, &self.report),
            #[cfg(feature = "collision")]
            Read::Sdf(m) => super::fixed_sdf(text, m, &self.report),
        }
    }
}
