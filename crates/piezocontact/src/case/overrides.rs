//! `--set dotted.key=value` overrides, applied to the TOML document before it is read so that
//! an override is checked exactly like the file, and the line of a key for messages.

use crate::error::{Error, Result};

/// Applies one `dotted.key=value` override to the document; the value is read as TOML
/// (numbers, booleans, quoted strings, arrays) or else taken as a bare string.
pub(super) fn apply_override(doc: &mut toml_edit::DocumentMut, setting: &str) -> Result<()> {
    let (key, value) = setting.split_once('=').ok_or_else(|| {
        input!("--set {setting}: expected dotted.key=value, e.g. --set mesh.nx=192")
    })?;
    let path: Vec<&str> = key.trim().split('.').collect();
    if path.iter().any(|k| k.is_empty()) {
        return Err(input!("--set {setting}: '{key}' is not a dotted key such as solver.r"));
    }
    let value: toml_edit::Value =
        value.trim().parse().unwrap_or_else(|_| toml_edit::Value::from(value.trim()));
    let mut table = doc.as_table_mut();
    for (depth, k) in path[..path.len() - 1].iter().enumerate() {
        let entry = table.entry(k).or_insert_with(toml_edit::table);
        table = entry.as_table_mut().ok_or_else(|| {
            input!("--set {setting}: '{}' is not a table", path[..=depth].join("."))
        })?;
    }
    let last = path[path.len() - 1];
    // An override replaces the key under whichever of its spellings the file uses.
    for &(section, a, b) in ALIASES {
        if path[..path.len() - 1] == [section] && (last == a || last == b) {
            table.remove(if last == a { b } else { a });
        }
    }
    table[last] = toml_edit::value(value);
    Ok(())
}

/// Keys with two spellings (serde aliases): (table, key, alias).
const ALIASES: &[(&str, &str, &str)] = &[
    ("material", "e31", "e32"),
    ("material", "e15", "e24"),
    ("material", "beta11_rel", "beta22_rel"),
];

/// Line (1-based) of a dotted key in a TOML text.
pub fn key_line(source: &str, dotted: &str) -> Option<usize> {
    let doc = toml_edit::Document::parse(source).ok()?;
    let mut item = doc.as_item();
    let mut span = None;
    for k in dotted.split('.') {
        let table = item.as_table_like()?;
        let (key, next) = table.get_key_value(k)?;
        span = key.span().or(span);
        item = next;
    }
    span.map(|s| source[..s.start].matches('\n').count() + 1)
}
