//! Robots standing on the ground.
