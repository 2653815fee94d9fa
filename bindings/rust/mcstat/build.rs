// The rpath of the shared libmcstat for this crate's tests, examples and
// doctests (mcstat-sys publishes the directory as DEP_MCSTAT_LIBDIR: Cargo
// passes a build script's rustc-link-arg to its own package's targets only).
fn main() {
    println!("cargo:rerun-if-env-changed=DEP_MCSTAT_LIBDIR");
    if let Some(dir) = std::env::var_os("DEP_MCSTAT_LIBDIR") {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.to_string_lossy());
    }
}
