//! The constants a bench run depends on, read from the sources: every `const` item of
//! the files under [`SCANNED`], outside `#[cfg(test)]` modules, as its name and its
//! normalised text (comments dropped, whitespace collapsed). Shared by host-sim's build
//! script (which compiles the build's digest in) and `bench summary --made-at` (which
//! reads an older commit's sources through git), so both read them the same way.

/// The sources whose constants can change a bench run's results, relative to the
/// workspace root: the core, the calibration, and host-sim's plant, trials and links
/// (its commands, plots and the accuracy report change no bench figure).
pub const SCANNED: [&str; 9] = [
    "src",
    "calibrate/src",
    "host-sim/src/bench",
    "host-sim/src/brush",
    "host-sim/src/sim",
    "host-sim/src/experiment",
    "host-sim/src/link",
    "host-sim/src/exact.rs",
    "host-sim/src/finger_file.rs",
];

/// Whether `path` (relative to the workspace root, `/`-separated) is a Rust file under
/// [`SCANNED`].
pub fn is_scanned(path: &str) -> bool {
    path.ends_with(".rs")
        && SCANNED
            .iter()
            .any(|s| path == *s || path.starts_with(&format!("{s}/")))
}

/// `source` without comments, strings kept (a `//` inside a string is not a comment).
fn without_comments(source: &str) -> String {
    let s = source.as_bytes();
    let mut out = Vec::with_capacity(s.len());
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        if rest.starts_with(b"//") {
            i += rest.iter().position(|&c| c == b'\n').unwrap_or(rest.len());
        } else if rest.starts_with(b"/*") {
            let mut depth = 0usize;
            while i < s.len() {
                if s[i..].starts_with(b"/*") {
                    depth += 1;
                    i += 2;
                } else if s[i..].starts_with(b"*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(b' ');
        } else if let Some(len) = raw_string_len(rest, i > 0 && is_ident_byte(s[i - 1])) {
            out.extend_from_slice(&rest[..len]);
            i += len;
        } else if let Some(len) = char_literal_len(rest) {
            out.extend_from_slice(&rest[..len]);
            i += len;
        } else if rest[0] == b'"' {
            let mut j = 1;
            while j < rest.len() && rest[j] != b'"' {
                j += if rest[j] == b'\\' { 2 } else { 1 };
            }
            let end = (j + 1).min(rest.len());
            out.extend_from_slice(&rest[..end]);
            i += end;
        } else {
            out.push(rest[0]);
            i += 1;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn is_ident_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// The length of the raw string (`r"..."`, `r#"..."#`, `br"..."`) at the start of `s`,
/// unless an identifier goes on before it.
fn raw_string_len(s: &[u8], after_ident: bool) -> Option<usize> {
    if after_ident {
        return None;
    }
    let start = usize::from(s.first() == Some(&b'b'));
    if s.get(start) != Some(&b'r') {
        return None;
    }
    let hashes = s[start + 1..].iter().take_while(|&&c| c == b'#').count();
    let open = start + 1 + hashes;
    if s.get(open) != Some(&b'"') {
        return None;
    }
    let mut close = vec![b'"'];
    close.extend(std::iter::repeat_n(b'#', hashes));
    let body = &s[open + 1..];
    Some(
        body.windows(close.len())
            .position(|w| w == close.as_slice())
            .map_or(s.len(), |p| open + 1 + p + close.len()),
    )
}

/// The length of the character literal at the start of `s` (`'x'`, `'\n'`, `b'"'`), or
/// `None` for a lifetime, a label or anything else.
fn char_literal_len(s: &[u8]) -> Option<usize> {
    let start = usize::from(s.first() == Some(&b'b'));
    if s.get(start) != Some(&b'\'') {
        return None;
    }
    let body = &s[start + 1..];
    if body.first() == Some(&b'\\') {
        let close = body.iter().skip(2).position(|&c| c == b'\'')?;
        return Some(start + 1 + 2 + close + 1);
    }
    let text = std::str::from_utf8(&body[..body.len().min(4)])
        .or_else(|e| std::str::from_utf8(&body[..e.valid_up_to()]))
        .ok()?;
    let width = text.chars().next()?.len_utf8();
    (body.get(width) == Some(&b'\'')).then_some(start + 1 + width + 1)
}

/// `code` with every `#[cfg(test)] mod NAME { .. }` block cut out.
fn without_test_modules(code: &str) -> String {
    let mut out = String::new();
    let mut rest = code;
    while let Some(i) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..i]);
        let after = &rest[i + "#[cfg(test)]".len()..];
        let trimmed = after.trim_start();
        if !trimmed.starts_with("mod ") && !trimmed.starts_with("pub mod ") {
            rest = after;
            continue;
        }
        let Some(open) = after.find('{') else {
            return out;
        };
        let mut depth = 0usize;
        let mut end = after.len();
        for (k, c) in after[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// `code` with the insides of its string and character literals replaced by `_` (same
/// length), so that a `;` or a bracket in a literal does not end or nest an item.
fn mask_literals(code: &str) -> Vec<u8> {
    let s = code.as_bytes();
    let mut out = s.to_vec();
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        let len = raw_string_len(rest, i > 0 && is_ident_byte(s[i - 1]))
            .or_else(|| char_literal_len(rest))
            .or_else(|| {
                (rest[0] == b'"').then(|| {
                    let mut j = 1;
                    while j < rest.len() && rest[j] != b'"' {
                        j += if rest[j] == b'\\' { 2 } else { 1 };
                    }
                    (j + 1).min(rest.len())
                })
            });
        match len {
            Some(n) => {
                for b in &mut out[i + 1..i + n.saturating_sub(1).max(1)] {
                    *b = b'_';
                }
                i += n.max(1);
            }
            None => i += 1,
        }
    }
    out
}

/// Every `const` item of `source`: `(name, item)`, the item from its name to its `;`,
/// whitespace collapsed. Const generics, `*const` pointers, `const fn` and `const`
/// blocks are not items and are skipped.
pub fn constants(source: &str) -> Vec<(String, String)> {
    let code = without_test_modules(&without_comments(source));
    let masked = String::from_utf8(mask_literals(&code)).unwrap_or_default();
    let b = masked.as_bytes();
    let is_ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(p) = masked[from..].find("const") {
        let at = from + p;
        from = at + 5;
        if (at > 0 && is_ident(b[at - 1])) || b.get(at + 5).is_some_and(|&c| is_ident(c)) {
            continue;
        }
        let before = masked[..at].trim_end().as_bytes().last().copied();
        if matches!(before, Some(b'<' | b',' | b'*' | b'&')) {
            continue;
        }
        let name_start = at + 5 + masked[at + 5..].len() - masked[at + 5..].trim_start().len();
        let name_len = b[name_start..].iter().take_while(|&&c| is_ident(c)).count();
        let name = &code[name_start..name_start + name_len];
        if name.is_empty() || matches!(name, "fn" | "unsafe" | "async" | "extern") {
            continue;
        }
        let (mut depth, mut end) = (0i32, None);
        for (k, &c) in b.iter().enumerate().skip(name_start) {
            match c {
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' | b'}' => depth -= 1,
                b';' if depth == 0 => {
                    end = Some(k);
                    break;
                }
                _ => {}
            }
            if depth < 0 {
                break;
            }
        }
        let Some(end) = end else { continue };
        let item: Vec<&str> = code[name_start..end].split_whitespace().collect();
        let item = item.join(" ");
        if !item.contains('=') {
            continue;
        }
        out.push((name.to_string(), item));
        from = end;
    }
    out
}

/// The digest of a set of constant items: FNV-1a (64 bit) of their texts, sorted, one a
/// line, as 16 hex digits. It depends on names and values, not on where they live.
pub fn digest(items: &[(String, String)]) -> String {
    let mut texts: Vec<&str> = items.iter().map(|(_, item)| item.as_str()).collect();
    texts.sort_unstable();
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for t in texts {
        for &byte in t.as_bytes().iter().chain(b"\n") {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    format!("{h:016x}")
}
