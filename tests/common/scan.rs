//! Independent scans of STEP and IGES text for the accounting tests: entity names of each
//! STEP instance (ISO 10303-21 §10 instance syntax, strings skipped) and IGES entity type
//! counts of the directory section (IGES 5.3 §2.2.4: fixed 8-column fields, section letter in
//! column 73).

use std::collections::BTreeMap;

/// The entity names of each STEP instance in the DATA section: `#12=PLANE(...)` gives
/// `PLANE`, a complex instance `#12=(BOUNDED_SURFACE() B_SPLINE_SURFACE(...) ...)` every
/// part name at its top level. Strings (`'...'`) are skipped.
pub fn step_instances(text: &str) -> Vec<Vec<String>> {
    let data = &text[text.find("DATA;").expect("a DATA section") + 5..];
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut in_str = false;
    for c in data.chars() {
        if c == '\'' {
            in_str = !in_str;
            continue;
        }
        if in_str {
            continue;
        }
        if c == ';' {
            if let Some(names) = instance_names(&cur) {
                out.push(names);
            }
            cur.clear();
        } else {
            cur.push(c);
        }
    }
    out
}

/// The names of one instance's text `#id = ...` (strings already removed).
pub fn instance_names(s: &str) -> Option<Vec<String>> {
    let s = s.trim();
    let rest = s.strip_prefix('#')?;
    let rhs = rest[rest.find('=')? + 1..].trim();
    if let Some(inner) = rhs.strip_prefix('(') {
        // Complex: identifiers directly followed by `(` at depth 0 of the inner text.
        let mut names = Vec::new();
        let (mut depth, mut word) = (0, String::new());
        for c in inner.chars() {
            match c {
                '(' => {
                    if depth == 0 && !word.is_empty() {
                        names.push(word.clone());
                    }
                    word.clear();
                    depth += 1;
                }
                ')' => {
                    depth -= 1;
                    word.clear();
                }
                c if depth == 0 && (c.is_ascii_alphanumeric() || c == '_') => word.push(c),
                _ => word.clear(),
            }
        }
        Some(names)
    } else {
        let name: String = rhs
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        Some(vec![name])
    }
}

/// Instances holding `kind` (as simple entity or complex part), counted in the text.
pub fn step_count(instances: &[Vec<String>], kind: &str) -> usize {
    instances
        .iter()
        .filter(|n| n.iter().any(|x| x == kind))
        .count()
}

/// IGES entity type counts of the D section: the type is columns 1–8 of each odd D line
/// (section letter in column 73, sequence number in columns 74–80).
pub fn iges_counts(text: &str) -> BTreeMap<i64, usize> {
    let mut out = BTreeMap::new();
    for l in text.lines() {
        if l.len() < 80 || l.as_bytes()[72] != b'D' {
            continue;
        }
        let seq: usize = l[73..80].trim().parse().expect("D sequence number");
        if seq % 2 == 1 {
            let t: i64 = l[0..8].trim().parse().expect("entity type number");
            *out.entry(t).or_insert(0) += 1;
        }
    }
    out
}
