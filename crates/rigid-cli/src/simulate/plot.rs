//! The body simulator's `--plot` figure: body angular velocity, energy error and momentum error
//! against time.

use crate::plotting::{save, Panel};
use plotters::style::{BLACK, BLUE, GREEN, RED};
use rigid::body::{State, Summary};
use std::path::Path;

/// Decimated time series for the figure.
#[derive(Default)]
pub struct Samples {
    t: Vec<f64>,
    w: [Vec<f64>; 3],
    energy: Vec<f64>,
    momentum: Vec<f64>,
}

impl Samples {
    /// Records the state at `t`, with the signed relative energy error and the relative
    /// angular-momentum error of `s`.
    pub fn push(&mut self, t: f64, x: &State, s: &Summary) {
        self.t.push(t);
        for (k, w) in self.w.iter_mut().enumerate() {
            w.push(x.twist.w[k]);
        }
        let scale = s.energy0.abs().max(s.kinetic0.abs());
        let de = s.energy - s.energy0;
        self.energy.push(if scale > 0.0 { de / scale } else { de });
        self.momentum.push(s.relative_momentum_error());
    }
}

/// Draws the three panels into `path` (SVG or PNG).
pub fn draw(path: &Path, s: &Samples) -> Result<(), String> {
    let panels = [
        Panel {
            title: "body angular velocity".into(),
            y_label: "ω (rad/s)".into(),
            curves: vec![
                ("ωx".into(), s.w[0].clone(), RED),
                ("ωy".into(), s.w[1].clone(), GREEN),
                ("ωz".into(), s.w[2].clone(), BLUE),
            ],
        },
        Panel {
            title: "relative energy error (E - E₀)/E₀".into(),
            y_label: "1".into(),
            curves: vec![(String::new(), s.energy.clone(), BLACK)],
        },
        Panel {
            title: "relative angular momentum error |L - L₀|/|L₀|".into(),
            y_label: "1".into(),
            curves: vec![(String::new(), s.momentum.clone(), BLACK)],
        },
    ];
    save(path, &s.t, &panels)
}
