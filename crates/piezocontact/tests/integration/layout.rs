//! The code's own rules, checked on its text: no function of the library or the command is
//! longer than 80 lines (tests included), no file of either imports a file that imports it
//! back (directly or around a cycle), and the outer loop of the contact algorithms knows no
//! method.

use std::collections::{BTreeMap, BTreeSet};
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

/// The source directories the rules hold in: the library's and the command's.
fn source_dirs() -> [PathBuf; 2] {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    [manifest.join("src"), manifest.join("../piezocontact-cli/src")]
}

#[test]
fn no_function_of_the_library_or_the_command_is_longer_than_80_lines() {
    let mut files = Vec::new();
    for dir in source_dirs() {
        sources(&dir, &mut files);
    }
    let mut long = Vec::new();
    for file in &files {
        for (name, line, length) in functions(&std::fs::read_to_string(file).unwrap()) {
            if length > MAX_LINES {
                long.push(format!("{}:{line} {name} ({length} lines)", file.display()));
            }
        }
    }
    assert!(files.len() > 40 && long.is_empty(), "{long:#?}");
    // The checker sees long functions: one of 81 lines is caught.
    let body = "    let a = 1;\n".repeat(79);
    assert_eq!(functions(&format!("fn long() {{\n{body}}}\n")), [("long".into(), 1, 81)]);
}

/// A module's path in its crate: `a/b.rs` and `a/b/mod.rs` are `[a, b]`, `lib.rs` `[]`.
type Module = Vec<String>;

/// The module of the file `relative` (to the crate's src).
fn module_of(relative: &Path) -> Module {
    let mut parts: Module =
        relative.with_extension("").iter().map(|p| p.to_string_lossy().into_owned()).collect();
    if parts.last().is_some_and(|p| ["mod", "lib", "main"].contains(&p.as_str())) {
        parts.pop();
    }
    parts
}

/// The code of a file that is compiled outside tests: before its `#[cfg(test)]` module,
/// without comment lines.
fn compiled_code(text: &str) -> String {
    let end = text.find("#[cfg(test)]\nmod ").unwrap_or(text.len());
    let lines = text[..end].lines().filter(|l| !l.trim_start().starts_with("//"));
    lines.collect::<Vec<_>>().join("\n")
}

/// The leading `a::b::c` of `text` (identifiers joined by `::`).
fn leading_path(text: &str) -> Vec<String> {
    let mut path = Vec::new();
    let mut rest = text;
    loop {
        let ident: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        if ident.is_empty() {
            return path;
        }
        rest = &rest[ident.len()..];
        path.push(ident);
        match rest.strip_prefix("::") {
            Some(next) => rest = next,
            None => return path,
        }
    }
}

/// The paths a file names through `crate::` and `super::` (a `{a, b::c}` group as its
/// items), relative to the crate's root; and those of `use child::…` for the children it
/// declares.
fn named_paths(module: &Module, code: &str) -> Vec<Vec<String>> {
    let mut named = Vec::new();
    for anchor in ["crate::", "super::"] {
        for (at, _) in code.match_indices(anchor) {
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut base = if anchor == "crate::" { Vec::new() } else { module.clone() };
            let mut rest = &code[at..];
            while let Some(next) = rest.strip_prefix("super::") {
                base.pop();
                rest = next;
            }
            rest = rest.strip_prefix("crate::").unwrap_or(rest);
            let items: Vec<&str> = match rest.strip_prefix('{') {
                Some(group) => group[..group.find('}').unwrap_or(group.len())].split(',').collect(),
                None => vec![rest],
            };
            for item in items {
                named.push([base.clone(), leading_path(item.trim())].concat());
            }
        }
    }
    let children: BTreeSet<String> = code
        .lines()
        .filter_map(|l| l.trim().trim_start_matches("pub ").strip_prefix("mod "))
        .map(|l| l.trim_end_matches(';').to_string())
        .collect();
    for line in code.lines().map(str::trim) {
        let used = line.strip_prefix("pub use ").or_else(|| line.strip_prefix("use "));
        let path = used.map(leading_path).unwrap_or_default();
        if path.first().is_some_and(|first| children.contains(first)) {
            named.push([module.clone(), path].concat());
        }
    }
    named
}

/// Which modules each module imports: the longest module prefix of each path it names.
fn imports(files: &BTreeMap<Module, String>) -> BTreeMap<Module, BTreeSet<Module>> {
    let mut edges = BTreeMap::new();
    for (module, text) in files {
        let targets = named_paths(module, &compiled_code(text))
            .into_iter()
            .filter_map(|path| {
                (0..=path.len()).rev().map(|k| path[..k].to_vec()).find(|m| files.contains_key(m))
            })
            .filter(|target| target != module)
            .collect();
        edges.insert(module.clone(), targets);
    }
    edges
}

/// A cycle of imports, as the modules around it, if there is one.
fn import_cycle(edges: &BTreeMap<Module, BTreeSet<Module>>) -> Option<Vec<Module>> {
    fn visit(
        module: &Module,
        edges: &BTreeMap<Module, BTreeSet<Module>>,
        stack: &mut Vec<Module>,
        done: &mut BTreeSet<Module>,
    ) -> Option<Vec<Module>> {
        if let Some(at) = stack.iter().position(|m| m == module) {
            return Some(stack[at..].to_vec());
        }
        if !done.insert(module.clone()) {
            return None;
        }
        stack.push(module.clone());
        for target in edges.get(module).into_iter().flatten() {
            if let Some(cycle) = visit(target, edges, stack, done) {
                return Some(cycle);
            }
        }
        stack.pop();
        None
    }
    let (mut stack, mut done) = (Vec::new(), BTreeSet::new());
    edges.keys().find_map(|m| visit(m, edges, &mut stack, &mut done))
}

/// The files under `dir` by module.
fn crate_files(dir: &Path) -> BTreeMap<Module, String> {
    let mut files = Vec::new();
    sources(dir, &mut files);
    let module = |f: &PathBuf| module_of(f.strip_prefix(dir).unwrap());
    files.iter().map(|f| (module(f), std::fs::read_to_string(f).unwrap())).collect()
}

#[test]
fn no_file_imports_a_file_that_imports_it_back() {
    for dir in source_dirs() {
        let files = crate_files(&dir);
        let edges = imports(&files);
        let count: usize = edges.values().map(BTreeSet::len).sum();
        assert!(files.len() > 10 && count > 20, "{}: {count} imports", dir.display());
        let cycle = import_cycle(&edges).map(|c| c.iter().map(|m| m.join("/")).collect::<Vec<_>>());
        assert!(cycle.is_none(), "{}: an import cycle {cycle:?}", dir.display());
    }
    // The checker sees cycles: through a sibling, a group, a parent and a child's `use`.
    let files = |pairs: &[(&str, &str)]| -> BTreeMap<Module, String> {
        pairs.iter().map(|(f, t)| (module_of(Path::new(f)), t.to_string())).collect()
    };
    let cyclic = [
        files(&[
            ("lib.rs", ""),
            ("a.rs", "use crate::b::X;"),
            ("b.rs", "use crate::{c, a::Y};"),
            ("c.rs", ""),
        ]),
        files(&[
            ("lib.rs", ""),
            ("p/mod.rs", "mod q;\npub use q::X;\nfn f() {}"),
            ("p/q.rs", "use super::f;"),
        ]),
    ];
    for files in cyclic {
        assert!(import_cycle(&imports(&files)).is_some(), "{files:?}");
    }
    let acyclic = files(&[
        ("lib.rs", ""),
        ("p/mod.rs", "mod q;\nmod r;"),
        ("p/q.rs", "use super::r::Z;"),
        ("p/r.rs", ""),
    ]);
    assert!(import_cycle(&imports(&acyclic)).is_none());
}

#[test]
fn the_outer_loop_names_no_method() {
    let algorithm = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/algorithm");
    for file in ["mod.rs", "outer.rs", "hencky.rs", "inner.rs", "solution.rs"] {
        let text = std::fs::read_to_string(algorithm.join(file)).unwrap();
        let code = compiled_code(&text);
        for name in ["Uzawa", "Newton", "uzawa::", "newton::", "\"uzawa\"", "\"newton\""] {
            assert!(!code.contains(name), "algorithm/{file} names {name}");
        }
    }
    let text = std::fs::read_to_string(algorithm.join("outer.rs")).unwrap();
    let length = functions(&compiled_code(&text))
        .into_iter()
        .filter(|(name, ..)| ["solve_contact_with", "solve", "iterate"].contains(&name.as_str()))
        .map(|(_, _, length)| length)
        .collect::<Vec<_>>();
    assert!(length.len() == 3 && length.iter().all(|l| *l < 60), "{length:?}");
}
