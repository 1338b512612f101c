//! What the OpenSubdiv side-by-side benchmarks share: the benchmark meshes,
//! the timing loop (the same as `osd_bench.cpp`'s), the OpenSubdiv helper's
//! build and its job files. Included by each bench with `#[path]`; each uses
//! a part of it.
#![allow(dead_code)]

use super::osd;
use capdiv_mesh::MeshInput;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// capdiv's cap depth and OpenSubdiv's isolation level.
pub const DEPTH: u32 = 4;

/// Median seconds per call of `f`, timed as `osd_bench.cpp` times.
pub fn time(mut f: impl FnMut()) -> (f64, usize) {
    let batch_of = |f: &mut dyn FnMut(), n: usize| {
        let t = Instant::now();
        for _ in 0..n {
            f();
        }
        t.elapsed()
    };
    let mut batch = 1;
    let mut took;
    loop {
        took = batch_of(&mut f, batch);
        if took >= Duration::from_millis(2) || batch >= 1 << 20 {
            break;
        }
        batch *= 2;
    }
    let samples = ((2.0 / took.as_secs_f64()) as usize).clamp(5, 21);
    let mut per: Vec<f64> = (0..samples)
        .map(|_| batch_of(&mut f, batch).as_secs_f64() / batch as f64)
        .collect();
    per.sort_by(f64::total_cmp);
    (per[samples / 2], samples)
}

/// The OpenSubdiv helper, built into the bench's target directory when its
/// source is newer.
pub fn helper() -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/osd/osd_bench.cpp");
    osd::compile(&src, "osd-bench")
}

/// Writes the job file of mesh `name` (isolation [`DEPTH`]) and returns its
/// path.
pub fn job_file(name: &str, mesh: &MeshInput) -> PathBuf {
    let mut job = osd::Job::new(mesh);
    job.isolation = DEPTH;
    let name: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.osdjob"));
    std::fs::write(&path, osd::job_text(&job)).expect("write the job file");
    path
}
