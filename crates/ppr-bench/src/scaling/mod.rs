//! Generated levels for the scaling measurements: families with any number of reflectors.

pub mod coverage_level;
pub mod level_family;
pub mod quad_builder;
pub mod room_maze;
