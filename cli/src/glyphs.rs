//! Text in pictures: the 8×8 font of the `font8x8` crate drawn into a
//! row-major RGB buffer, clipped to it.

use font8x8::UnicodeFonts;

/// Draws `s` into `rgb` (`width × height` pixels, 3 bytes each) with its top
/// left at `(x, y)`, `size` pixels per font pixel, in colour `c`; what falls
/// outside the buffer is dropped. Characters without a glyph are skipped.
#[allow(clippy::too_many_arguments)] // a buffer, its size, a place, a text, a style
pub fn text(
    rgb: &mut [u8],
    width: usize,
    height: usize,
    (x, y): (usize, usize),
    s: &str,
    size: usize,
    c: [u8; 3],
) {
    let mut put = |px: usize, py: usize| {
        if px < width && py < height {
            let k = 3 * (py * width + px);
            if let Some(p) = rgb.get_mut(k..k + 3) {
                p.copy_from_slice(&c);
            }
        }
    };
    for (i, ch) in s.chars().enumerate() {
        let Some(glyph) = font8x8::BASIC_FONTS.get(ch) else {
            continue;
        };
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits & (1 << col) != 0 {
                    for dy in 0..size {
                        for dx in 0..size {
                            put(x + (8 * i + col) * size + dx, y + row * size + dy);
                        }
                    }
                }
            }
        }
    }
}
