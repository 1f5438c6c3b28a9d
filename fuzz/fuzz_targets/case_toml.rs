//! Fuzzes the case reader: TOML text plus `--set` overrides (the input's lines after a line
//! `---` are overrides), then validation and the problem and contact model it describes.
//! Any input must give a value or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let (toml, overrides) = text.split_once("\n---\n").unwrap_or((text, ""));
    let overrides: Vec<String> = overrides.lines().map(str::to_string).collect();
    let _ = piezocontact_cli::fuzzing::case(toml, &overrides);
});
