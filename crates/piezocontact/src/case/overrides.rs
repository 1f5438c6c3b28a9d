//! Overrides `dotted.key=value` (the command line's `--set`, the Python package's dict),
//! applied to the TOML document before it is read so that an override is checked exactly
//! like the file, and the line of a key for messages.

use crate::error::Result;

/// Applies one `dotted.key=value` override to the document; the value is read as TOML
/// (numbers, booleans, quoted strings, arrays, tables) or else taken as a bare string. A table
/// given as the value sets the keys it names and keeps the others: `solver={eps=1e-6}` is
/// `solver.eps=1e-6`, not a `[solver]` table emptied of its other keys.
pub(super) fn apply_override(doc: &mut toml_edit::DocumentMut, setting: &str) -> Result<()> {
    let (key, value) = setting.split_once('=').ok_or_else(|| {
        input!("the override {setting}: expected dotted.key=value, e.g. mesh.nx=192")
    })?;
    let path: Vec<String> = key.trim().split('.').map(str::to_string).collect();
    if path.iter().any(|k| k.is_empty()) {
        return Err(input!("the override {setting}: '{key}' is not a dotted key such as solver.r"));
    }
    let value: toml_edit::Value =
        value.trim().parse().unwrap_or_else(|_| toml_edit::Value::from(value.trim()));
    set(doc, &path, value, setting)
}

/// Sets `value` at `path`; a table sets each of its keys in the table at `path`.
fn set(
    doc: &mut toml_edit::DocumentMut,
    path: &[String],
    mut value: toml_edit::Value,
    setting: &str,
) -> Result<()> {
    value.decor_mut().clear();
    if let toml_edit::Value::InlineTable(inline) = value {
        table_at(doc, path, setting)?;
        for (key, value) in inline {
            set(doc, &[path, &[key]].concat(), value, setting)?;
        }
        return Ok(());
    }
    let (last, parents) = path.split_last().expect("a dotted key is not empty");
    let table = table_at(doc, parents, setting)?;
    // An override replaces the key under whichever of its spellings the file uses.
    for &(section, a, b) in ALIASES {
        if parents == [section] && (last == a || last == b) {
            table.remove(if last == a { b } else { a });
        }
    }
    table.insert(last, toml_edit::value(value));
    Ok(())
}

/// The table at `path`, made where missing (inline inside an inline table).
fn table_at<'d>(
    doc: &'d mut toml_edit::DocumentMut,
    path: &[String],
    setting: &str,
) -> Result<&'d mut dyn toml_edit::TableLike> {
    let mut item = doc.as_item_mut();
    for (depth, key) in path.iter().enumerate() {
        let made = if item.is_inline_table() {
            toml_edit::Item::Value(toml_edit::InlineTable::new().into())
        } else {
            toml_edit::table()
        };
        let table = item.as_table_like_mut().expect("checked below when made or met");
        item = table.entry(key).or_insert(made);
        if !item.is_table_like() {
            let key = path[..=depth].join(".");
            return Err(input!("the override {setting}: '{key}' is not a table"));
        }
    }
    Ok(item.as_table_like_mut().expect("the root, or checked in the loop"))
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
