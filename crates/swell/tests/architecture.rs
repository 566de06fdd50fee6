//! Issue 33: the library's layers, and docs/ARCHITECTURE.md checked against the tree, so neither can
//! drift (as `readme_example.rs` does for the README's example).
//!
//! - **Layers.** docs/ARCHITECTURE.md's import table lists the top-level modules in layer order (its
//!   rows, the first the bottom layer). Non-test code of a module may refer (`crate::x` in `use` lines, grouped
//!   `use crate::{a::B, c::D}`, inline paths, `super::` chains up to the crate root, `$crate::` in
//!   macros) only to modules in rows before its own. [`KNOWN_UPWARD`] lists the exceptions still
//!   being removed.
//! - **Import table.** Each row's "imports from" is exactly the set of modules its code refers to.
//! - **Module map.** The map names every source file of the library, the CLI and the viewer once,
//!   and every path it names exists.
//!
//! Test code is left out: items under `#[cfg(test)]` (or `#[cfg(all(test, ...))]`), `#[test]`
//! functions and the files of test modules declared out of line (`water/fft_ocean/tests.rs`), as
//! are comments, doc comments and string literals. A hand-written scanner, std only.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Upward imports, as (from, to) top-level modules, that the layer check accepts: none (issue 33
/// removed the last, `scene` -> `shading`). The test fails on an entry that is no longer needed,
/// so the list cannot outlive its imports.
const KNOWN_UPWARD: &[(&str, &str)] = &[];

/// The crates whose source files the module map must name, each exactly once.
const MAPPED_SOURCE_DIRS: &[&str] = &["crates/swell/src", "crates/swell-cli/src", "crates/swell-viewer/src"];

/// The library's source directory, relative to the workspace root.
const LIB_SRC: &str = "crates/swell/src";

const DOC: &str = "docs/ARCHITECTURE.md";

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every `.rs` file under `dir` (relative to the root), as paths relative to the root with `/`.
fn rust_files(root: &Path, dir: &str) -> Vec<String> {
    fn walk(root: &Path, dir: &str, out: &mut Vec<String>) {
        let entries = std::fs::read_dir(root.join(dir)).unwrap_or_else(|e| panic!("reading {dir}: {e}"));
        for entry in entries {
            let entry = entry.unwrap();
            let name = entry.file_name().into_string().unwrap();
            let path = format!("{dir}/{name}");
            if entry.file_type().unwrap().is_dir() {
                walk(root, &path, out);
            } else if name.ends_with(".rs") {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(root, dir, &mut out);
    out.sort();
    out
}

// ---------------------------------------------------------------------------------------------
// Scanner

fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_' || b >= 0x80
}

/// The source with comments (line, block, doc) and string, byte-string, raw-string and char
/// literals replaced by spaces. Newlines are kept, so byte offsets and line numbers are the
/// source's.
fn blank_comments_and_literals(src: &str) -> Vec<u8> {
    let s = src.as_bytes();
    let mut out = s.to_vec();
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for b in &mut out[from..to.min(s.len())] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    };
    let mut i = 0;
    while i < s.len() {
        let prev_ident = i > 0 && is_ident_byte(s[i - 1]);
        match s[i] {
            b'/' if s.get(i + 1) == Some(&b'/') => {
                let end = s[i..].iter().position(|&b| b == b'\n').map_or(s.len(), |p| i + p);
                blank(&mut out, i, end);
                i = end;
            }
            b'/' if s.get(i + 1) == Some(&b'*') => {
                let (mut depth, mut j) = (1, i + 2);
                while j < s.len() && depth > 0 {
                    if s[j] == b'/' && s.get(j + 1) == Some(&b'*') {
                        depth += 1;
                        j += 2;
                    } else if s[j] == b'*' && s.get(j + 1) == Some(&b'/') {
                        depth -= 1;
                        j += 2;
                    } else {
                        j += 1;
                    }
                }
                blank(&mut out, i, j);
                i = j;
            }
            b'r' if (!prev_ident || (s[i - 1] == b'b' && (i < 2 || !is_ident_byte(s[i - 2]))))
                && matches!(s.get(i + 1), Some(b'"') | Some(b'#')) =>
            {
                // A raw string r"..." or r#"..."# (br"..." too: the b is left as an identifier).
                let hashes = s[i + 1..].iter().take_while(|&&b| b == b'#').count();
                if s.get(i + 1 + hashes) != Some(&b'"') {
                    i += 1; // r#ident
                    continue;
                }
                let close: Vec<u8> = std::iter::once(b'"').chain(std::iter::repeat_n(b'#', hashes)).collect();
                let body = i + 2 + hashes;
                let end = s[body..]
                    .windows(close.len())
                    .position(|w| w == close.as_slice())
                    .map_or(s.len(), |p| body + p + close.len());
                blank(&mut out, i + 1, end);
                i = end;
            }
            b'"' => {
                let mut j = i + 1;
                while j < s.len() && s[j] != b'"' {
                    j += if s[j] == b'\\' { 2 } else { 1 };
                }
                blank(&mut out, i, j + 1);
                i = j + 1;
            }
            b'\'' => {
                if s.get(i + 1) == Some(&b'\\') {
                    // '\n', '\'', '\u{..}'
                    let mut j = i + 3;
                    while j < s.len() && s[j] != b'\'' {
                        j += 1;
                    }
                    blank(&mut out, i, j + 1);
                    i = j + 1;
                } else {
                    // 'x' (a char, possibly several bytes long) or a lifetime / label 'a.
                    let len = src[i + 1..].chars().next().map_or(0, char::len_utf8);
                    if len > 0 && s.get(i + 1 + len) == Some(&b'\'') {
                        blank(&mut out, i, i + 2 + len);
                        i += 2 + len;
                    } else {
                        i += 1;
                    }
                }
            }
            _ => i += 1,
        }
    }
    out
}

/// The index just past the bracket matching the one at `open` (`(`, `[` or `{`).
fn matching_close(code: &[u8], open: usize) -> usize {
    let mut depth = 0i32;
    for (j, &b) in code.iter().enumerate().skip(open) {
        match b {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => {
                depth -= 1;
                if depth == 0 {
                    return j + 1;
                }
            }
            _ => {}
        }
    }
    code.len()
}

fn skip_ws(code: &[u8], mut i: usize) -> usize {
    while i < code.len() && code[i].is_ascii_whitespace() {
        i += 1;
    }
    i
}

fn ident_at(code: &[u8], i: usize) -> Option<&str> {
    if i >= code.len() || !is_ident_byte(code[i]) || code[i].is_ascii_digit() {
        return None;
    }
    let end = code[i..].iter().position(|&b| !is_ident_byte(b)).map_or(code.len(), |p| i + p);
    std::str::from_utf8(&code[i..end]).ok()
}

/// Whether an attribute's text (between `#[` and `]`) makes its item test-only: `test`,
/// `cfg(test)` or `cfg(all(..., test, ...))`.
fn attribute_is_test_only(attr: &str) -> bool {
    let a: String = attr.chars().filter(|c| !c.is_whitespace()).collect();
    if a == "test" || a == "cfg(test)" {
        return true;
    }
    if let Some(args) = a.strip_prefix("cfg(all(").and_then(|r| r.strip_suffix("))")) {
        let mut depth = 0;
        let mut parts = vec![String::new()];
        for c in args.chars() {
            match c {
                '(' => depth += 1,
                ')' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(String::new());
                    continue;
                }
                _ => {}
            }
            parts.last_mut().unwrap().push(c);
        }
        return parts.iter().any(|p| p == "test");
    }
    false
}

/// Blanks every test-only item of `code` (the attribute, any further attributes and the item up
/// to its `;` or its closing brace). Returns the names of test-only modules declared out of line
/// (`#[cfg(test)] mod tests;`).
fn blank_test_items(code: &mut [u8]) -> Vec<String> {
    let mut out_of_line = Vec::new();
    let mut i = 0;
    while i + 1 < code.len() {
        if !(code[i] == b'#' && code[i + 1] == b'[') {
            i += 1;
            continue;
        }
        let attr_end = matching_close(code, i + 1);
        let attr = String::from_utf8_lossy(&code[i + 2..attr_end - 1]).into_owned();
        if !attribute_is_test_only(&attr) {
            i = attr_end;
            continue;
        }
        // Skip further attributes, then the item: to `;` or the end of its first `{...}` at depth 0.
        let mut j = skip_ws(code, attr_end);
        while j + 1 < code.len() && code[j] == b'#' && code[j + 1] == b'[' {
            j = skip_ws(code, matching_close(code, j + 1));
        }
        let item_start = j;
        let mut end = code.len();
        while j < code.len() {
            match code[j] {
                b';' => {
                    end = j + 1;
                    break;
                }
                b'{' => {
                    end = matching_close(code, j);
                    break;
                }
                b'(' | b'[' => j = matching_close(code, j),
                _ => j += 1,
            }
        }
        let item = String::from_utf8_lossy(&code[item_start..end]).into_owned();
        let words: Vec<&str> =
            item.split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ';')).filter(|w| !w.is_empty()).collect();
        if let Some(pos) = words.iter().position(|w| *w == "mod") {
            if let Some(name) = words.get(pos + 1).and_then(|w| w.strip_suffix(';')) {
                out_of_line.push(name.to_string());
            }
        }
        for b in &mut code[i..end] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
        i = end;
    }
    out_of_line
}

/// A library source file with its test code and comments blanked.
struct SourceFile {
    /// Relative to the workspace root, e.g. `crates/swell/src/world/world.rs`.
    path: String,
    /// The module path, e.g. `["world", "world"]`; empty for lib.rs.
    module: Vec<String>,
    code: Vec<u8>,
}

/// The module path of a file under `LIB_SRC` (`scene/mod.rs` is `scene`, `lib.rs` the root).
fn module_path(path: &str) -> Vec<String> {
    let rel = path.strip_prefix(LIB_SRC).unwrap().trim_start_matches('/').trim_end_matches(".rs");
    let mut parts: Vec<String> = rel.split('/').map(str::to_string).collect();
    if matches!(parts.last().map(String::as_str), Some("mod") | Some("lib")) {
        parts.pop();
    }
    parts
}

/// The library's non-test source files, blanked.
fn library_sources(root: &Path) -> Vec<SourceFile> {
    let mut files: Vec<SourceFile> = rust_files(root, LIB_SRC)
        .into_iter()
        .map(|path| {
            let src = std::fs::read_to_string(root.join(&path)).unwrap();
            SourceFile { module: module_path(&path), code: blank_comments_and_literals(&src), path }
        })
        .collect();
    // Files of out-of-line test modules, and everything below them.
    let mut test_modules: Vec<Vec<String>> = Vec::new();
    for f in &mut files {
        for name in blank_test_items(&mut f.code) {
            let mut m = f.module.clone();
            m.push(name);
            test_modules.push(m);
        }
    }
    // A file that declares itself test-only (`#![cfg(test)]`) counts as a test module too.
    for f in &files {
        let code: String = String::from_utf8_lossy(&f.code).chars().filter(|c| !c.is_whitespace()).collect();
        if code.contains("#![cfg(test)]") {
            test_modules.push(f.module.clone());
        }
    }
    files.retain(|f| !test_modules.iter().any(|t| f.module.starts_with(t)));
    files
}

/// One reference from a top-level module to another.
#[derive(Clone, Debug)]
struct Import {
    path: String,
    line: usize,
    from: String,
    to: String,
    /// The path as written up to the module, e.g. `crate::shading`.
    text: String,
}

/// What the crate root (lib.rs) knows: its modules, and which module each name it re-exports or
/// each `#[macro_export]` macro comes from.
struct CrateRoot {
    modules: Vec<String>,
    names: BTreeMap<String, String>,
}

fn crate_root(files: &[SourceFile]) -> CrateRoot {
    let lib = files.iter().find(|f| f.module.is_empty()).expect("lib.rs");
    let words = |code: &[u8]| -> Vec<String> {
        String::from_utf8_lossy(code)
            .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ';' || c == '!'))
            .filter(|w| !w.is_empty())
            .map(str::to_string)
            .collect()
    };
    let lib_words = words(&lib.code);
    let mut modules = Vec::new();
    let mut names = BTreeMap::new();
    for (k, w) in lib_words.iter().enumerate() {
        if w == "mod" {
            if let Some(m) = lib_words.get(k + 1).and_then(|m| m.strip_suffix(';')) {
                modules.push(m.to_string());
            }
        }
    }
    // `pub use m::{A, B};` and `pub use m::A;`: every later word of the statement comes from m.
    let text = String::from_utf8_lossy(&lib.code).into_owned();
    for stmt in text.split(';') {
        let Some(at) = stmt.find("pub use ") else { continue };
        let rest = &stmt[at + "pub use ".len()..];
        let ws = words(rest.as_bytes());
        if let Some(m) = ws.first().filter(|m| modules.contains(m)) {
            for w in &ws[1..] {
                if w != "as" && w != "self" {
                    names.insert(w.clone(), m.clone());
                }
            }
        }
    }
    // `#[macro_export] macro_rules! name` anywhere: `crate::name!` is that module's.
    for f in files.iter().filter(|f| !f.module.is_empty()) {
        let ws = words(&f.code);
        for (k, w) in ws.iter().enumerate() {
            if w == "macro_rules!" && k >= 1 && ws[..k].iter().rev().take(2).any(|p| p == "macro_export") {
                names.insert(ws[k + 1].clone(), f.module[0].clone());
            }
        }
    }
    CrateRoot { modules, names }
}

fn line_of(code: &[u8], i: usize) -> usize {
    1 + code[..i].iter().filter(|&&b| b == b'\n').count()
}

/// The first identifiers of the comma-separated entries of the group `{...}` opening at `open`,
/// with their offsets.
fn group_heads(code: &[u8], open: usize) -> Vec<(usize, String)> {
    let close = matching_close(code, open) - 1;
    let mut heads = Vec::new();
    let mut at_start = true;
    let mut depth = 0;
    let mut j = open + 1;
    while j < close {
        match code[j] {
            b'{' | b'(' | b'[' => depth += 1,
            b'}' | b')' | b']' => depth -= 1,
            b',' if depth == 0 => at_start = true,
            _ if at_start && depth == 0 => {
                if let Some(id) = ident_at(code, j) {
                    heads.push((j, id.to_string()));
                    at_start = false;
                    j += id.len();
                    continue;
                }
            }
            _ => {}
        }
        j += 1;
    }
    heads
}

/// Every reference of the file to another top-level module.
fn imports_of(file: &SourceFile, root: &CrateRoot) -> Vec<Import> {
    let code = &file.code;
    let from = &file.module[0];
    let mut found = Vec::new();
    // Inline `mod name { ... }` blocks, for `super::` chains: (module, brace depth inside it).
    let mut inline: Vec<usize> = Vec::new();
    let mut brace_depth = 0usize;
    let resolve = |at: usize, segment: &str, text: String, found: &mut Vec<Import>| {
        let to = if root.modules.iter().any(|m| m == segment) {
            Some(segment.to_string())
        } else {
            root.names.get(segment).cloned()
        };
        // Otherwise an item defined in lib.rs itself (`crate::GRAVITY`): the crate root, below
        // every module.
        if let Some(to) = to.filter(|to| to != from) {
            found.push(Import { path: file.path.clone(), line: line_of(code, at), from: from.clone(), to, text });
        }
    };
    let mut i = 0;
    while i < code.len() {
        match code[i] {
            b'{' => {
                brace_depth += 1;
                i += 1;
                continue;
            }
            b'}' => {
                if inline.last() == Some(&brace_depth) {
                    inline.pop();
                }
                brace_depth = brace_depth.saturating_sub(1);
                i += 1;
                continue;
            }
            _ => {}
        }
        if (i > 0 && is_ident_byte(code[i - 1])) || !is_ident_byte(code[i]) {
            i += 1;
            continue;
        }
        let Some(word) = ident_at(code, i) else {
            i += 1;
            continue;
        };
        let after = i + word.len();
        let path_follows = |k: usize| {
            let k = skip_ws(code, k);
            (code.get(k) == Some(&b':') && code.get(k + 1) == Some(&b':')).then(|| skip_ws(code, k + 2))
        };
        let prev = code[..i].iter().rposition(|b| !b.is_ascii_whitespace());
        let continues_path = prev.is_some_and(|p| p >= 1 && code[p] == b':' && code[p - 1] == b':');
        match word {
            "mod" => {
                let k = skip_ws(code, after);
                if let Some(name) = ident_at(code, k) {
                    if code.get(skip_ws(code, k + name.len())) == Some(&b'{') {
                        inline.push(brace_depth + 1);
                    }
                }
            }
            "crate" if !continues_path => {
                if let Some(k) = path_follows(after) {
                    let dollar = if i > 0 && code[i - 1] == b'$' { "$" } else { "" };
                    if code.get(k) == Some(&b'{') {
                        for (at, head) in group_heads(code, k) {
                            resolve(at, &head, format!("{dollar}crate::{{{head}::..}}"), &mut found);
                        }
                    } else if let Some(seg) = ident_at(code, k) {
                        resolve(k, seg, format!("{dollar}crate::{seg}"), &mut found);
                    }
                }
            }
            "super" if !continues_path => {
                // Count the chain; it escapes the top-level module when it climbs to the root.
                let (mut n, mut k) = (1, path_follows(after));
                while let Some(at) = k {
                    if ident_at(code, at) == Some("super") {
                        n += 1;
                        k = path_follows(at + 5);
                    } else {
                        break;
                    }
                }
                // `super` inside a file's own module climbs from the file's parent.
                let depth = file.module.len() + inline.len();
                if let (Some(k), true) = (k, n >= depth) {
                    let text = "super::".repeat(n);
                    if code.get(k) == Some(&b'{') {
                        for (at, head) in group_heads(code, k) {
                            resolve(at, &head, format!("{text}{{{head}::..}}"), &mut found);
                        }
                    } else if let Some(seg) = ident_at(code, k) {
                        resolve(k, seg, format!("{text}{seg}"), &mut found);
                    }
                }
            }
            _ => {}
        }
        i = after;
    }
    found
}

/// Every reference between top-level modules in the library's non-test code.
fn library_imports(root_dir: &Path) -> (CrateRoot, Vec<Import>) {
    let files = library_sources(root_dir);
    let root = crate_root(&files);
    let imports = files.iter().filter(|f| !f.module.is_empty()).flat_map(|f| imports_of(f, &root)).collect();
    (root, imports)
}

// ---------------------------------------------------------------------------------------------
// docs/ARCHITECTURE.md

/// One row of the import table: the module, what it imports, the doc's line.
struct Row {
    module: String,
    imports: BTreeSet<String>,
    line: usize,
}

/// The import table: the first table whose header starts `| module | imports from |`. Its rows
/// are in layer order, lowest first.
fn import_table(doc: &str) -> Result<Vec<Row>, String> {
    let lines: Vec<&str> = doc.lines().collect();
    let cells =
        |l: &str| -> Vec<String> { l.trim().trim_matches('|').split('|').map(|c| c.trim().to_string()).collect() };
    let start = lines
        .iter()
        .position(|l| {
            let c = cells(l);
            l.trim_start().starts_with('|') && c.len() >= 2 && c[0] == "module" && c[1] == "imports from"
        })
        .ok_or(format!("{DOC}: no import table (a table whose header is `| module | imports from | ...`)"))?;
    let mut rows = Vec::new();
    for (k, l) in lines.iter().enumerate().skip(start + 2) {
        if !l.trim_start().starts_with('|') {
            break;
        }
        let line = k + 1;
        let c = cells(l);
        let module = c[0]
            .strip_prefix('`')
            .and_then(|m| m.strip_suffix('`'))
            .filter(|m| !m.contains('`'))
            .ok_or(format!("{DOC}:{line}: import table: the module cell must be one `name`, found {:?}", c[0]))?;
        let mut imports = BTreeSet::new();
        if c.get(1).map(String::as_str) != Some("nothing") {
            for part in c.get(1).map_or("", String::as_str).split(',') {
                let name = part.trim().strip_prefix('`').and_then(|m| m.strip_suffix('`')).ok_or(format!(
                    "{DOC}:{line}: import table: \"imports from\" must be `name`s separated by commas, or nothing; found {:?}",
                    c.get(1)
                ))?;
                imports.insert(name.to_string());
            }
        }
        rows.push(Row { module: module.to_string(), imports, line });
    }
    Ok(rows)
}

/// One path the module map names, relative to the workspace root (directories end in `/`).
struct MapEntry {
    path: String,
    line: usize,
}

/// The module map: the first ```text block after `## Module map`. An entry is a line's first word,
/// a path relative to the directory entry it is indented under by two spaces (top-level entries,
/// at no indentation, are relative to the workspace root); a directory ends in `/`. A line
/// indented further than two spaces past the directory it is under continues the previous
/// entry's description.
fn module_map(doc: &str) -> Result<Vec<MapEntry>, String> {
    let lines: Vec<&str> = doc.lines().collect();
    let heading = lines.iter().position(|l| l.trim() == "## Module map").ok_or(format!("{DOC}: no `## Module map`"))?;
    let open = heading
        + lines[heading..]
            .iter()
            .position(|l| l.trim() == "```text")
            .ok_or(format!("{DOC}: the module map has no ```text block"))?;
    let mut entries = Vec::new();
    let mut dirs: Vec<(usize, String)> = Vec::new(); // (indentation, path)
    for (k, l) in lines.iter().enumerate().skip(open + 1) {
        let line = k + 1;
        if l.trim() == "```" {
            return Ok(entries);
        }
        if l.trim().is_empty() {
            continue;
        }
        let indent = l.len() - l.trim_start().len();
        while dirs.last().is_some_and(|(d, _)| *d >= indent) {
            dirs.pop();
        }
        let parent = match dirs.last() {
            None if indent == 0 => String::new(),
            None => return Err(format!("{DOC}:{line}: module map: an indented line under no directory")),
            Some((d, _)) if indent > d + 2 => continue, // a description's continuation
            Some((d, p)) if indent == d + 2 => p.clone(),
            Some((d, p)) => {
                return Err(format!(
                    "{DOC}:{line}: module map: indented {indent} under {p} (at {d}): entries go 2 spaces in, continuations further"
                ))
            }
        };
        let word = l.split_whitespace().next().unwrap();
        if word.contains('*') {
            return Err(format!("{DOC}:{line}: module map: {word}: name each file, not a pattern"));
        }
        let path = format!("{parent}{word}");
        if word.ends_with('/') {
            dirs.push((indent, path.clone()));
        }
        entries.push(MapEntry { path, line });
    }
    Err(format!("{DOC}: the module map's ```text block is not closed"))
}

// ---------------------------------------------------------------------------------------------
// The checks

/// The layer check and the import table's truth, as failure messages.
fn import_failures(doc: &str, root: &CrateRoot, imports: &[Import], known_upward: &[(&str, &str)]) -> Vec<String> {
    let rows = match import_table(doc) {
        Ok(rows) => rows,
        Err(e) => return vec![e],
    };
    let mut failures = Vec::new();
    let mut rank: BTreeMap<&str, usize> = BTreeMap::new();
    for (k, row) in rows.iter().enumerate() {
        if !root.modules.contains(&row.module) {
            failures.push(format!(
                "{DOC}:{}: import table: `{}` is not a module of crates/swell/src/lib.rs",
                row.line, row.module
            ));
        }
        if rank.insert(&row.module, k).is_some() {
            failures.push(format!("{DOC}:{}: import table: `{}` has two rows", row.line, row.module));
        }
    }
    for m in &root.modules {
        if !rank.contains_key(m.as_str()) {
            failures.push(format!("{DOC} import table: module `{m}` has no row"));
        }
    }
    if !failures.is_empty() {
        return failures;
    }

    // Layers: only from rows above.
    let mut upward_seen: BTreeSet<(String, String)> = BTreeSet::new();
    for imp in imports {
        if rank[imp.to.as_str()] > rank[imp.from.as_str()] {
            upward_seen.insert((imp.from.clone(), imp.to.clone()));
            if !known_upward.contains(&(imp.from.as_str(), imp.to.as_str())) {
                failures.push(format!(
                    "{}:{}: upward import: `{}` uses `{}`, a higher layer ({DOC}'s import table lists `{}` after `{}`)",
                    imp.path, imp.line, imp.from, imp.text, imp.to, imp.from
                ));
            }
        }
    }
    for (from, to) in known_upward {
        if !upward_seen.contains(&(from.to_string(), to.to_string())) {
            failures.push(format!(
                "KNOWN_UPWARD in crates/swell/tests/architecture.rs lists (\"{from}\", \"{to}\"), but `{from}` no longer imports `{to}` upward: remove the entry"
            ));
        }
    }

    // Rows: exactly what the code imports.
    for row in &rows {
        let actual: BTreeMap<&str, &Import> =
            imports.iter().filter(|i| i.from == row.module).map(|i| (i.to.as_str(), i)).rev().collect();
        for (to, imp) in &actual {
            if !row.imports.contains(*to) {
                failures.push(format!(
                    "{DOC}:{} import table: the `{}` row does not list `{to}`, which {}:{} imports ({})",
                    row.line, row.module, imp.path, imp.line, imp.text
                ));
            }
        }
        for listed in &row.imports {
            if !actual.contains_key(listed.as_str()) {
                failures.push(format!(
                    "{DOC}:{} import table: the `{}` row lists `{listed}`, but no non-test code of `{}` imports it",
                    row.line, row.module, row.module
                ));
            }
        }
    }

    // "No two modules import each other" only where it is true.
    if doc.contains("no two modules import each other") {
        let pairs: BTreeSet<(&str, &str)> = imports.iter().map(|i| (i.from.as_str(), i.to.as_str())).collect();
        for (a, b) in &pairs {
            if a < b && pairs.contains(&(*b, *a)) {
                failures.push(format!("{DOC} says \"no two modules import each other\", but `{a}` and `{b}` do"));
            }
        }
    }
    failures
}

/// The module map against the tree, as failure messages.
fn module_map_failures(doc: &str, root: &Path) -> Vec<String> {
    let entries = match module_map(doc) {
        Ok(entries) => entries,
        Err(e) => return vec![e],
    };
    let mut failures = Vec::new();
    let mut named: BTreeMap<&str, usize> = BTreeMap::new();
    for e in &entries {
        let exists = if e.path.ends_with('/') { root.join(&e.path).is_dir() } else { root.join(&e.path).is_file() };
        if !exists {
            failures.push(format!("{DOC}:{} module map: {} does not exist", e.line, e.path));
        }
        if let Some(first) = named.insert(&e.path, e.line) {
            failures.push(format!("{DOC}:{} module map: {} is named twice (also at line {first})", e.line, e.path));
        }
    }
    for dir in MAPPED_SOURCE_DIRS {
        for file in rust_files(root, dir) {
            if !named.contains_key(file.as_str()) {
                failures.push(format!("{DOC} module map: {file} is not named"));
            }
        }
    }
    failures
}

fn report(what: &str, failures: &[String]) {
    if !failures.is_empty() {
        let mut msg = format!("{what}: {} problem(s)\n", failures.len());
        for f in failures {
            writeln!(msg, "  {f}").unwrap();
        }
        panic!("{msg}");
    }
}

fn read_doc(root: &Path) -> String {
    std::fs::read_to_string(root.join(DOC)).unwrap()
}

#[test]
fn no_module_imports_upward_and_the_import_table_is_true() {
    let root = workspace_root();
    let (crate_root, imports) = library_imports(&root);
    let mut failures = import_failures(&read_doc(&root), &crate_root, &imports, KNOWN_UPWARD);
    if !failures.is_empty() {
        // What the rows should say, in the table's format, for the one fixing it.
        let mut actual: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
        for m in &crate_root.modules {
            actual.entry(m).or_default();
        }
        for i in &imports {
            actual.entry(&i.from).or_default().insert(&i.to);
        }
        let mut rows = String::from("what the non-test code imports:");
        for (m, to) in &actual {
            let list: Vec<String> = to.iter().map(|t| format!("`{t}`")).collect();
            let list = if list.is_empty() { "nothing".to_string() } else { list.join(", ") };
            write!(rows, "\n    | `{m}` | {list} |").unwrap();
        }
        failures.push(rows);
    }
    report("layers and import table", &failures);
}

#[test]
fn the_module_map_names_every_source_file_once() {
    let root = workspace_root();
    report("module map", &module_map_failures(&read_doc(&root), &root));
}

// ---------------------------------------------------------------------------------------------
// The checker's own tests: it sees what it must and nothing it must not.

fn scan(path: &str, src: &str, modules: &[&str]) -> Vec<(usize, String)> {
    let mut code = blank_comments_and_literals(src);
    blank_test_items(&mut code);
    let file = SourceFile { path: path.into(), module: module_path(path), code };
    let mut names = BTreeMap::new();
    names.insert("Error".to_string(), "error".to_string());
    let root = CrateRoot { modules: modules.iter().map(|m| m.to_string()).collect(), names };
    imports_of(&file, &root).into_iter().map(|i| (i.line, i.to)).collect()
}

#[test]
fn the_scanner_finds_every_form_of_path_and_skips_tests_comments_and_strings() {
    let src = r##"//! use crate::render::Doc;
use crate::math::Vec;
use crate::{raster::A, shading::{B, C}};
pub(crate) use crate::water
    ::Model;
/* crate::render::Block /* nested crate::render */ */
fn f() -> crate::Error {
    let s = "crate::render::Str"; let r = r#"crate::render::Raw"#; let c = '"';
    let l: &'static str = "";
    crate::spectrum::g(); super::super::terrain::h();
}
#[cfg(all(test, target_arch = "x86_64"))]
fn only_tests() { crate::render::T; }
#[test]
fn a_test() { crate::render::T; }
#[cfg(test)]
mod tests {
    use crate::render::Renderer;
    fn nested() { { crate::export::x(); } }
}
fn after() { crate::limits::MAX; crate::GRAVITY; }
"##;
    let modules =
        ["math", "raster", "shading", "water", "render", "spectrum", "terrain", "limits", "error", "export", "scene"];
    let found = scan("crates/swell/src/world/world.rs", src, &modules);
    let expect: Vec<(usize, String)> = [
        (2, "math"),
        (3, "raster"),
        (3, "shading"),
        (4, "water"),
        (7, "error"),
        (10, "spectrum"),
        (10, "terrain"),
        (21, "limits"),
    ]
    .iter()
    .map(|(l, m)| (*l, m.to_string()))
    .collect();
    assert_eq!(found, expect);
    // `super::super` from a file one level down stays in its module; from two levels down too.
    assert!(scan("crates/swell/src/water/fft_ocean/cascade.rs", "use super::super::foam::F;", &modules).is_empty());
    assert_eq!(
        scan("crates/swell/src/water/fft_ocean/cascade.rs", "use super::super::super::math::V;", &modules),
        vec![(1, "math".to_string())]
    );
}

#[test]
fn the_checks_fail_on_an_upward_import_a_wrong_row_and_a_missing_file() {
    let root = workspace_root();
    let doc = read_doc(&root);
    let (crate_root, mut imports) = library_imports(&root);
    let imp = |from: &str, to: &str| Import {
        path: format!("crates/swell/src/{from}/x.rs"),
        line: 7,
        from: from.into(),
        to: to.into(),
        text: format!("crate::{to}"),
    };
    imports.push(imp("math", "render"));
    let failures = import_failures(&doc, &crate_root, &imports, KNOWN_UPWARD);
    assert!(
        failures
            .iter()
            .any(|f| f.starts_with("crates/swell/src/math/x.rs:7: upward import: `math` uses `crate::render`")),
        "{failures:#?}"
    );
    assert!(failures.iter().any(|f| f.contains("the `math` row does not list `render`")), "{failures:#?}");

    // A listed entry that is no longer needed fails.
    let (_, imports) = library_imports(&root);
    let stale: Vec<(&str, &str)> = KNOWN_UPWARD.iter().copied().chain([("math", "export")]).collect();
    let failures = import_failures(&doc, &crate_root, &imports, &stale);
    assert!(failures.iter().any(|f| f.contains("lists (\"math\", \"export\")")), "{failures:#?}");

    // A file the map leaves out, and one it names that does not exist.
    let broken = doc.replacen("\n  error.rs ", "\n  nonexistent.rs ", 1);
    assert_ne!(broken, doc, "the map names error.rs two spaces under crates/swell/src/");
    let failures = module_map_failures(&broken, &root);
    assert!(
        failures.iter().any(|f| f.ends_with("module map: crates/swell/src/error.rs is not named")),
        "{failures:#?}"
    );
    assert!(failures.iter().any(|f| f.ends_with("crates/swell/src/nonexistent.rs does not exist")), "{failures:#?}");
}
