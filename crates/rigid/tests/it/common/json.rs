//! Reading numbers out of the JSON fixtures and reference outputs.

use nalgebra::DMatrix;
use serde_json::Value;

/// A JSON array of numbers.
pub fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// A row-major JSON matrix (array of rows).
pub fn mat_of(v: &Value) -> DMatrix<f64> {
    let rows: Vec<Vec<f64>> = v.as_array().expect("array").iter().map(vec_of).collect();
    DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
}
