//! SSPR: the projection hash against the exact reference and a CPU projection.
