//! With the cargo feature `petsc`: finds PETSc by pkg-config (from `PETSC_DIR`, else Debian's
//! PETSc 3.18), checks that its configuration is the one the bindings declare (32-bit
//! `PetscInt`, real double scalars, Open MPI), and links it with MPI.

fn main() {
    println!("cargo:rerun-if-env-changed=PETSC_DIR");
    #[cfg(feature = "petsc")]
    petsc::link();
}

#[cfg(feature = "petsc")]
mod petsc {
    use std::path::PathBuf;

    /// Debian's PETSc 3.18 (package petsc-dev).
    const DEBIAN: &str = "/usr/lib/petscdir/petsc3.18/x86_64-linux-gnu-real";
    const INSTALL: &str = "install it with: apt-get install petsc-dev openmpi-bin (Debian), or set PETSC_DIR to a PETSc 3.18 built with MUMPS, real double scalars and 32-bit indices";

    pub fn link() {
        let dir = PathBuf::from(std::env::var("PETSC_DIR").unwrap_or_else(|_| DEBIAN.into()));
        let pkgconfig = dir.join("lib/pkgconfig");
        let path = std::env::var("PKG_CONFIG_PATH").unwrap_or_default();
        // SAFETY: a build script runs on one thread; pkg-config reads this variable.
        unsafe { std::env::set_var("PKG_CONFIG_PATH", format!("{}:{path}", pkgconfig.display())) };
        let library = pkg_config::Config::new()
            .atleast_version("3.18")
            .probe("PETSc")
            .unwrap_or_else(|e| panic!("PETSc not found under {} ({e}); {INSTALL}", dir.display()));
        check_configuration(&library.include_paths);
        pkg_config::probe_library("mpi").unwrap_or_else(|e| {
            panic!("MPI (Open MPI's pkg-config `mpi`) not found ({e}); {INSTALL}")
        });
    }

    /// The bindings declare 32-bit `PetscInt`, real double `PetscScalar` and Open MPI's
    /// handles: refuse another PETSc before it links and fails at run time.
    fn check_configuration(include: &[PathBuf]) {
        let conf = include
            .iter()
            .map(|p| p.join("petscconf.h"))
            .find(|p| p.exists())
            .unwrap_or_else(|| panic!("petscconf.h not found in {include:?}; {INSTALL}"));
        let text = std::fs::read_to_string(&conf).expect("petscconf.h is readable");
        let has = |name: &str| text.lines().any(|l| l.starts_with(&format!("#define {name} ")));
        let refuse = |why: &str| panic!("{}: {why}; {INSTALL}", conf.display());
        if has("PETSC_USE_64BIT_INDICES") {
            refuse("PETSc has 64-bit indices, the bindings declare 32-bit PetscInt");
        }
        if has("PETSC_USE_COMPLEX") || !has("PETSC_USE_REAL_DOUBLE") {
            refuse("PETSc's scalars are not real doubles");
        }
        if !has("PETSC_HAVE_OMPI_MAJOR_VERSION") {
            refuse("PETSc is not built with Open MPI, whose handles the bindings declare");
        }
        if !has("PETSC_HAVE_MUMPS") {
            refuse("PETSc is not built with MUMPS");
        }
    }
}
