//! Serde helpers for the spatial types in rigid's files: a 3-vector as `[x, y, z]`, a 3x3 matrix
//! as row-major nested arrays `[[r00, r01, r02], …]` (docs/conventions.md: "Matrices in JSON are
//! row-major nested arrays"). Used with `#[serde(with = "…")]`.

/// `Vec3` as `[x, y, z]`.
pub(crate) mod vec3 {
    use crate::spatial::Vec3;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub(crate) fn serialize<S: Serializer>(v: &Vec3, s: S) -> Result<S::Ok, S::Error> {
        [v.x, v.y, v.z].serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec3, D::Error> {
        let [x, y, z] = <[f64; 3]>::deserialize(d)?;
        Ok(Vec3::new(x, y, z))
    }
}

/// `Mat3` as row-major `[[…], […], […]]`.
pub(crate) mod mat3 {
    use crate::spatial::Mat3;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub(crate) fn serialize<S: Serializer>(m: &Mat3, s: S) -> Result<S::Ok, S::Error> {
        let rows: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]));
        rows.serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Mat3, D::Error> {
        let rows = <[[f64; 3]; 3]>::deserialize(d)?;
        Ok(Mat3::from_fn(|r, c| rows[r][c]))
    }
}
