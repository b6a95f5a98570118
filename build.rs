//! Build script: the build's provenance for `signorini --version` and
//! `NAME.log` ([`provenance`]); and, only with the `petsc` feature, the C
//! layer over PETSc (`src/solve/petsc/shim.c`) compiled against the
//! installed PETSc and MPI, found by `pkg-config` (`petsc`, `ompi-c` or
//! `mpich`) or by `PETSC_DIR` (and `PETSC_ARCH`).

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    provenance::emit();
    #[cfg(feature = "petsc")]
    petsc::build();
}

/// Sets `SIGNORINI_COMMIT` (git's 12-digit hash of `HEAD`, `unknown`
/// outside a git checkout of this crate: a crate unpacked from a registry,
/// a source archive, no `git`) and `SIGNORINI_FEATURES` (the enabled cargo
/// features, comma-separated, `none`) for `src/output/provenance.rs`.
mod provenance {
    use std::path::Path;
    use std::process::Command;

    /// The trimmed output of `git ARGS`, if it ran and succeeded.
    fn git(args: &[&str]) -> Option<String> {
        let out = Command::new("git").args(args).output().ok()?;
        let text = String::from_utf8(out.stdout).ok()?.trim().to_string();
        (out.status.success() && !text.is_empty()).then_some(text)
    }

    /// Whether `a` and `b` are the same folder.
    fn same(a: &Path, b: &Path) -> bool {
        matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b)
    }

    pub fn emit() {
        let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
        // the commit of this crate's own checkout, not of a repository
        // around it (a home folder kept in git, with the crate in ~/.cargo)
        let own = git(&["rev-parse", "--show-toplevel"])
            .is_some_and(|top| same(Path::new(&top), Path::new(&manifest)));
        let commit = own
            .then(|| git(&["rev-parse", "--short=12", "HEAD"]))
            .flatten();
        println!(
            "cargo:rustc-env=SIGNORINI_COMMIT={}",
            commit.as_deref().unwrap_or("unknown")
        );
        if own {
            // a new commit (HEAD, the branch it names, packed refs) rebuilds
            let branch = git(&["symbolic-ref", "-q", "HEAD"]);
            let refs = ["HEAD", "packed-refs"].into_iter().chain(branch.as_deref());
            for r in refs {
                if let Some(path) = git(&["rev-parse", "--git-path", r]) {
                    if Path::new(&path).exists() {
                        println!("cargo:rerun-if-changed={path}");
                    }
                }
            }
        }
        let mut features: Vec<String> = std::env::vars()
            .filter_map(|(k, _)| k.strip_prefix("CARGO_FEATURE_").map(str::to_string))
            .filter(|f| f != "DEFAULT")
            .map(|f| f.to_lowercase().replace('_', "-"))
            .collect();
        features.sort();
        let features = if features.is_empty() {
            "none".to_string()
        } else {
            features.join(", ")
        };
        println!("cargo:rustc-env=SIGNORINI_FEATURES={features}");
    }
}

#[cfg(feature = "petsc")]
mod petsc {
    use std::process::Command;

    /// `pkg-config --cflags`/`--libs` of the first of `names` found.
    fn pkg_config(names: &[&str]) -> Option<(Vec<String>, Vec<String>)> {
        for name in names {
            let run = |flag: &str| {
                Command::new("pkg-config")
                    .args([flag, name])
                    .output()
                    .ok()
                    .filter(|o| o.status.success())
                    .map(|o| {
                        String::from_utf8_lossy(&o.stdout)
                            .split_whitespace()
                            .map(str::to_string)
                            .collect::<Vec<_>>()
                    })
            };
            if let (Some(c), Some(l)) = (run("--cflags"), run("--libs")) {
                return Some((c, l));
            }
        }
        None
    }

    pub fn build() {
        println!("cargo:rerun-if-changed=src/solve/petsc/shim.c");
        println!("cargo:rerun-if-env-changed=PETSC_DIR");
        println!("cargo:rerun-if-env-changed=PETSC_ARCH");
        let (mut cflags, mut libs) = match std::env::var("PETSC_DIR") {
            Ok(dir) => {
                let arch = std::env::var("PETSC_ARCH").unwrap_or_default();
                let base = format!("{dir}/{arch}");
                (
                    vec![format!("-I{dir}/include"), format!("-I{base}/include")],
                    vec![format!("-L{base}/lib"), "-lpetsc".to_string()],
                )
            }
            Err(_) => pkg_config(&["petsc", "PETSc"]).unwrap_or_else(|| {
                panic!(
                    "the `petsc` feature needs PETSc: install it (Debian/Ubuntu: \
                     `apt-get install petsc-dev`) or set PETSC_DIR (and PETSC_ARCH)"
                )
            }),
        };
        if let Some((c, l)) = pkg_config(&["ompi-c", "mpich", "mpi"]) {
            cflags.extend(c);
            libs.extend(l);
        }
        let mut build = cc::Build::new();
        build.file("src/solve/petsc/shim.c").warnings(false);
        for flag in &cflags {
            if let Some(dir) = flag.strip_prefix("-I") {
                build.include(dir);
            } else if let Some(def) = flag.strip_prefix("-D") {
                let (k, v) = def
                    .split_once('=')
                    .map_or((def, None), |(k, v)| (k, Some(v)));
                build.define(k, v);
            }
        }
        build.compile("signorini_petsc_shim");
        for flag in &libs {
            if let Some(dir) = flag.strip_prefix("-L") {
                println!("cargo:rustc-link-search=native={dir}");
                println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
            } else if let Some(lib) = flag.strip_prefix("-l") {
                println!("cargo:rustc-link-lib={lib}");
            }
        }
    }
}
