//! The crate docs and the README describe the catalogue as it is: every
//! scheme in `scheme::catalogue()` has a row in both, with its claimed
//! order (and, in the README, its geometry and force evaluations), and no
//! row names a scheme that is not there. A scheme added, removed or
//! re-claimed without its documentation fails here.

use stepladder::scheme::{SchemeMeta, catalogue};

/// The rows of the first Markdown table whose header starts with `| id |`
/// in `text`, split into trimmed cells, the id's backticks removed.
fn catalogue_rows(text: &str) -> Vec<Vec<String>> {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines
        .iter()
        .position(|l| l.trim_start().starts_with("| id |"))
        .expect("a catalogue table");
    lines[start + 2..]
        .iter()
        .take_while(|l| l.trim_start().starts_with('|'))
        .map(|l| {
            l.trim()
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().trim_matches('`').to_string())
                .collect()
        })
        .collect()
}

fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

fn assert_same_ids(rows: &[Vec<String>], where_: &str) {
    let documented: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    let ids: Vec<&str> = catalogue().iter().map(|m| m.id).collect();
    assert_eq!(
        documented, ids,
        "{where_}'s catalogue table lists other schemes (or in another order) than the catalogue"
    );
}

#[test]
fn the_readme_catalogue_table_is_the_catalogue() {
    let readme = include_str!("../README.md");
    let rows = catalogue_rows(readme);
    assert_same_ids(&rows, "README.md");
    for (row, meta) in rows.iter().zip(catalogue()) {
        let SchemeMeta {
            order,
            symplectic,
            symmetric,
            ..
        } = *meta;
        let expected = [
            order.to_string(),
            yes_no(symplectic).to_string(),
            yes_no(symmetric).to_string(),
            meta.forces_label(),
        ];
        assert_eq!(&row[2..6], &expected, "README.md row of {}", meta.id);
    }
}

#[test]
fn the_crate_docs_catalogue_table_is_the_catalogue() {
    let docs: String = include_str!("../src/lib.rs")
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .map(|l| format!("{}\n", l.trim_start()))
        .collect();
    let rows = catalogue_rows(&docs);
    assert_same_ids(&rows, "the crate docs");
    for (row, meta) in rows.iter().zip(catalogue()) {
        assert_eq!(
            row[1],
            meta.order.to_string(),
            "crate docs row of {}",
            meta.id
        );
    }
}

#[test]
fn the_table_reader_sees_a_wrong_row() {
    let text = "| id | order | family |\n|---|---|---|\n| `euler` | 2 | explicit Euler |\n";
    let rows = catalogue_rows(text);
    assert_eq!(rows, vec![vec!["euler", "2", "explicit Euler"]]);
    assert_ne!(rows[0][1], catalogue()[0].order.to_string());
}

/// The prelude is a list a reader can take in at once: at most thirty names,
/// each written out (no glob, no module), so that `use
/// stepladder::prelude::*` brings nothing the list does not show.
#[test]
fn the_prelude_lists_at_most_thirty_names_by_hand() {
    let names = exported(include_str!("../src/prelude.rs"));
    assert!(!names.is_empty(), "no names found in src/prelude.rs");
    assert!(
        names.iter().all(|n| n != "*" && n != "self"),
        "a glob or a module in the prelude: {names:?}"
    );
    assert!(names.len() <= 30, "{} names: {names:?}", names.len());
    let mut unique = names.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), names.len(), "a name listed twice: {names:?}");
}

/// The documented modules and the files that declare what each exports.
const SURFACE: [(&str, &str); 8] = [
    ("stepladder::prelude", include_str!("../src/prelude.rs")),
    ("stepladder::guard", include_str!("../src/guard.rs")),
    ("stepladder::scheme", include_str!("../src/scheme/mod.rs")),
    ("stepladder::scene", include_str!("../src/scene/mod.rs")),
    ("stepladder::study", include_str!("../src/study/mod.rs")),
    (
        "stepladder::conditions",
        include_str!("../src/maths/conditions.rs"),
    ),
    ("stepladder::error", include_str!("../src/error.rs")),
    ("stepladder::state", include_str!("../src/state.rs")),
];

/// The names a module file makes public: the names of its `pub use` lists
/// (an `as` rename under its new name) and the items it declares `pub` at
/// its top level, skipping what is `#[doc(hidden)]`; a function with its
/// signature as written, up to its body.
fn exported(source: &str) -> Vec<String> {
    let lines: Vec<&str> = source.lines().collect();
    let mut names = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let hidden = i > 0 && lines[i - 1].trim() == "#[doc(hidden)]";
        let mut statement = line.to_string();
        if line.starts_with("pub use ") {
            while !statement.trim_end().ends_with(';') {
                i += 1;
                statement.push(' ');
                statement.push_str(lines[i].trim());
            }
            if !hidden {
                let list = statement
                    .trim_end_matches(';')
                    .rsplit_once("::")
                    .map_or("", |(_, tail)| tail);
                for item in list.split([',', '{', '}']).map(str::trim) {
                    if !item.is_empty() {
                        names.push(item.rsplit(" as ").next().unwrap().to_string());
                    }
                }
            }
        } else if let Some(rest) = line.strip_prefix("pub ").or_else(|| {
            line.strip_prefix("macro_rules! ")
                .filter(|_| lines[i.saturating_sub(1)].trim() == "#[macro_export]")
        }) {
            if rest.starts_with("fn ") || rest.starts_with("const fn ") {
                while !statement.contains('{') && !statement.trim_end().ends_with(';') {
                    i += 1;
                    statement.push(' ');
                    statement.push_str(lines[i].trim());
                }
                let signature = statement.split('{').next().unwrap();
                if !hidden {
                    names.push(signature.split_whitespace().collect::<Vec<_>>().join(" "));
                }
            } else if !hidden && !rest.starts_with("use ") {
                // a constant up to its value, a type up to its body
                let head = if rest.starts_with("const ") || rest.starts_with("static ") {
                    rest.split(" = ").next().unwrap()
                } else {
                    rest.split(['{', '(', ';']).next().unwrap()
                };
                names.push(head.trim().to_string());
            }
        }
        i += 1;
    }
    names
}

/// The public surface, module by module: every name a user can reach, and
/// the signatures of the functions declared in the module files. A change
/// here is a change of the API, reviewed as a snapshot diff
/// (`cargo insta review`). That no public signature holds a type without a
/// documented path, and that no path is deeper than two segments, was
/// checked on this list against rustdoc's own index.
#[test]
fn the_public_surface_is_what_the_snapshot_shows() {
    let mut listing = String::new();
    for (module, source) in SURFACE {
        listing.push_str(module);
        listing.push('\n');
        let mut names = exported(source);
        names.sort();
        for name in names {
            listing.push_str("    ");
            listing.push_str(&name);
            listing.push('\n');
        }
    }
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.bind(|| insta::assert_snapshot!("public_surface", listing));
}

/// The crate's inner modules are public only so that `internals` can name
/// them: every other crate of the repository (the lab, its tests, the
/// downstream crate, the audit) and the core's own integration tests and
/// benches reach them through `stepladder::internals::` and no other path.
#[test]
fn code_outside_the_core_reaches_the_inner_modules_through_one_door() {
    const INNER: [&str; 16] = [
        "ladder::",
        "maths::",
        "parallel::",
        "run::",
        "tolerance::",
        "wording::",
        "scheme::compensated::",
        "study::accuracy::",
        "study::adaptive::",
        "study::breakdown::",
        "study::cost::",
        "study::geometry::",
        "study::hard::",
        "study::round_off::",
        "study::stability::",
        "study::verdict::",
    ];
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut offending = Vec::new();
    let mut read = 0;
    let mut stack: Vec<_> = [
        "lab",
        "audit/src",
        "audit/tests",
        "downstream",
        "tests",
        "benches",
    ]
    .iter()
    .map(|d| root.join(d))
    .collect();
    while let Some(path) = stack.pop() {
        if path.is_dir() {
            if path.ends_with("target") {
                continue;
            }
            for entry in std::fs::read_dir(&path).unwrap() {
                stack.push(entry.unwrap().path());
            }
        } else if path.extension().is_some_and(|e| e == "rs") {
            read += 1;
            let text = std::fs::read_to_string(&path).unwrap();
            for (n, line) in text.lines().enumerate() {
                // a bare module in a `use` ends in `;`: read it as `::`
                let line = line.replace(';', "::");
                if INNER
                    .iter()
                    .any(|m| line.contains(&format!("stepladder::{m}")))
                {
                    offending.push(format!("{}:{}: {}", path.display(), n + 1, line.trim()));
                }
            }
        }
    }
    assert!(read > 50, "only {read} source files found");
    assert!(
        offending.is_empty(),
        "inner modules reached past `internals`:\n{}",
        offending.join("\n")
    );
}
