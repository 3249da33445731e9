//! Markdown building blocks: tables and number formats that stay identical
//! across machines (a few significant digits, never the last bits).

use stepladder::study::Reach;

/// A Markdown table.
#[derive(Clone, Debug, Default)]
pub struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column headings.
    pub fn new(header: &[&str]) -> Self {
        Self {
            header: header.iter().map(|s| s.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row (cells beyond the header's width are ignored).
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    /// The table as Markdown, one line per row.
    pub fn render(&self) -> String {
        let line = |cells: &[String]| {
            let cells: Vec<String> = (0..self.header.len())
                .map(|i| {
                    cells
                        .get(i)
                        .map_or(String::new(), |c| c.replace('|', "\\|"))
                })
                .collect();
            format!("| {} |\n", cells.join(" | "))
        };
        let mut out = line(&self.header);
        out.push_str(&format!("|{}\n", "---|".repeat(self.header.len())));
        for r in &self.rows {
            out.push_str(&line(r));
        }
        out
    }
}

/// A positive quantity to three significant digits, `1.23e-4`.
pub fn sci(x: f64) -> String {
    format!("{x:.2e}")
}

/// An optional quantity, `-` when absent.
pub fn opt(x: Option<f64>, f: impl Fn(f64) -> String) -> String {
    x.map_or("-".into(), f)
}

/// An order of accuracy to three decimals.
pub fn order(x: f64) -> String {
    format!("{x:.3}")
}

/// `yes` or `no`.
pub fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// The widest prose line the report writes; tables keep the width they need.
pub const PROSE_WIDTH: usize = 100;

/// `text` with every paragraph and list item wrapped at [`PROSE_WIDTH`]
/// columns (a list item's continuation lines indented under its text), and
/// every other line (tables, headings, HTML, code blocks, blank lines) left
/// as it is. Markdown renders the wrapped text identically.
pub fn wrap_prose(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 50);
    let mut in_code = false;
    for line in text.split_inclusive('\n') {
        let (body, end) = match line.strip_suffix('\n') {
            Some(b) => (b, "\n"),
            None => (line, ""),
        };
        let trimmed = body.trim_start();
        if trimmed.starts_with("```") {
            in_code = !in_code;
        }
        let kept = in_code
            || trimmed.starts_with("```")
            || body.chars().count() <= PROSE_WIDTH
            || trimmed.starts_with('|')
            || trimmed.starts_with('#')
            || trimmed.starts_with('<')
            || body.starts_with("    ");
        if kept {
            out.push_str(line);
            continue;
        }
        let indent = list_indent(body);
        let mut width = 0;
        for (i, word) in body.split(' ').filter(|w| !w.is_empty()).enumerate() {
            let w = word.chars().count();
            if i > 0 && width + 1 + w > PROSE_WIDTH {
                out.push('\n');
                out.push_str(&" ".repeat(indent));
                width = indent;
            } else if i > 0 {
                out.push(' ');
                width += 1;
            }
            out.push_str(word);
            width += w;
        }
        out.push_str(end);
    }
    out
}

/// The indent of a list item's continuation lines: under the item's text.
pub fn list_indent(line: &str) -> usize {
    let lead = line.len() - line.trim_start().len();
    let rest = &line[lead..];
    if rest.starts_with("- ") || rest.starts_with("* ") {
        return lead + 2;
    }
    let digits = rest.chars().take_while(char::is_ascii_digit).count();
    if digits > 0 && rest[digits..].starts_with(". ") {
        return lead + digits + 2;
    }
    lead
}

/// A cost in force evaluations, to three digits; `<=` marks an upper bound.
pub fn evaluations(r: Reach) -> String {
    match r {
        Reach::Interpolated(c) => sci(c),
        Reach::AtMost(c) => format!("<= {}", sci(c)),
        Reach::NotReached => "not reached".into(),
    }
}

/// A duration in seconds with a unit, to three digits.
pub fn duration(seconds: f64) -> String {
    if seconds < 1e-3 {
        format!("{:.3} us", seconds * 1e6)
    } else if seconds < 1.0 {
        format!("{:.3} ms", seconds * 1e3)
    } else {
        format!("{seconds:.3} s")
    }
}

/// A time to target; `<=` marks an upper bound.
pub fn time_reach(r: Reach) -> String {
    match r {
        Reach::Interpolated(c) => duration(c),
        Reach::AtMost(c) => format!("<= {}", duration(c)),
        Reach::NotReached => "not reached".into(),
    }
}
