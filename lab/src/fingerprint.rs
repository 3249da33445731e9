//! The fingerprint of the sources a committed page is made from, for the
//! pages too slow to make in CI: `audit/AUDIT.md` ([`fingerprint`]) and the
//! sensitivity map. The command that makes a page writes the fingerprint
//! into it; a harness test recomputes it, so a page made from other code
//! fails CI until it is made again. This file is compiled into the lab and
//! into the audit.

use std::path::{Path, PathBuf};

/// What AUDIT.md is made from: the audit crate's sources, manifest and
/// lock file (so the pinned crate versions), the sources of the published
/// crate under `src/` (the studies and verdicts that judge the audited
/// methods), and the N-body references its race reads from
/// `lab/references/` (not the lab's code, which the audit never builds).
/// `root` is the repository root.
pub fn fingerprint(root: &Path) -> std::io::Result<String> {
    fingerprint_of(
        root,
        &["src", "audit/src", "audit/tests"],
        &[
            "audit/Cargo.toml",
            "audit/Cargo.lock",
            "lab/references/pleiades.json",
            "lab/references/outer-solar-system.json",
        ],
    )
}

/// FNV-1a (64 bit) over every input file's path (relative, `/`-separated),
/// length and bytes, in the order of the paths: a stable, dependency-free
/// digest of the inputs, as 16 hex digits. The inputs are every `.rs` file
/// under `folders` and the `files`, all relative to `root`.
pub fn fingerprint_of(root: &Path, folders: &[&str], files: &[&str]) -> std::io::Result<String> {
    let mut inputs = Vec::new();
    for folder in folders {
        collect(root, &root.join(folder), &mut inputs)?;
    }
    inputs.extend(files.iter().map(|f| f.to_string()));
    inputs.sort();
    let files = inputs;
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    for file in &files {
        let bytes = std::fs::read(root.join(file))?;
        eat(file.as_bytes());
        eat(&(bytes.len() as u64).to_le_bytes());
        eat(&bytes);
    }
    Ok(format!("{hash:016x}"))
}

/// Every `.rs` file under `folder`, as a path relative to `root`.
fn collect(root: &Path, folder: &Path, out: &mut Vec<String>) -> std::io::Result<()> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(folder)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    entries.sort();
    for path in entries {
        if path.is_dir() {
            collect(root, &path, out)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).expect("under the root");
            let parts: Vec<_> = relative.iter().map(|p| p.to_string_lossy()).collect();
            out.push(parts.join("/"));
        }
    }
    Ok(())
}
