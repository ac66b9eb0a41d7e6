//! Mechanics.
