//! `-o PATH` behaves like a shell redirection that never leaves a partial
//! file: a new or regular file is replaced whole (keeping its permissions),
//! a FIFO and the target of a symbolic link are written through, and the
//! FIFO or link stays what it was.

mod common;

use common::{capdiv, s, tempdir};
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::Path;

/// A small valid input and the bytes `capdiv pole` prints for it on stdout.
fn pole_input(dir: &Path) -> (String, Vec<u8>) {
    let input = dir.join("in.json");
    std::fs::copy(
        concat!(env!("CARGO_MANIFEST_DIR"), "/examples/saddle.json"),
        &input,
    )
    .unwrap();
    let input = s(&input).to_string();
    let run = capdiv(&["pole", &input], None);
    run.assert_ok();
    assert!(!run.stdout.is_empty());
    (input, run.stdout)
}

#[test]
fn a_fifo_is_written_through_and_stays_a_fifo() {
    let dir = tempdir();
    let (input, expected) = pole_input(dir.path());
    let fifo = dir.path().join("pipe");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("run mkfifo");
    assert!(made.success());
    // A reader process reads the FIFO until the writer closes it; if the
    // FIFO were replaced by a file its open would never return, so it is
    // bounded by `timeout` and the test fails on its empty output.
    let reader = std::process::Command::new("timeout")
        .args(["30", "cat", s(&fifo)])
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("run timeout cat");
    let run = capdiv(&["pole", &input, "-o", s(&fifo)], None);
    run.assert_ok();
    let got = reader.wait_with_output().unwrap();
    assert!(got.status.success(), "the reader saw no writer");
    assert_eq!(got.stdout, expected);
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "the FIFO was replaced: {kind:?}");
    // Nothing else was left in the directory (no temporary file).
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["in.json", "pipe"]);
}

#[test]
fn a_symlink_writes_its_target_and_stays_a_link() {
    let dir = tempdir();
    let (input, expected) = pole_input(dir.path());
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    let target = sub.join("target.json");
    std::fs::write(&target, b"old").unwrap();
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o640)).unwrap();
    let link = dir.path().join("link.json");
    std::os::unix::fs::symlink(&target, &link).unwrap();

    let run = capdiv(&["pole", &input, "-o", s(&link)], None);
    run.assert_ok();
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced");
    assert_eq!(std::fs::read_link(&link).unwrap(), target);
    assert_eq!(std::fs::read(&target).unwrap(), expected);
    let mode = std::fs::metadata(&target).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640, "the target's permissions changed");
}

#[test]
fn a_dangling_symlink_creates_its_target() {
    let dir = tempdir();
    let (input, expected) = pole_input(dir.path());
    let target = dir.path().join("new.json");
    let link = dir.path().join("link.json");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let run = capdiv(&["pole", &input, "-o", s(&link)], None);
    run.assert_ok();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), expected);
}

#[test]
fn a_regular_file_is_replaced_keeping_its_permissions() {
    let dir = tempdir();
    let (input, expected) = pole_input(dir.path());
    let out = dir.path().join("out.json");
    std::fs::write(
        &out,
        b"an older and longer content than the new one ........",
    )
    .unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o600)).unwrap();
    let run = capdiv(&["pole", &input, "-o", s(&out)], None);
    run.assert_ok();
    assert_eq!(std::fs::read(&out).unwrap(), expected);
    let mode = std::fs::metadata(&out).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o600);
}

#[test]
fn a_directory_is_refused_in_one_line() {
    let dir = tempdir();
    let (input, _) = pole_input(dir.path());
    let run = capdiv(&["pole", &input, "-o", s(dir.path())], None);
    assert_eq!(run.code, Some(2));
    assert!(run.stdout.is_empty());
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(run.stderr.contains("is a directory"), "{}", run.stderr);
}

#[test]
fn a_streamed_output_follows_the_same_rules() {
    let dir = tempdir();
    let (input, _) = pole_input(dir.path());
    let args = ["patches", "--depth", "2", "--stream", &input];
    let expected = capdiv(&args, None);
    expected.assert_ok();
    // Through a link to a regular file with its permissions.
    let target = dir.path().join("target.json");
    std::fs::write(&target, b"old").unwrap();
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o604)).unwrap();
    let link = dir.path().join("link.json");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let run = capdiv(&[&args[..], &["-o", s(&link)]].concat(), None);
    run.assert_ok();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), expected.stdout);
    let mode = std::fs::metadata(&target).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o604);
    // Through a FIFO (bounded reader, as above).
    let fifo = dir.path().join("pipe");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let reader = std::process::Command::new("timeout")
        .args(["30", "cat", s(&fifo)])
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let run = capdiv(&[&args[..], &["-o", s(&fifo)]].concat(), None);
    run.assert_ok();
    let got = reader.wait_with_output().unwrap();
    assert_eq!(got.stdout, expected.stdout);
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
}
