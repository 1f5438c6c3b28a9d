//! The code's own rules, checked on its text: no function of the library is longer than 80
//! lines (tests included), and the outer loop of the contact algorithms knows no method.

use std::path::{Path, PathBuf};

/// The longest a function may be, from its `fn` line to its closing brace.
const MAX_LINES: usize = 80;

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// (name, first line, length) of every function with a body in `text`: from the `fn` line to
/// the first line that closes it at the same indentation (rustfmt's layout).
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let trimmed = line.trim_start();
        let indent = &line[..line.len() - trimmed.len()];
        let Some(rest) = ["pub fn ", "pub(crate) fn ", "pub(super) fn ", "fn "]
            .iter()
            .find_map(|p| trimmed.strip_prefix(p))
        else {
            continue;
        };
        let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        let Some(open) =
            (i..lines.len()).find(|&j| lines[j].ends_with('{') || lines[j].ends_with(';'))
        else {
            continue;
        };
        if lines[open].ends_with(';') {
            continue; // a declaration in a trait
        }
        let close = if lines[open].trim_end().ends_with('}') {
            open
        } else {
            let end = format!("{indent}}}");
            (open + 1..lines.len()).find(|&j| lines[j] == end).unwrap_or(lines.len() - 1)
        };
        found.push((name, i + 1, close - i + 1));
    }
    found
}

#[test]
fn no_function_of_the_library_is_longer_than_80_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let mut long = Vec::new();
    for file in &files {
        for (name, line, length) in functions(&std::fs::read_to_string(file).unwrap()) {
            if length > MAX_LINES {
                long.push(format!("{}:{line} {name} ({length} lines)", file.display()));
            }
        }
    }
    assert!(files.len() > 30 && long.is_empty(), "{long:#?}");
    // The checker sees long functions: one of 81 lines is caught.
    let body = "    let a = 1;\n".repeat(79);
    assert_eq!(functions(&format!("fn long() {{\n{body}}}\n")), [("long".into(), 1, 81)]);
}

#[test]
fn the_outer_loop_names_no_method() {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/algorithm/mod.rs"))
            .unwrap();
    let code: String = text
        .lines()
        .take_while(|l| !l.starts_with("#[cfg(test)]"))
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect();
    for name in ["Uzawa", "Newton", "uzawa::", "newton::", "\"uzawa\"", "\"newton\""] {
        assert!(!code.contains(name), "algorithm/mod.rs names {name}");
    }
    let (_, length) = functions(&text)
        .into_iter()
        .find(|(name, ..)| name == "solve_contact_with")
        .map(|(_, line, length)| (line, length))
        .unwrap();
    assert!(length < 60, "solve_contact_with is {length} lines");
}
