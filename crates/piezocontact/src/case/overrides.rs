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
        if parents.first().is_some_and(|p| p == section) && (last == a || last == b) {
            table.remove(if last == a { b } else { a });
        }
    }
    table.insert(last, toml_edit::value(value));
    Ok(())
}

/// The table at `path`, made where missing (inline inside an inline table). A top-level
/// array of tables (`[[material]]`) is entered by the name of one of its tables:
/// `material.film.young`.
fn table_at<'d>(
    doc: &'d mut toml_edit::DocumentMut,
    path: &[String],
    setting: &str,
) -> Result<&'d mut dyn toml_edit::TableLike> {
    let root: &mut dyn toml_edit::TableLike = doc.as_table_mut();
    if let [first, name, tail @ ..] = path
        && root.get(first).is_some_and(toml_edit::Item::is_array_of_tables)
    {
        let array = root.get_mut(first).and_then(|i| i.as_array_of_tables_mut());
        let array = array.expect("checked to be an array of tables");
        let names: Vec<String> =
            array.iter().filter_map(|t| t.get("name")?.as_str().map(str::to_string)).collect();
        let Some(table) =
            array.iter_mut().find(|t| t.get("name").and_then(|v| v.as_str()) == Some(name))
        else {
            return Err(input!(
                "the override {setting}: no [[{first}]] is named '{name}' (the names are {})",
                names.join(", ")
            ));
        };
        return walk(table, false, tail, path.len() - tail.len(), path, setting);
    }
    walk(root, false, path, 0, path, setting)
}

/// The table at `rest` below `table` (itself inline or not), made where missing; `path` and
/// `done` (its keys before `rest`) name keys in messages.
fn walk<'d>(
    mut table: &'d mut dyn toml_edit::TableLike,
    mut inline: bool,
    rest: &[String],
    done: usize,
    path: &[String],
    setting: &str,
) -> Result<&'d mut dyn toml_edit::TableLike> {
    for (depth, key) in rest.iter().enumerate() {
        let made = if inline {
            toml_edit::Item::Value(toml_edit::InlineTable::new().into())
        } else {
            toml_edit::table()
        };
        let item = table.entry(key).or_insert(made);
        if !item.is_table_like() {
            let key = path[..=done + depth].join(".");
            let hint = if item.is_array_of_tables() {
                format!(": it is a list of [[{key}]] tables, so name one, as {key}.<name>.<key>")
            } else {
                String::new()
            };
            return Err(input!("the override {setting}: '{key}' is not a table{hint}"));
        }
        inline = item.is_inline_table();
        table = item.as_table_like_mut().expect("checked above");
    }
    Ok(table)
}

/// Keys with two spellings (serde aliases): (table, key, alias).
const ALIASES: &[(&str, &str, &str)] = &[
    ("material", "e31", "e32"),
    ("material", "e15", "e24"),
    ("material", "beta11_rel", "beta22_rel"),
];

/// Line (1-based) of a dotted key in a TOML text; a key of an array of tables names one of
/// them by its `name` (`material.film.young`).
pub fn key_line(source: &str, dotted: &str) -> Option<usize> {
    let doc = toml_edit::Document::parse(source).ok()?;
    let mut table: &dyn toml_edit::TableLike = doc.as_table();
    let mut span = None;
    let mut keys = dotted.split('.');
    while let Some(k) = keys.next() {
        let (key, next) = table.get_key_value(k)?;
        span = key.span().or(span);
        if let Some(array) = next.as_array_of_tables() {
            let Some(name) = keys.next() else { break };
            let named =
                array.iter().find(|t| t.get("name").and_then(|v| v.as_str()) == Some(name))?;
            span = named.get_key_value("name").and_then(|(key, _)| key.span()).or(span);
            table = named;
            continue;
        }
        match next.as_table_like() {
            Some(inner) => table = inner,
            None => {
                if keys.next().is_some() {
                    return None;
                }
                break;
            }
        }
    }
    span.map(|s| source[..s.start].matches('\n').count() + 1)
}
