//! The robot simulator's `--plot` figure: joint angles, joint velocities, torques and total
//! energy against time (one panel each).

use crate::plotting::{color, save, Panel};
use plotters::style::BLACK;
use rigid::multibody::Model;
use std::path::Path;

/// Decimated time series of the 1-dof joints (and the energy).
pub struct Samples {
    names: Vec<String>,
    /// `(index in q, index in v)` of each 1-dof joint.
    dofs: Vec<(usize, usize)>,
    t: Vec<f64>,
    q: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    tau: Vec<Vec<f64>>,
    energy: Vec<f64>,
}

impl Samples {
    /// Empty series for the 1-dof joints of `model`.
    pub fn new(model: &Model) -> Self {
        let joints: Vec<_> = model
            .joints()
            .iter()
            .filter(|j| j.nq == 1 && j.nv == 1)
            .collect();
        let n = joints.len();
        Self {
            names: joints.iter().map(|j| j.name.clone()).collect(),
            dofs: joints.iter().map(|j| (j.idx_q, j.idx_v)).collect(),
            t: Vec::new(),
            q: vec![Vec::new(); n],
            v: vec![Vec::new(); n],
            tau: vec![Vec::new(); n],
            energy: Vec::new(),
        }
    }

    /// Records one state.
    pub fn push(&mut self, _model: &Model, t: f64, q: &[f64], v: &[f64], tau: &[f64], energy: f64) {
        self.t.push(t);
        for (k, &(iq, iv)) in self.dofs.iter().enumerate() {
            self.q[k].push(q[iq]);
            self.v[k].push(v[iv]);
            self.tau[k].push(tau[iv]);
        }
        self.energy.push(energy);
    }

    fn curves(&self, x: &[Vec<f64>]) -> Vec<(String, Vec<f64>, plotters::style::RGBColor)> {
        x.iter()
            .enumerate()
            .map(|(k, y)| (self.names[k].clone(), y.clone(), color(k)))
            .collect()
    }

    /// Draws the four panels into `path` (SVG or PNG).
    pub fn draw(&self, path: &Path) -> Result<(), String> {
        let panels = [
            Panel {
                title: "joint positions (1-dof joints)".into(),
                y_label: "q (rad or m)".into(),
                curves: self.curves(&self.q),
            },
            Panel {
                title: "joint velocities".into(),
                y_label: "v (rad/s or m/s)".into(),
                curves: self.curves(&self.v),
            },
            Panel {
                title: "control torques".into(),
                y_label: "τ (N·m or N)".into(),
                curves: self.curves(&self.tau),
            },
            Panel {
                title: "total energy K + U".into(),
                y_label: "E (J)".into(),
                curves: vec![(String::new(), self.energy.clone(), BLACK)],
            },
        ];
        save(path, &self.t, &panels)
    }
}
