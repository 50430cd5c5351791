//! The exact planar reflection as a technique.
