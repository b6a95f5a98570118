//! Build script: only with the `petsc` feature, compile the C layer over
//! PETSc (`src/solve/petsc/shim.c`) against the installed PETSc and MPI,
//! found by `pkg-config` (`petsc`, `ompi-c` or `mpich`) or by `PETSC_DIR`
//! (and `PETSC_ARCH`). Without the feature it does nothing.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "petsc")]
    petsc::build();
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
