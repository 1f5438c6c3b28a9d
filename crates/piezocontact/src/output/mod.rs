//! Result files: ParaView `.vtu` ([`vtu`]).

pub mod vtu;
