// Finds the installed libmcstat through pkg-config (mcstat.pc; set
// PKG_CONFIG_PATH for a non-system prefix).  With the "static" feature,
// libmcstat.a is linked and Requires.private / Libs.private (GSL, libm,
// pthread) follow from pkg-config --static.
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
}
