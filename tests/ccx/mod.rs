//! CalculiX's `ccx` for the tests that compare with it: whether it is
//! installed, and the displacements it prints.

use std::path::Path;
use std::process::Command;

/// Whether `ccx` runs here; if not, says that the test is skipped.
pub fn installed() -> bool {
    let found = Command::new("ccx").arg("-v").output().is_ok();
    if !found {
        eprintln!("skipped: ccx (CalculiX) is not installed; apt-get install calculix-ccx");
    }
    found
}

/// `U` of `*NODE PRINT` in ccx's `.dat`: node id → displacement.
pub fn ccx_displacements(dat: &Path) -> Vec<(u64, [f64; 3])> {
    let text = std::fs::read_to_string(dat).unwrap();
    text.lines()
        .filter_map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            if f.len() != 4 {
                return None;
            }
            let id = f[0].parse().ok()?;
            let u = [f[1].parse().ok()?, f[2].parse().ok()?, f[3].parse().ok()?];
            Some((id, u))
        })
        .collect()
}

/// Runs `ccx -i <stem>` in `dir` (the deck `<stem>.inp` there); the
/// displacements of its `.dat`.
pub fn run(dir: &Path, stem: &str) -> Vec<(u64, [f64; 3])> {
    let out = Command::new("ccx")
        .args(["-i", stem])
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    ccx_displacements(&dir.join(format!("{stem}.dat")))
}
