//! Host-side drivers for capdiv's embedded targets: build the
//! firmware, run it under QEMU with a time limit, decode its defmt log, parse
//! the report lines; run the WASM demo under node.
//!
//! The checks themselves are in `tests/firmware_qemu.rs` and `tests/wasm_node.rs`.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

pub mod report;

/// The repository root (this crate lives in `embedded-tests/`).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("crate has a parent directory")
        .to_path_buf()
}

/// Runs `cargo <args>` in `dir` (so that `dir/.cargo/config.toml` applies),
/// with its own target directory `dir/target`; panics with cargo's output on failure.
pub fn cargo_in(dir: &Path, args: &[&str]) {
    let out = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .current_dir(dir)
        .args(args)
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_BUILD_TARGET")
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo {args:?} in {} failed:\n{}",
        dir.display(),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Builds the firmware (release) for `target`, with extra cargo arguments
/// (e.g. `--no-default-features --features eg`), and returns the ELF path.
/// Different feature sets share the path: run the ELF before the next build.
pub fn build_firmware(target: &str, extra: &str) -> PathBuf {
    let dir = repo_root().join("firmware");
    let mut args = vec!["build", "--release", "--target", target];
    args.extend(extra.split_whitespace());
    cargo_in(&dir, &args);
    dir.join("target")
        .join(target)
        .join("release")
        .join("capdiv-firmware")
}

/// What a run under an emulator or interpreter gave.
pub struct Run {
    /// Exit code, `None` when killed by a signal.
    pub code: Option<i32>,
    /// Raw standard output.
    pub stdout: Vec<u8>,
    /// Standard error, as text.
    pub stderr: String,
    /// Wall time.
    pub elapsed: Duration,
}

/// Runs `cmd` with a time limit; `Err` (with what it printed) if it hangs.
pub fn run_with_limit(mut cmd: Command, limit: Duration) -> Result<Run, String> {
    let start = Instant::now();
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {cmd:?}: {e}"))?;
    let mut out = child.stdout.take().expect("piped stdout");
    let mut err = child.stderr.take().expect("piped stderr");
    let reader = std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = out.read_to_end(&mut buf);
        buf
    });
    let err_reader = std::thread::spawn(move || {
        let mut buf = String::new();
        let _ = err.read_to_string(&mut buf);
        buf
    });
    loop {
        match child.try_wait().map_err(|e| e.to_string())? {
            Some(status) => {
                let elapsed = start.elapsed();
                return Ok(Run {
                    code: status.code(),
                    stdout: reader.join().unwrap_or_default(),
                    stderr: err_reader.join().unwrap_or_default(),
                    elapsed,
                });
            }
            None if start.elapsed() > limit => {
                let _ = child.kill();
                let _ = child.wait();
                let stdout = reader.join().unwrap_or_default();
                return Err(format!(
                    "{cmd:?} did not finish within {limit:?} (hang); {} bytes of output",
                    stdout.len()
                ));
            }
            None => std::thread::sleep(Duration::from_millis(20)),
        }
    }
}

/// The QEMU command line for a firmware ELF on `machine` with `cpu`.
pub fn qemu(machine: &str, cpu: Option<&str>, elf: &Path) -> Command {
    let mut cmd = Command::new("qemu-system-arm");
    cmd.args(["-machine", machine]);
    if let Some(cpu) = cpu {
        cmd.args(["-cpu", cpu]);
    }
    cmd.args([
        "-nographic",
        "-monitor",
        "none",
        "-serial",
        "none",
        "-semihosting-config",
        "enable=on,target=native",
        "-kernel",
    ]);
    cmd.arg(elf);
    cmd
}

/// Decodes a raw defmt byte stream with the format table of `elf`: one
/// string per frame. Fails on a malformed frame; a truncated last frame is
/// dropped (the callers require a final `done` line, so truncation fails them).
pub fn decode_defmt(elf: &[u8], log: &[u8]) -> Result<Vec<String>, String> {
    let table = defmt_decoder::Table::parse(elf)
        .map_err(|e| format!("defmt table: {e}"))?
        .ok_or("the ELF has no .defmt section")?;
    let mut stream = table.new_stream_decoder();
    stream.received(log);
    let mut lines = Vec::new();
    loop {
        match stream.decode() {
            Ok(frame) => lines.push(frame.display_message().to_string()),
            Err(defmt_decoder::DecodeError::UnexpectedEof) => break,
            Err(defmt_decoder::DecodeError::Malformed) => {
                return Err(format!("malformed defmt frame after {} lines", lines.len()))
            }
        }
    }
    Ok(lines)
}
