//! Kinetic energy is never made by a contact: tumbling boxes and balls thrown at the ground,
//! with and without restitution, the contact impulses' `ΔK` checked at every step
//! (`ContactStats::kinetic_change`) and the energy they took since the start
//! (`Simulator::contact_dissipation`).

use super::*;
use rigid::spatial::so3;

/// A small deterministic generator (xorshift), numbers in [-1, 1].
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn vec3(&mut self, scale: f64) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * scale
    }
}

/// Twelve throws of `n` bodies (a flat box, a ball, a cube, in turn) at random orientations and
/// twists onto the ground, restitution 0, 0.5 and 1 in turn, 1.5 s each: returns the steps with
/// a contact and the largest `ΔK` of a step without restitution; panics if the contacts ever
/// gave energy or the state is not finite.
fn throws(n: usize, spin: f64) -> (usize, f64) {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut worst_gain = f64::NEG_INFINITY;
    let mut impacts = 0;
    for case in 0..12 {
        let e = [0.0, 0.5, 1.0][case % 3];
        let kinds = [
            Free::cube(1.0 + rng.next().abs() * 4.0, Vec3::new(0.3, 0.2, 0.1)),
            Free::ball(0.5 + rng.next().abs(), 0.08),
            Free::cube(2.0, Vec3::new(0.15, 0.15, 0.15)),
        ];
        let bodies: Vec<Free> = (0..n).map(|i| kinds[(case + i) % 3].clone()).collect();
        let mut ground = Ground::horizontal(0.0, 0.2 + rng.next().abs());
        ground.restitution = e;
        let (model, mut cm) = scene(&bodies, Vec3::new(0.0, 0.0, -G), Some(ground));
        cm.restitution = e;
        let (mut q0, mut v0) = (Vec::new(), Vec::new());
        for i in 0..n {
            let p = Vec3::new(
                0.4 * i as f64,
                0.05 * rng.next(),
                0.3 + 0.1 * rng.next().abs(),
            );
            q0.extend(q_of(p, &so3::exp(&rng.vec3(3.0))));
            v0.extend(rng.vec3(spin).iter());
            v0.extend(rng.vec3(2.0).iter());
        }
        let mut sim = simulator(&model, cm, &q0, &v0, 1e-3);
        for _ in 0..1500 {
            if let Err(err) = sim.step() {
                panic!("case {case} (e = {e}): {err}");
            }
            let s = sim.contact_stats();
            if e == 0.0 {
                // no rebound: no step's impulses give energy
                worst_gain = worst_gain.max(s.kinetic_change);
            }
            impacts += usize::from(s.active > 0);
            assert!(
                sim.contact_dissipation() >= -1e-9,
                "case {case}: the contacts have given {} J",
                -sim.contact_dissipation()
            );
        }
    }
    (impacts, worst_gain)
}

#[test]
fn contacts_never_add_kinetic_energy_on_random_impacts() {
    let (impacts, worst_gain) = throws(1, 8.0);
    println!("random impacts: {impacts} steps with contact, largest ΔK of a step without restitution {worst_gain:.2e} J");
    assert!(impacts > 5000);
    assert!(worst_gain <= 1e-9, "a contact gave {worst_gain} J");
}

/// The same with three bodies in one model (three free-flyers, each meeting only the ground).
/// This diverged within 0.4–0.6 s until the Delassus rows were cleared between steps: a row
/// of `Z = L⁻ᵀ Jᵀ` kept the entries of the body it belonged to at an earlier step, which
/// coupled contacts of different bodies.
#[test]
fn contacts_never_add_kinetic_energy_with_several_bodies() {
    let (impacts, worst_gain) = throws(3, 2.0);
    assert!(impacts > 5000);
    assert!(worst_gain <= 1e-9, "a contact gave {worst_gain} J");
}
