//! The CLI's pictures as a user meets them: one set of defaults (depth 4,
//! 800×600) for `surface`, `render` and `compare`.
mod common;

use common::*;

fn png_size(path: &std::path::Path) -> (usize, usize) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let info = dec.read_info().unwrap();
    let i = info.info();
    (i.width as usize, i.height as usize)
}

/// Without `--depth` and `--size`: `surface` reports depth 4; `render`
/// draws 800×600 and the same bytes as with `--depth 4 --size 800x600`
/// (and other bytes than `--depth 3`, so the depth is not ignored);
/// `compare` draws 800-pixel panels; each command's `--help` states the
/// defaults.
#[test]
fn one_set_of_defaults() {
    let dir = tempdir();
    let mesh = write_json(
        dir.path(),
        "cube.json",
        &serde_json::json!({
            "kind": "mesh",
            "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]],
            "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]
        }),
    );
    let sum = capdiv(&["surface", "--quiet", s(&mesh)], None).ok_json();
    assert_eq!(sum["summary"]["depth"], 4);

    let out = |n: &str| dir.path().join(n);
    let render = |extra: &[&str], name: &str| {
        let mut args = vec!["render", "--shade", "mean", "sample:eg-saddle-n5"];
        args.extend_from_slice(extra);
        let path = out(name);
        args.extend_from_slice(&["-o", s(&path)]);
        capdiv(&args, None).assert_ok();
        std::fs::read(out(name)).unwrap()
    };
    let plain = render(&[], "default.png");
    assert_eq!(png_size(&out("default.png")).0, 800);
    // The legend strip is under the 600 rows of the picture.
    assert!(png_size(&out("default.png")).1 > 600);
    let explicit = render(&["--depth", "4", "--size", "800x600"], "explicit.png");
    assert_eq!(plain, explicit, "the defaults are not depth 4, 800x600");
    let shallower = render(&["--depth", "3"], "depth3.png");
    assert_ne!(plain, shallower, "--depth changes nothing");

    let run = capdiv(
        &["compare", "sample:eg-saddle-n5", "-o", s(&out("c.png"))],
        None,
    );
    run.assert_ok();
    // Two panels (EG, Catmull-Clark) and an 8-pixel gap.
    assert_eq!(png_size(&out("c.png")).0, 2 * 800 + 8);

    for cmd in ["surface", "render", "compare"] {
        let help = capdiv(&[cmd, "--help"], None).stdout_str();
        let depth = help
            .split("--depth")
            .nth(1)
            .unwrap_or_else(|| panic!("{cmd}: no --depth"));
        let depth = &depth[..depth.find("\n  -").unwrap_or(depth.len())];
        assert!(depth.contains("[default: 4]"), "{cmd}: {depth}");
        if cmd != "surface" {
            assert!(help.contains("[default: 800x600]"), "{cmd}: {help}");
        }
    }
}
