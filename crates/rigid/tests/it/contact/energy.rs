//! Kinetic energy is never made by a contact.
