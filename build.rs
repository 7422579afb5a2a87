//! Generates the PETSc FFI with bindgen when the `parallel` feature is on.
//! Without the feature this does nothing and the crate needs no system library.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "parallel")]
    petsc::generate();
}

#[cfg(feature = "parallel")]
mod petsc {
    use std::path::PathBuf;
    use std::process::Command;

    fn pkg_config(args: &[&str]) -> String {
        let out = Command::new("pkg-config")
            .args(args)
            .arg("PETSc")
            .output()
            .expect(
            "pkg-config is needed to find PETSc (apt-get install pkg-config libpetsc-real3.18-dev)",
        );
        if !out.status.success() {
            panic!(
                "pkg-config cannot find PETSc: {} (apt-get install libpetsc-real3.18-dev)",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        String::from_utf8_lossy(&out.stdout).trim().to_string()
    }

    /// MPI include flags from `mpicc -showme:compile` (Open MPI), since PETSc's
    /// .pc file has none.
    fn mpi_includes() -> Vec<String> {
        Command::new("mpicc")
            .arg("-showme:compile")
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| {
                String::from_utf8_lossy(&o.stdout)
                    .split_whitespace()
                    .filter(|f| f.starts_with("-I"))
                    .map(str::to_string)
                    .collect()
            })
            .unwrap_or_default()
    }

    pub fn generate() {
        let cflags = pkg_config(&["--cflags"]);
        for flag in pkg_config(&["--libs"]).split_whitespace() {
            if let Some(dir) = flag.strip_prefix("-L") {
                println!("cargo:rustc-link-search=native={dir}");
                println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
            } else if let Some(lib) = flag.strip_prefix("-l") {
                println!("cargo:rustc-link-lib={lib}");
            }
        }
        let mut builder = bindgen::Builder::default()
            .header_contents("wrapper.h", "#include <petscsnes.h>\n")
            .allowlist_function("(Petsc|PETSc|Mat|Vec|KSP|PC|SNES|IS|ISLocalToGlobalMapping)[A-Z_].*")
            .allowlist_var("(PETSC|MAT|KSP|PC|SNES|VEC|INSERT|ADD|NORM)_.*")
            .blocklist_function(".*(VA|Va)[Ll]ist.*")
            .blocklist_function(".*(MPIIO|FILE|Fortran).*")
            .blocklist_type("(MPI_|ompi_).*")
            .blocklist_item("ompi_.*")
            .raw_line("pub use mpi::ffi::{MPI_Comm, MPI_Datatype, MPI_Op, MPI_Request, MPI_Group, MPI_Status, MPI_Info, MPI_Errhandler, MPI_Win, MPI_Aint};")
            .layout_tests(false)
            .derive_default(true)
            .generate_comments(false);
        for flag in cflags
            .split_whitespace()
            .map(str::to_string)
            .chain(mpi_includes())
        {
            if flag.starts_with("-I") && !flag.contains("mumps_seq") {
                builder = builder.clang_arg(flag);
            }
        }
        let bindings = builder.generate().expect("bindgen failed on petscsnes.h");
        let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR")).join("petsc_ffi.rs");
        bindings
            .write_to_file(&out)
            .expect("cannot write the PETSc bindings");
        println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    }
}
