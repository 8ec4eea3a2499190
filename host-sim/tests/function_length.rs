//! No function in the workspace's sources is over [`MAX_LINES`] lines (issue 25: "no host-sim
//! function is over about 80 lines"; issue 56 extends it to every file of [`SOURCE_DIRS`]:
//! the core, host-sim and calibrate, their tests included). Read from the sources: every
//! `fn` item with a body, counted from the line of its `fn` keyword to the line of its
//! closing brace (doc comments and attributes left out), with strings, characters and
//! comments skipped so that a brace inside one is not counted. A nested `fn` is counted on
//! its own and as part of its outer function; closures are part of the function that holds
//! them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The longest a function may be, in lines.
const MAX_LINES: usize = 80;

/// The directories scanned (every `.rs` file under each), relative to the workspace root.
const SOURCE_DIRS: [&str; 5] = [
    "src",
    "host-sim/src",
    "host-sim/tests",
    "calibrate/src",
    "calibrate/tests",
];

/// Functions allowed over [`MAX_LINES`] (`FILE::NAME`, the file relative to the workspace
/// root): none. An entry must be over the limit: one that is no longer fails the test, so
/// the list cannot go stale.
const ALLOWED_OVER: &[&str] = &[];

/// One function: its name, the line of its `fn` keyword (1-based) and its length in lines.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Function {
    name: String,
    line: usize,
    lines: usize,
}

/// `source` with every comment, string and character literal replaced by spaces (line
/// breaks kept), so that only code is left, on the same lines.
fn code_only(source: &str) -> Vec<u8> {
    let s = source.as_bytes();
    let mut out = Vec::with_capacity(s.len());
    let blank = |out: &mut Vec<u8>, b: &[u8]| {
        out.extend(b.iter().map(|&c| if c == b'\n' { b'\n' } else { b' ' }));
    };
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        let prev_ident = i > 0 && (s[i - 1].is_ascii_alphanumeric() || s[i - 1] == b'_');
        let end = if rest.starts_with(b"//") {
            rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len())
        } else if rest.starts_with(b"/*") {
            block_comment_len(rest)
        } else if !prev_ident && raw_string_start(rest).is_some() {
            raw_string_len(rest)
        } else if rest[0] == b'"' || (!prev_ident && rest.starts_with(b"b\"")) {
            let open = rest.iter().position(|&c| c == b'"').unwrap_or(0);
            open + quoted_len(&rest[open..], b'"')
        } else if rest[0] == b'\'' || (!prev_ident && rest.starts_with(b"b'")) {
            let open = rest.iter().position(|&c| c == b'\'').unwrap_or(0);
            char_literal_len(&rest[open..]).map_or(1, |n| open + n)
        } else {
            out.push(rest[0]);
            i += 1;
            continue;
        };
        blank(&mut out, &rest[..end]);
        i += end;
    }
    out
}

/// The length of the (nested) block comment at the start of `s`.
fn block_comment_len(s: &[u8]) -> usize {
    let (mut depth, mut i) = (0usize, 0);
    while i < s.len() {
        if s[i..].starts_with(b"/*") {
            depth += 1;
            i += 2;
        } else if s[i..].starts_with(b"*/") {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    s.len()
}

/// The number of `#`s of the raw string (`r"`, `r#"`, `br"`, ...) at the start of `s`.
fn raw_string_start(s: &[u8]) -> Option<usize> {
    let s = s.strip_prefix(b"b").unwrap_or(s);
    let s = s.strip_prefix(b"r")?;
    let hashes = s.iter().take_while(|&&c| c == b'#').count();
    (s.get(hashes) == Some(&b'"')).then_some(hashes)
}

/// The length of the raw string at the start of `s`.
fn raw_string_len(s: &[u8]) -> usize {
    let hashes = raw_string_start(s).unwrap_or(0);
    let open = s.iter().position(|&c| c == b'"').unwrap_or(0) + 1;
    let mut close = vec![b'"'];
    close.extend(std::iter::repeat_n(b'#', hashes));
    s[open..]
        .windows(close.len())
        .position(|w| w == close.as_slice())
        .map_or(s.len(), |p| open + p + close.len())
}

/// The length of the `quote`-delimited literal (with backslash escapes) at the start of `s`.
fn quoted_len(s: &[u8], quote: u8) -> usize {
    let mut i = 1;
    while i < s.len() {
        match s[i] {
            b'\\' => i += 2,
            c if c == quote => return i + 1,
            _ => i += 1,
        }
    }
    s.len()
}

/// The length of the character literal at the start of `s`, or `None` for a lifetime or
/// a label (`'a`, `'static`, `'outer:`).
fn char_literal_len(s: &[u8]) -> Option<usize> {
    match s.get(1)? {
        b'\\' => Some(quoted_len(s, b'\'')),
        _ => {
            // One character (up to 4 bytes of UTF-8), then the closing quote.
            let width = std::str::from_utf8(&s[1..s.len().min(5)])
                .or_else(|e| std::str::from_utf8(&s[1..1 + e.valid_up_to()]))
                .ok()?
                .chars()
                .next()?
                .len_utf8();
            (s.get(1 + width) == Some(&b'\'')).then_some(width + 2)
        }
    }
}

/// Every function with a body in `source`.
fn functions(source: &str) -> Vec<Function> {
    let code = code_only(source);
    let line_of = |i: usize| 1 + code[..i].iter().filter(|&&c| c == b'\n').count();
    let is_ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(p) = code[i..].windows(2).position(|w| w == b"fn") {
        let at = i + p;
        i = at + 2;
        let before = at.checked_sub(1).map(|j| code[j]);
        if before.is_some_and(is_ident) || code.get(at + 2).is_some_and(|&c| is_ident(c)) {
            continue;
        }
        let mut j = at + 2;
        while code.get(j).is_some_and(u8::is_ascii_whitespace) {
            j += 1;
        }
        let name_len = code[j..].iter().take_while(|&&c| is_ident(c)).count();
        if name_len == 0 {
            continue; // a `fn(..)` pointer type
        }
        let name = String::from_utf8_lossy(&code[j..j + name_len]).into_owned();
        let Some(open) = body_start(&code, j + name_len) else {
            continue; // a declaration without a body
        };
        let close = matching_brace(&code, open);
        out.push(Function {
            name,
            line: line_of(at),
            lines: line_of(close) - line_of(at) + 1,
        });
    }
    out
}

/// The `{` that opens the body of the function whose signature starts at `from`, or `None`
/// if a `;` ends the signature first (a trait method or foreign function without a body).
fn body_start(code: &[u8], from: usize) -> Option<usize> {
    let mut depth = 0i32; // the () and [] of the signature
    for (k, &c) in code.iter().enumerate().skip(from) {
        match c {
            b'(' | b'[' => depth += 1,
            b')' | b']' => depth -= 1,
            b';' if depth == 0 => return None,
            b'{' if depth == 0 => return Some(k),
            _ => {}
        }
    }
    None
}

/// The `}` that closes the `{` at `open` (the end of `code` if none does).
fn matching_brace(code: &[u8], open: usize) -> usize {
    let mut depth = 0usize;
    for (k, &c) in code.iter().enumerate().skip(open) {
        match c {
            b'{' => depth += 1,
            b'}' => {
                depth -= 1;
                if depth == 0 {
                    return k;
                }
            }
            _ => {}
        }
    }
    code.len() - 1
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// Every function of [`SOURCE_DIRS`] over [`MAX_LINES`], by `FILE::NAME` (several if a
/// file has more than one of that name): `(FILE:LINE, lines)`.
fn long_functions() -> BTreeMap<String, Vec<(String, usize)>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out: BTreeMap<String, Vec<(String, usize)>> = BTreeMap::new();
    for dir in SOURCE_DIRS {
        let files = rust_files(&root.join(dir));
        assert!(!files.is_empty(), "no .rs file under {dir}");
        for file in files {
            let rel = file
                .strip_prefix(&root)
                .unwrap()
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/");
            let text = std::fs::read_to_string(&file).unwrap();
            for f in functions(&text).into_iter().filter(|f| f.lines > MAX_LINES) {
                out.entry(format!("{rel}::{}", f.name))
                    .or_default()
                    .push((format!("{rel}:{}", f.line), f.lines));
            }
        }
    }
    out
}

#[test]
fn no_function_in_the_workspace_sources_is_over_the_limit() {
    let long = long_functions();
    let offenders: Vec<String> = long
        .iter()
        .filter(|(key, _)| !ALLOWED_OVER.contains(&key.as_str()))
        .flat_map(|(key, at)| at.iter().map(move |(a, n)| format!("{a} {key}: {n} lines")))
        .collect();
    let stale: Vec<&str> = ALLOWED_OVER
        .iter()
        .copied()
        .filter(|key| !long.contains_key(*key))
        .collect();
    let mut failures = Vec::new();
    if !offenders.is_empty() {
        failures.push(format!(
            "{} function(s) over {MAX_LINES} lines; extract helpers:\n{}",
            offenders.len(),
            offenders.join("\n")
        ));
    }
    if !stale.is_empty() {
        failures.push(format!(
            "allowed over {MAX_LINES} lines but no longer over (or gone), remove from \
             ALLOWED_OVER: {}",
            stale.join(", ")
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The scanner counts what it should and skips what it should.
#[test]
fn the_scanner_counts_bodies_and_skips_strings_comments_and_declarations() {
    let src = r##"
/// A doc comment with fn fake() { and a brace
fn one() -> [u8; 2] {
    let s = "}}} fn two() {";
    let r = r#"" } "#;
    let c = '}';
    let q = '\'';
    let l: &'static str = "x"; // }
    /* } /* nested } */ fn three() { */
    [0, 1]
}
trait T {
    fn declared(&self) -> u8;
    fn defaulted(&self) -> u8 {
        let f: fn(u8) -> u8 = |x| x;
        f(1)
    }
}
"##;
    let found: Vec<(String, usize, usize)> = functions(src)
        .into_iter()
        .map(|f| (f.name, f.line, f.lines))
        .collect();
    assert_eq!(
        found,
        vec![("one".into(), 3, 9), ("defaulted".into(), 14, 4)]
    );
}
