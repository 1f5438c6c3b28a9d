//! Result files: ParaView `.vtu` and `.pvd` ([`vtu`]) with the contact fields ([`fields`]),
//! figures drawn from the data they show ([`plot`]), and safe writing ([`files`]: atomic
//! files, claimed output directories).

pub mod fields;
pub mod files;
pub mod plot;
pub mod vtu;
