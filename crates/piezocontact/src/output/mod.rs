//! Result files: ParaView `.vtu` ([`vtu`]), figures ([`plot`]) and safe writing ([`files`]:
//! atomic files, claimed output directories).

pub mod files;
pub mod plot;
pub mod vtu;
