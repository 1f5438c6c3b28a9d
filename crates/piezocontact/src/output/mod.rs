//! Result files: ParaView `.vtu` ([`vtu`]) and safe writing ([`files`]: atomic files, claimed
//! output directories).

pub mod files;
pub mod vtu;
