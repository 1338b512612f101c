//! capdiv's analysis side by side with OpenSubdiv 3.5's, on the same meshes
//! with the same tags, per input face; and the patches each makes per face.
//!
//! - capdiv: [`SurfacePlan::for_mesh`] at depth 4 (validation, topology, tags,
//!   caps, feature-adaptive refinement); patches counted from one
//!   [`Evaluator::evaluate`].
//! - OpenSubdiv: `TopologyRefinerFactory::Create`, `RefineAdaptive` to
//!   isolation level 4, `PatchTableFactory::Create` (Gregory basis end caps,
//!   infinitely sharp patches) and a `PatchMap`, in `osd/osd_bench.cpp`,
//!   built here with `g++ … -losdCPU` and run on a job file of each mesh
//!   (the format of `tests/osd/oracle.cpp`).
//!
//! Both sides time the same way: batches of analyses (doubled until a batch
//! takes 2 ms), then 5..21 batches (about 2 s), the median time per analysis;
//! a result is dropped inside the timed batch on both sides.
//!
//! `cargo bench -p capdiv-mesh --bench osd_side_by_side` prints markdown
//! tables (`-- --only NAME,NAME` for some meshes). For instruction counts
//! (`scripts/osd-side-by-side.sh`): `-- --prepare NAME` writes the mesh's job
//! file and prints the helper's and the job's paths, `-- --once NAME` runs
//! the analysis once inside `capdiv_analyse` (callgrind's
//! `--toggle-collect=capdiv_analyse`).

#[path = "osd/common.rs"]
mod common;
#[path = "../tests/osd/mod.rs"]
mod osd;

use capdiv_mesh::samples::feature_torus;
use capdiv_mesh::sinks::SurfaceStats;
use capdiv_mesh::{samples, Evaluator, MeshInput, PlanOptions, SurfacePlan, Topology};
use common::{helper, job_file, time, DEPTH};
use std::collections::BTreeMap;
use std::hint::black_box;
use std::path::Path;
use std::process::Command;

/// A named benchmark mesh.
struct Case {
    name: &'static str,
    mesh: MeshInput,
}

/// Builds one benchmark mesh.
type Make = fn() -> MeshInput;

/// The meshes, in table order; only those `keep` accepts are built.
fn cases(keep: &dyn Fn(&str) -> bool) -> Vec<Case> {
    let makers: [(&'static str, Make); 14] = [
        ("torus-features-1e4", || feature_torus(25)),
        ("torus-features-1e5", || feature_torus(79)),
        ("grid-1e4", || samples::grid(100, 100)),
        ("grid-1e5", || samples::grid(316, 316)),
        ("feature-mix-1e4", || samples::feature_mix(10_000)),
        ("icosphere-1280", || samples::icosphere(3)),
        ("icosphere-5120", || samples::icosphere(4)),
        ("globe(8,12)", || samples::globe(8, 12)),
        ("mushroom", samples::mushroom),
        ("hand", samples::hand),
        ("rounded_cube(6)", || samples::rounded_cube(6)),
        ("cube", samples::cube),
        ("two_beam_corner", samples::two_beam_corner),
        ("triangle_and_pentagon", samples::triangle_and_pentagon_mesh),
    ];
    makers
        .into_iter()
        .filter(|(name, _)| keep(name))
        .map(|(name, make)| Case { name, mesh: make() })
        .collect()
}

fn options() -> PlanOptions<'static> {
    PlanOptions {
        depth: DEPTH,
        ..Default::default()
    }
}

/// The measured analysis, under a fixed symbol for callgrind.
#[no_mangle]
#[inline(never)]
fn capdiv_analyse(mesh: &MeshInput) -> SurfacePlan<'static> {
    SurfacePlan::for_mesh(mesh, options()).expect("capdiv analyses the mesh")
}

/// The helper's `key value` lines.
fn run_helper(helper: &Path, job: &Path) -> BTreeMap<String, f64> {
    let out = Command::new(helper)
        .arg(job)
        .output()
        .expect("run the OpenSubdiv helper");
    assert!(
        out.status.success(),
        "OpenSubdiv helper failed on {}:\n{}",
        job.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let (k, v) = l.split_once(' ')?;
            Some((k.to_string(), v.trim().parse().ok()?))
        })
        .collect()
}

struct Row {
    name: &'static str,
    faces: usize,
    capdiv_ns: f64,
    capdiv_samples: usize,
    topology_ns: f64,
    osd: BTreeMap<String, f64>,
    patches: BTreeMap<u32, usize>,
    uncovered: usize,
    steps: usize,
}

fn levels(total: f64, by: impl Iterator<Item = (u32, f64)>) -> String {
    by.filter(|&(_, n)| n > 0.0)
        .map(|(l, n)| format!("{l}: {:.0}%", 100.0 * n / total))
        .collect::<Vec<_>>()
        .join(", ")
}

fn measure(case: &Case, helper: &Path) -> Row {
    let faces = case.mesh.faces.len();
    let (capdiv, capdiv_samples) = time(|| {
        black_box(capdiv_analyse(black_box(&case.mesh)));
    });
    let (topology, _) = time(|| {
        black_box(Topology::new(black_box(&case.mesh)).ok());
    });
    let plan = capdiv_analyse(&case.mesh);
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut stats = SurfaceStats::new();
    ev.evaluate(&case.mesh.vertices, &mut stats)
        .expect("evaluate");
    // The levels that have patches.
    let by_level = (0u32..).zip(stats.levels).filter(|&(_, n)| n > 0).collect();
    let osd = run_helper(helper, &job_file(case.name, &case.mesh));
    Row {
        name: case.name,
        faces,
        capdiv_ns: capdiv * 1e9,
        capdiv_samples,
        topology_ns: topology * 1e9,
        osd,
        patches: by_level,
        uncovered: plan.uncovered.len(),
        steps: plan.steps.len(),
    }
}

fn print_tables(rows: &[Row]) {
    println!("### Analysis per input face (wall clock, median)\n");
    println!(
        "| mesh | faces | capdiv `for_mesh` ns/face | (its `Topology::new`) | OSD Create | \
         OSD RefineAdaptive | OSD PatchTable | OSD PatchMap | OSD total ns/face | \
         capdiv / OSD |"
    );
    println!("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    for r in rows {
        let f = r.faces as f64;
        let o = |k: &str| r.osd.get(k).copied().unwrap_or(f64::NAN) / f;
        println!(
            "| {} | {} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} |",
            r.name,
            r.faces,
            r.capdiv_ns / f,
            r.topology_ns / f,
            o("create_ns"),
            o("refine_ns"),
            o("table_ns"),
            o("map_ns"),
            o("total_ns"),
            r.capdiv_ns / r.osd["total_ns"],
        );
    }
    println!("\n### Patches per input face\n");
    println!(
        "| mesh | faces | capdiv patches/face | OSD patches/face | capdiv by level | \
         OSD by depth | OSD end caps/face | capdiv steps, uncovered |"
    );
    println!("|---|--:|--:|--:|---|---|--:|---|");
    for r in rows {
        let f = r.faces as f64;
        let capdiv: usize = r.patches.values().sum();
        let osd = r.osd["patches"];
        let osd_levels = (0..=20u32).filter_map(|d| Some((d, *r.osd.get(&format!("depth{d}"))?)));
        println!(
            "| {} | {} | {:.2} | {:.2} | {} | {} | {:.3} | {}, {} |",
            r.name,
            r.faces,
            capdiv as f64 / f,
            osd / f,
            levels(
                capdiv as f64,
                r.patches.iter().map(|(&l, &n)| (l, n as f64))
            ),
            levels(osd, osd_levels),
            r.osd["endcap"] / f,
            r.steps,
            r.uncovered,
        );
    }
    let samples: Vec<String> = rows
        .iter()
        .map(|r| format!("{}/{}", r.capdiv_samples, r.osd["samples"]))
        .collect();
    println!(
        "\nSamples (capdiv/OSD) per mesh: {}. Ratio > 1: capdiv's analysis is slower.",
        samples.join(", ")
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1).cloned())
    };
    if let Some(name) = value("--once") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        let plan = capdiv_analyse(&case.mesh);
        println!("faces {}", case.mesh.faces.len());
        println!("regular {}", plan.regular.len());
        return;
    }
    if let Some(name) = value("--prepare") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        println!("helper {}", helper().display());
        println!("job {}", job_file(case.name, &case.mesh).display());
        println!("faces {}", case.mesh.faces.len());
        return;
    }
    let only = value("--only");
    let keep = |n: &str| only.as_ref().is_none_or(|o| o.split(',').any(|x| x == n));
    let helper = helper();
    let mut rows = Vec::new();
    for case in cases(&keep) {
        eprintln!("measuring {} ({} faces)", case.name, case.mesh.faces.len());
        rows.push(measure(&case, &helper));
    }
    print_tables(&rows);
}
