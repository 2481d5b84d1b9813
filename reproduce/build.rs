//! Links libtorch so `reproduce` runs without LD_LIBRARY_PATH (see estimator/build.rs, which
//! also records libtorch's version): an rpath to libtorch's directory and
//! `-Wl,--no-as-needed -ltorch`, which keeps libtorch_cuda loaded when a GPU is present.

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if os == "linux" || os == "windows" {
        if let Some(lib) = std::env::var_os("DEP_TCH_LIBTORCH_LIB") {
            println!("cargo:rustc-link-arg=-Wl,-rpath={}", lib.to_string_lossy());
        }
        println!("cargo:rustc-link-arg=-Wl,--no-as-needed");
        println!("cargo:rustc-link-arg=-ltorch");
    }
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=LIBTORCH");
}
