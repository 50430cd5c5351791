//! `ppr-render`: renders a glTF level with PPR and with the exact mirrored reference.
fn main() {}
