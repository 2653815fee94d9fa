// Finds the installed libmcstat through pkg-config (mcstat.pc; set
// PKG_CONFIG_PATH for a non-system prefix).  With the "static" feature,
// libmcstat.a is linked and Requires.private / Libs.private (GSL, libm,
// pthread) follow from pkg-config --static.
//
// Shared linking records the library directory as an rpath, so that test
// binaries and examples run without LD_LIBRARY_PATH.  Cargo applies
// rustc-link-arg only to this package's own targets, so the directory is
// also published as metadata (DEP_MCSTAT_LIBDIR in the build scripts of
// the packages that depend on this one: the mcstat crate's emits the same
// rpath for its targets, and an application's build.rs can do likewise).
fn main() {
    let statik = std::env::var_os("CARGO_FEATURE_STATIC").is_some();
    let lib = pkg_config::Config::new()
        .atleast_version("0.1")
        .statik(statik)
        .probe("mcstat")
        .unwrap_or_else(|e| {
            panic!(
                "libmcstat not found through pkg-config ({e}); install it (cmake --install) \
                 and set PKG_CONFIG_PATH to its lib/pkgconfig"
            )
        });
    for dir in &lib.include_paths {
        println!("cargo:include={}", dir.display());
    }
    if !statik {
        // the directory holding libmcstat.so: the first -L of mcstat.pc
        // that has it (pkg-config omits -L for the system directories,
        // which the loader searches anyway)
        let libdir = lib.link_paths.iter().find(|d| d.join("libmcstat.so").exists() || d.join("libmcstat.dylib").exists());
        if let Some(dir) = libdir {
            println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
            println!("cargo:libdir={}", dir.display());
        }
    }
}
