//! The module's exports: a C-like ABI over one scene held by the module.
//!
//! Calls that can fail return `0` on success and `-1` on error; the error's
//! one-line message is then in the text buffer ([`viewer_text_ptr`],
//! [`viewer_text_len`]). Buffers are read through pointers into the module's
//! memory, valid until the next call that changes the scene (the page makes
//! fresh typed-array views after every call, as memory may also grow).
//!
//! Shading codes: 0 plain, 1 highlight lines, 2 Gaussian, 3 mean curvature.

use crate::input;
use crate::paint::{Mode, View};
use crate::samples::SAMPLES;
use crate::scene::{Options, Scene, Up};
use std::cell::RefCell;

#[derive(Default)]
struct State {
    scene: Option<Scene>,
    /// Text in (a dropped file) and out (messages, names, summaries).
    text: Vec<u8>,
    /// Control points as `f32` for drawing.
    control: Vec<f32>,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

fn with<T>(f: impl FnOnce(&mut State) -> T) -> T {
    STATE.with(|s| f(&mut s.borrow_mut()))
}

fn set_text(st: &mut State, s: &str) -> i32 {
    st.text.clear();
    st.text.extend_from_slice(s.as_bytes());
    st.text.len() as i32
}

fn status(st: &mut State, r: Result<(), String>) -> i32 {
    match r {
        Ok(()) => {
            if let Some(sc) = &st.scene {
                st.control.clear();
                st.control
                    .extend(sc.positions().iter().flatten().map(|&c| c as f32));
            }
            0
        }
        Err(e) => {
            set_text(st, &e);
            -1
        }
    }
}

fn options(depth: u32, catmull_clark: u32, grid: u32) -> Options {
    Options {
        depth,
        catmull_clark: catmull_clark != 0,
        grid: grid as usize,
    }
}

fn mode(code: i32) -> Result<Mode, String> {
    Mode::from_code(code).ok_or_else(|| format!("shading {code}: 0..=3"))
}

/// Number of samples.
#[no_mangle]
pub extern "C" fn viewer_sample_count() -> u32 {
    SAMPLES.len() as u32
}

/// Puts sample `i`'s name (`about = false`) or description into the text
/// buffer; returns its length, `-1` for no such sample.
#[no_mangle]
pub extern "C" fn viewer_sample_text(i: u32, about: u32) -> i32 {
    with(|st| match SAMPLES.get(i as usize) {
        Some(s) => set_text(st, if about != 0 { s.about } else { s.name }),
        None => -1,
    })
}

/// Shows sample `i` with the given depth, scheme (`catmull_clark` ≠ 0:
/// Catmull-Clark caps), grid and shading. On error the previous scene stays.
#[no_mangle]
pub extern "C" fn viewer_load_sample(
    i: u32,
    depth: u32,
    catmull_clark: u32,
    grid: u32,
    shading: i32,
) -> i32 {
    with(|st| {
        let r = (|| {
            let s = SAMPLES
                .get(i as usize)
                .ok_or_else(|| format!("sample {i}: there are {}", SAMPLES.len()))?;
            let scene = Scene::new(
                s.name,
                (s.build)(),
                options(depth, catmull_clark, grid),
                mode(shading)?,
            )?;
            st.scene = Some(scene);
            Ok(())
        })();
        status(st, r)
    })
}

/// Room for `len` bytes of a dropped file's text; the page writes the UTF-8
/// bytes there, then calls [`viewer_load_text`].
#[no_mangle]
pub extern "C" fn viewer_text_alloc(len: u32) -> *mut u8 {
    with(|st| {
        st.text.clear();
        st.text.resize(len as usize, 0);
        st.text.as_mut_ptr()
    })
}

/// Shows the mesh of the text in the buffer (OBJ or JSON, see
/// [`crate::input`]). On error the previous scene stays and the buffer holds
/// the message.
#[no_mangle]
pub extern "C" fn viewer_load_text(depth: u32, catmull_clark: u32, grid: u32, shading: i32) -> i32 {
    with(|st| {
        let r = (|| {
            let text = std::str::from_utf8(&st.text)
                .map_err(|e| format!("not UTF-8 text (byte {})", e.valid_up_to()))?;
            let mesh = input::parse(text)?;
            let scene = Scene::new(
                "file",
                mesh,
                options(depth, catmull_clark, grid),
                mode(shading)?,
            )?;
            st.scene = Some(scene);
            Ok(())
        })();
        status(st, r)
    })
}

fn on_scene(f: impl FnOnce(&mut Scene) -> Result<(), String>) -> i32 {
    with(|st| {
        let r = match st.scene.as_mut() {
            Some(sc) => f(sc),
            None => Err("no mesh loaded".into()),
        };
        status(st, r)
    })
}

/// New depth, scheme or grid (a new plan).
#[no_mangle]
pub extern "C" fn viewer_set_options(depth: u32, catmull_clark: u32, grid: u32) -> i32 {
    on_scene(|sc| sc.set_options(options(depth, catmull_clark, grid)))
}

/// New shading (its colour scale recomputed).
#[no_mangle]
pub extern "C" fn viewer_set_shading(shading: i32) -> i32 {
    on_scene(|sc| {
        sc.set_mode(mode(shading)?);
        Ok(())
    })
}

/// Moves control point `vertex` to `(x, y, z)` and re-evaluates the surface
/// through the analysed plan.
#[no_mangle]
pub extern "C" fn viewer_move_vertex(vertex: u32, x: f64, y: f64, z: f64) -> i32 {
    on_scene(|sc| sc.move_vertex(vertex as usize, [x, y, z]))
}

/// Recomputes the colour scale and light lines (after a drag).
#[no_mangle]
pub extern "C" fn viewer_rescale() -> i32 {
    on_scene(|sc| {
        sc.rescale();
        Ok(())
    })
}

/// The axis shown upward: 0 `z`, 1 `y` (the highlight lines' light plane
/// lies above the surface along it). Repaints the whole surface.
#[no_mangle]
pub extern "C" fn viewer_set_up(axis: u32) -> i32 {
    on_scene(|sc| {
        let up = match axis {
            0 => Up::Z,
            1 => Up::Y,
            _ => return Err(format!("up axis {axis}: 0 (z) or 1 (y)")),
        };
        sc.set_up(up);
        Ok(())
    })
}

/// The view the highlight lines are spaced in: the orbit target
/// `(x, y, z)`, the world length `height` the picture's height spans at its
/// depth, and `lines` line spacings across that height. Under the highlight
/// shading only the per-vertex highlight parameters change (re-read them
/// with [`viewer_stripes`]).
#[no_mangle]
pub extern "C" fn viewer_set_view(x: f64, y: f64, z: f64, height: f64, lines: f64) -> i32 {
    on_scene(|sc| {
        sc.set_view(View {
            target: [x, y, z],
            height,
            lines,
        })
    })
}

/// Light-line spacings across the picture's height by default (the CLI's
/// `--lines` default, [`capdiv_mesh::shade::DEFAULT_LINES`]).
#[no_mangle]
pub extern "C" fn viewer_default_lines() -> f64 {
    capdiv_mesh::shade::DEFAULT_LINES
}

/// Puts Wavefront OBJ text into the text buffer: `what` 0 the control mesh
/// with its edited positions ([`Scene::control_obj`]), 1 the surface
/// ([`Scene::surface_obj`]). Returns its length, or `-1` (message in the
/// buffer).
#[no_mangle]
pub extern "C" fn viewer_export_obj(what: u32) -> i32 {
    with(|st| {
        let text = match (what, st.scene.as_ref()) {
            (_, None) => Err("no mesh loaded".to_string()),
            (0, Some(sc)) => Ok(sc.control_obj()),
            (1, Some(sc)) => sc.surface_obj(),
            _ => Err(format!("export {what}: 0 (control mesh) or 1 (surface)")),
        };
        match text {
            Ok(t) => set_text(st, &t),
            Err(e) => {
                set_text(st, &e);
                -1
            }
        }
    })
}

/// Control points back to the file's positions.
#[no_mangle]
pub extern "C" fn viewer_reset() -> i32 {
    on_scene(Scene::reset_positions)
}

/// Puts the scene's summary (JSON) into the text buffer; returns its length.
#[no_mangle]
pub extern "C" fn viewer_summary() -> i32 {
    with(|st| match st.scene.as_ref().map(Scene::summary) {
        Some(s) => set_text(st, &s),
        None => set_text(st, "null"),
    })
}

/// The text buffer.
#[no_mangle]
pub extern "C" fn viewer_text_ptr() -> *const u8 {
    with(|st| st.text.as_ptr())
}

/// Bytes in the text buffer.
#[no_mangle]
pub extern "C" fn viewer_text_len() -> u32 {
    with(|st| st.text.len() as u32)
}

fn scene_value<T: Default>(f: impl FnOnce(&Scene) -> T) -> T {
    with(|st| st.scene.as_ref().map(f).unwrap_or_default())
}

/// Surface vertices.
#[no_mangle]
pub extern "C" fn viewer_vertex_count() -> u32 {
    scene_value(|s| s.surface().len() as u32)
}

/// Triangle indices (3 per triangle).
#[no_mangle]
pub extern "C" fn viewer_index_count() -> u32 {
    scene_value(|s| s.surface().indices.len() as u32)
}

/// `3·vertices` `f32` positions.
#[no_mangle]
pub extern "C" fn viewer_positions() -> *const f32 {
    scene_value(|s| s.paint.positions.as_ptr())
}

/// `3·vertices` `f32` unit normals.
#[no_mangle]
pub extern "C" fn viewer_normals() -> *const f32 {
    scene_value(|s| s.paint.normals.as_ptr())
}

/// `4·vertices` RGBA bytes.
#[no_mangle]
pub extern "C" fn viewer_colors() -> *const u8 {
    scene_value(|s| s.paint.colors.as_ptr())
}

/// `vertices` `f32` highlight-line parameters.
#[no_mangle]
pub extern "C" fn viewer_stripes() -> *const f32 {
    scene_value(|s| s.paint.stripes.as_ptr())
}

/// `u32` triangle indices.
#[no_mangle]
pub extern "C" fn viewer_indices() -> *const u32 {
    scene_value(|s| s.surface().indices.as_ptr())
}

/// First vertex rewritten by the last call (an edit rewrites only the
/// patches around the moved point).
#[no_mangle]
pub extern "C" fn viewer_dirty_first() -> u32 {
    scene_value(|s| s.dirty().0 as u32)
}

/// One past the last vertex rewritten by the last call.
#[no_mangle]
pub extern "C" fn viewer_dirty_end() -> u32 {
    scene_value(|s| s.dirty().1 as u32)
}

/// Control points.
#[no_mangle]
pub extern "C" fn viewer_control_count() -> u32 {
    scene_value(|s| s.positions().len() as u32)
}

/// `3·control points` `f32` positions.
#[no_mangle]
pub extern "C" fn viewer_control_points() -> *const f32 {
    with(|st| st.control.as_ptr())
}

/// Control-mesh edges (2 indices each).
#[no_mangle]
pub extern "C" fn viewer_edge_count() -> u32 {
    scene_value(|s| (s.edges.len() / 2) as u32)
}

/// `2·edges` `u32` control-point indices.
#[no_mangle]
pub extern "C" fn viewer_edges() -> *const u32 {
    scene_value(|s| s.edges.as_ptr())
}

/// Colour scale `m` of the curvature shadings.
#[no_mangle]
pub extern "C" fn viewer_scale() -> f64 {
    scene_value(Scene::scale)
}

/// Bounding box coordinate `k` (0..3 low corner, 3..6 high corner) of the
/// surface; 0 without a scene.
#[no_mangle]
pub extern "C" fn viewer_bounds(k: u32) -> f64 {
    scene_value(|s| match k {
        0..=2 => s.surface().lo[k as usize],
        3..=5 => s.surface().hi[k as usize - 3],
        _ => 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text() -> String {
        let (p, n) = (viewer_text_ptr(), viewer_text_len() as usize);
        // SAFETY: the module's own buffer, `n` bytes, not changed meanwhile.
        String::from_utf8(unsafe { std::slice::from_raw_parts(p, n) }.to_vec()).unwrap()
    }

    fn load_text(s: &str) -> i32 {
        let p = viewer_text_alloc(s.len() as u32);
        // SAFETY: `p` has room for `s.len()` bytes.
        unsafe { std::ptr::copy_nonoverlapping(s.as_ptr(), p, s.len()) };
        viewer_load_text(3, 0, 8, 0)
    }

    #[test]
    fn a_page_session_through_the_exports() {
        // Each test thread has its own state.
        assert_eq!(viewer_vertex_count(), 0);
        assert_eq!(viewer_set_shading(1), -1);
        assert_eq!(text(), "no mesh loaded");
        let n = viewer_sample_count();
        assert!(n >= 8);
        assert!(viewer_sample_text(0, 0) > 0);
        assert_eq!(text(), SAMPLES[0].name);
        assert_eq!(viewer_sample_text(n, 0), -1);

        assert_eq!(viewer_load_sample(1, 3, 0, 8, 0), 0);
        let (vc, ic) = (viewer_vertex_count(), viewer_index_count());
        assert!(vc > 0 && ic > 0 && ic % 3 == 0);
        assert_eq!(viewer_control_count(), 8 * 9 + 2);
        assert!(viewer_edge_count() > 0);
        assert!(viewer_bounds(5) > viewer_bounds(2));
        // SAFETY: the module's buffers of the documented lengths.
        let colors = |k| unsafe { std::slice::from_raw_parts(viewer_colors(), 4 * k).to_vec() };
        let plain = colors(vc as usize);
        assert_eq!(viewer_set_shading(2), 0);
        assert_ne!(colors(vc as usize), plain);
        assert!(viewer_scale() > 0.0);
        assert_eq!(viewer_set_shading(9), -1);

        // An edit of control point 0 moves its copy and the surface.
        let first = |p: *const f32| unsafe { *p };
        let c0 = first(viewer_control_points());
        assert_eq!(viewer_move_vertex(0, c0 as f64 + 0.3, 0.0, 0.0), 0);
        assert_eq!(first(viewer_control_points()), c0 + 0.3);
        assert_eq!(viewer_vertex_count(), vc);
        assert_eq!(viewer_move_vertex(1 << 20, 0.0, 0.0, 0.0), -1);
        assert!(text().contains("vertex"));
        assert_eq!(viewer_reset(), 0);
        assert_eq!(first(viewer_control_points()), c0);

        // A broken file: a message, and the globe is still there.
        assert_eq!(load_text("{\"kind\": \"mesh\", \"vertices\": 3}"), -1);
        assert!(text().starts_with("JSON"), "{}", text());
        assert_eq!(viewer_vertex_count(), vc);
        assert!(viewer_summary() > 0);
        assert!(text().contains("\"globe\""));

        // A good one replaces it.
        let torus = capdiv_mesh::samples::torus(6, 5);
        let mut obj = String::new();
        for v in &torus.vertices {
            obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
        }
        for f in &torus.faces {
            let corners: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
            obj += &format!("f {}\n", corners.join(" "));
        }
        assert_eq!(load_text(&obj), 0, "{}", text());
        assert_eq!(viewer_control_count(), 30);
        assert!(viewer_summary() > 0);
        assert!(text().contains("\"file\""));
    }
}
