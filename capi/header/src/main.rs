//! Generates capdiv's C header from the C ABI crate's source with cbindgen
//! (configuration `capi/cbindgen.toml`):
//!
//! ```sh
//! cargo run --manifest-path capi/header/Cargo.toml            # writes capi/include/capdiv.h
//! cargo run --manifest-path capi/header/Cargo.toml -- --check # fails if it differs
//! ```
//!
//! CI runs `--check` (scripts/ci-cfirmware.sh): the checked-in header must be
//! byte for byte what the current source generates.
use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let check = match std::env::args().nth(1).as_deref() {
        None => false,
        Some("--check") => true,
        Some(other) => {
            eprintln!("unknown argument {other:?}; usage: capdiv-capi-header [--check]");
            return ExitCode::from(2);
        }
    };
    let capi = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let config = match cbindgen::Config::from_file(capi.join("cbindgen.toml")) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("capi/cbindgen.toml: {e}");
            return ExitCode::FAILURE;
        }
    };
    let bindings = match cbindgen::Builder::new()
        .with_crate(&capi)
        .with_config(config)
        .generate()
    {
        Ok(b) => b,
        Err(e) => {
            eprintln!("cbindgen: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let header = capi.join("include").join("capdiv.h");
    if check {
        let current = std::fs::read(&header).unwrap_or_default();
        if current == generated {
            println!("capi/include/capdiv.h is current");
            ExitCode::SUCCESS
        } else {
            eprintln!(
                "capi/include/capdiv.h differs from what capi/src generates: \
                 run `cargo run --manifest-path capi/header/Cargo.toml` and commit it"
            );
            ExitCode::FAILURE
        }
    } else if let Err(e) = std::fs::write(&header, &generated) {
        eprintln!("{}: {e}", header.display());
        ExitCode::FAILURE
    } else {
        println!("wrote {}", header.display());
        ExitCode::SUCCESS
    }
}
