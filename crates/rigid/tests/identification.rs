//! The regressor, the base parameters and least squares on the built-in robots and random trees.

mod common;
use rigid::identification::*;
use rigid::multibody::*;

#[test]
fn scratch() {
    for name in builtin_names() {
        let model = builtin(name).unwrap();
        let base = BaseParameters::of_model(&model, JointTerms::default(), 1).unwrap();
        println!("{name}: {} base of {}\n{base}", base.len(), 10 * model.njoints());
    }
}
