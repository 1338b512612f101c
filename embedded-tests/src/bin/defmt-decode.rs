//! `defmt-decode ELF [LOG]`: prints the defmt frames in LOG (or stdin) as text,
//! one per line, using the format strings in ELF. The same decoding the tests
//! use, for reading a firmware run by hand:
//! `qemu-system-arm … -kernel ELF | defmt-decode ELF`.
use std::io::{Read, Write};

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let Some(elf) = args.get(1) else {
        eprintln!("usage: defmt-decode ELF [LOG]");
        return std::process::ExitCode::from(2);
    };
    let log = match args.get(2) {
        Some(path) => std::fs::read(path),
        None => {
            let mut buf = Vec::new();
            std::io::stdin().read_to_end(&mut buf).map(|_| buf)
        }
    };
    let result = std::fs::read(elf)
        .map_err(|e| e.to_string())
        .and_then(|elf| Ok((elf, log.map_err(|e| e.to_string())?)))
        .and_then(|(elf, log)| capdiv_embedded_tests::decode_defmt(&elf, &log));
    match result {
        Ok(lines) => {
            let mut out = std::io::stdout().lock();
            for l in lines {
                // A closed pipe (`| head`) just ends the output.
                if writeln!(out, "{l}").is_err() {
                    break;
                }
            }
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("defmt-decode: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
