//! IGES file structure: the fixed-column S/G/D/P/T sections, Global-section delimiters,
//! Hollerith strings and Fortran `D` exponents, directory entries with their parameters.

use super::IgesError;
use std::collections::BTreeMap;

/// A parameter: number, string or empty (default).
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    Num(f64),
    Str(String),
    Empty,
}

impl Param {
    pub fn num(&self) -> Option<f64> {
        match self {
            Param::Num(x) => Some(*x),
            _ => None,
        }
    }
}

/// One directory entry with its parameters.
#[derive(Clone, Debug)]
pub struct Entry {
    pub de: usize,
    pub etype: i64,
    pub form: i64,
    pub transform: usize,
    /// The status number (directory field 9), right-aligned and zero-padded to its eight
    /// digits (IGES 5.3 §2.2.4.4.9): 1–2 blank status, 3–4 subordinate entity switch, 5–6
    /// entity use flag, 7–8 hierarchy. Files write it with leading blanks or zeros alike.
    pub status: String,
    pub params: Vec<Param>,
}

impl Entry {
    /// The subordinate entity switch (status digits 3–4): `"00"` independent, `"01"`
    /// physically dependent, `"02"` logically dependent, `"03"` both.
    pub fn subordinate(&self) -> &str {
        self.status.get(2..4).unwrap_or("00")
    }
    /// Whether the entry is physically or logically dependent: part of another entity.
    pub fn dependent(&self) -> bool {
        self.subordinate() != "00"
    }
}

/// The status field's text right-aligned and zero-padded to eight digits (blanks inside the
/// field are zeros: each pair is a two-digit number).
fn status_digits(field: &str) -> String {
    format!("{:0>8}", field.trim()).replace(' ', "0")
}

/// Parse the free-format parameter text with the file's delimiters.
fn split_params(s: &str, pd: char, rd: char) -> Result<Vec<Param>, String> {
    let b: Vec<char> = s.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    let mut cur = String::new();
    while i < b.len() {
        let c = b[i];
        if c == pd || c == rd {
            let t = cur.trim();
            out.push(if t.is_empty() {
                Param::Empty
            } else {
                number(t)
                    .map(Param::Num)
                    .ok_or_else(|| format!("'{t}' is not a number"))?
            });
            cur.clear();
            if c == rd {
                return Ok(out);
            }
            i += 1;
            continue;
        }
        if c == 'H' && !cur.trim().is_empty() && cur.trim().chars().all(|d| d.is_ascii_digit()) {
            let count = cur.trim();
            // The count is checked against what is left, never added to an index first: a
            // count near `usize::MAX` would wrap.
            let n = match count.parse::<usize>() {
                Ok(n) if n <= b.len() - (i + 1) => n,
                _ => {
                    return Err(format!(
                        "Hollerith count {count} runs past the end of the parameters ({} characters left)",
                        b.len() - (i + 1)
                    ));
                }
            };
            out.push(Param::Str(b[i + 1..i + 1 + n].iter().collect()));
            cur.clear();
            i += 1 + n;
            // Skip to the delimiter after the string.
            while i < b.len() && b[i] != pd && b[i] != rd {
                i += 1;
            }
            if i < b.len() && b[i] == rd {
                return Ok(out);
            }
            i += 1;
            continue;
        }
        cur.push(c);
        i += 1;
    }
    let t = cur.trim();
    if !t.is_empty() {
        out.push(
            number(t)
                .map(Param::Num)
                .ok_or_else(|| format!("'{t}' is not a number"))?,
        );
    }
    Ok(out)
}

/// A number in IGES syntax (Fortran `D` exponents allowed).
fn number(t: &str) -> Option<f64> {
    let t = t.replace(['D', 'd'], "E");
    let t = if t.ends_with('.') { format!("{t}0") } else { t };
    let x: f64 = t.trim_start_matches('+').parse().ok()?;
    x.is_finite().then_some(x)
}

/// The raw sections of a file.
struct Sections {
    global: String,
    dir: Vec<String>,
    par: Vec<(usize, String)>,
}

fn sections(text: &str, file: &str) -> Result<Sections, IgesError> {
    let mut s = Sections {
        global: String::new(),
        dir: Vec::new(),
        par: Vec::new(),
    };
    for (n, raw) in text.lines().enumerate() {
        let line = raw.trim_end_matches('\r');
        if line.trim().is_empty() {
            continue;
        }
        let chars: Vec<char> = line.chars().collect();
        if chars.len() < 73 {
            return Err(IgesError {
                file: file.into(),
                location: format!("line {}", n + 1),
                reason: format!("line has {} columns, IGES lines have 80", chars.len()),
            });
        }
        let body: String = chars[..72].iter().collect();
        match chars[72] {
            'S' | 'T' => {}
            'G' => s.global.push_str(&body),
            'D' => s.dir.push(body),
            'P' => {
                let de: usize = chars[64..72]
                    .iter()
                    .collect::<String>()
                    .trim()
                    .parse()
                    .unwrap_or(0);
                s.par.push((de, chars[..64].iter().collect()));
            }
            c => {
                return Err(IgesError {
                    file: file.into(),
                    location: format!("line {}", n + 1),
                    reason: format!("unknown section letter '{c}' in column 73"),
                });
            }
        }
    }
    Ok(s)
}

fn field(l: &str, k: usize) -> &str {
    l.get(k * 8..(k + 1) * 8).unwrap_or("").trim()
}

/// Directory entries by DE number, the unit, the minimum user-intended resolution (Global
/// parameter 19, in the model's unit, when positive and finite), header warnings, and the
/// `(DE, type)` of the directory entries no parameter line points to (left out of the
/// entries, each with a warning).
pub type Parsed = (
    BTreeMap<usize, Entry>,
    Option<String>,
    Option<f64>,
    Vec<String>,
    Vec<(usize, i64)>,
);

/// Parse an IGES file into directory entries (by DE number), the unit and header warnings.
pub fn parse(text: &str, file: &str) -> Result<Parsed, IgesError> {
    let s = sections(text, file)?;
    let mut warnings = Vec::new();
    // Global: delimiters, then the unit (parameters 14, 15).
    let g = s.global.as_str();
    let (pd, rd) = {
        let gd =
            |rest: &str| -> Option<char> { rest.strip_prefix("1H").and_then(|r| r.chars().next()) };
        let pd = gd(g).unwrap_or(',');
        let after = if g.starts_with("1H") {
            g.get(2 + pd.len_utf8()..).unwrap_or("")
        } else {
            g.get(pd.len_utf8()..).unwrap_or("")
        };
        let rd = gd(after.trim_start_matches(pd)).unwrap_or(';');
        (pd, rd)
    };
    let mut unit = None;
    let mut resolution = None;
    match split_params(g, pd, rd) {
        Ok(gp) => {
            resolution = gp
                .get(18)
                .and_then(|p| p.num())
                .filter(|r| *r > 0.0 && r.is_finite());
            let flag = gp.get(13).and_then(|p| p.num());
            // Units flag (Global 14): 1 inch (the IGES default), 2 mm, 3 named in Global 15,
            // 4 ft, 5 mi, 6 m, 7 km, 8 mil, 9 micron, 10 cm, 11 microinch.
            let by_flag = |f: i64| -> Option<&'static str> {
                Some(match f {
                    1 => "inch",
                    2 => "mm",
                    4 => "foot",
                    5 => "mile",
                    6 => "m",
                    7 => "km",
                    8 => "mil",
                    9 => "um",
                    10 => "cm",
                    11 => "microinch",
                    _ => return None,
                })
            };
            let name = match gp.get(14) {
                Some(Param::Str(n)) if !n.is_empty() => Some(crate::model::normalize_unit(n)),
                _ => None,
            };
            unit = match flag.map(|f| f as i64) {
                Some(3) => name.or(Some("inch".into())),
                Some(f) if by_flag(f).is_some() => by_flag(f).map(String::from),
                f => {
                    let f = f.map_or("missing".to_string(), |f| f.to_string());
                    warnings.push(format!(
                        "units flag {f} is not valid; the IGES default (inch) is used"
                    ));
                    Some("inch".into())
                }
            };
        }
        // A string that claims to run past the end of the section is a broken file, not a
        // header quirk: refuse it rather than guess where the header's values are.
        Err(e) if e.starts_with("Hollerith") => {
            return Err(IgesError {
                file: file.into(),
                location: "global section".into(),
                reason: e,
            });
        }
        Err(e) => warnings.push(format!("global section unreadable ({e}); defaults used")),
    }
    if s.dir.len() % 2 != 0 {
        return Err(IgesError {
            file: file.into(),
            location: "directory".into(),
            reason: "odd number of directory lines".into(),
        });
    }
    // Parameter text by DE pointer.
    let mut ptext: BTreeMap<usize, String> = BTreeMap::new();
    for (de, t) in &s.par {
        ptext.entry(*de).or_default().push_str(t);
    }
    let mut out = BTreeMap::new();
    let mut no_params = Vec::new();
    for k in 0..s.dir.len() / 2 {
        let (l1, l2) = (&s.dir[2 * k], &s.dir[2 * k + 1]);
        let de = 2 * k + 1;
        let int = |x: &str| x.parse::<i64>().unwrap_or(0);
        let etype = int(field(l1, 0));
        let Some(t) = ptext.get(&de) else {
            warnings.push(format!("DE {de} (type {etype}) has no parameter data"));
            no_params.push((de, etype));
            continue;
        };
        let params = split_params(t, pd, rd).map_err(|r| IgesError {
            file: file.into(),
            location: format!("DE {de}"),
            reason: r,
        })?;
        out.insert(
            de,
            Entry {
                de,
                etype,
                form: int(field(l2, 4)),
                transform: int(field(l1, 6)).max(0) as usize,
                status: status_digits(field(l1, 8)),
                params,
            },
        );
    }
    Ok((out, unit, resolution, warnings, no_params))
}
