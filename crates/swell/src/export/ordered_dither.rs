//! Palette indices for an image by ordered (Bayer) dithering: a fixed 8 x 8 pattern of offsets,
//! added before the nearest palette colour is looked up, turns the steps between palette colours in
//! a smooth gradient (the sky, a calm sea) into a fine texture instead of bands. Unlike error
//! diffusion it does not make still parts of an animation crawl from frame to frame, it
//! compresses better, and every pixel is independent of the others, which keeps it fast.

use super::median_cut::CHANNEL_WEIGHTS;

/// The 8 x 8 Bayer threshold matrix: each of 0..63 once, neighbouring thresholds far apart.
const BAYER_8: [[u8; 8]; 8] = [
    [0, 32, 8, 40, 2, 34, 10, 42],
    [48, 16, 56, 24, 50, 18, 58, 26],
    [12, 44, 4, 36, 14, 46, 6, 38],
    [60, 28, 52, 20, 62, 30, 54, 22],
    [3, 35, 11, 43, 1, 33, 9, 41],
    [51, 19, 59, 27, 49, 17, 57, 25],
    [15, 47, 7, 39, 13, 45, 5, 37],
    [63, 31, 55, 23, 61, 29, 53, 21],
];

/// Bits per channel of the nearest-colour table: cells of 4 x 4 x 4 levels, fine enough beside the
/// dither's offsets, small enough (512 KiB) to stay in cache.
const TABLE_BITS: u32 = 6;

/// Palette indices (one byte per pixel) of an RGBA8 image `width` pixels wide (alpha ignored),
/// each the nearest `palette` colour (weighted distance of [`CHANNEL_WEIGHTS`]) to the pixel plus
/// the Bayer offset of its position. `palette` holds 1 to 256 colours.
///
/// The offsets' peak-to-peak amplitude, in levels, is the spacing of the palette where the pixel
/// is: the largest channel difference from the pixel's nearest colour to that colour's nearest
/// neighbour, at least the lookup table's cell (4 levels) and at most `max_amplitude` (0: no
/// dithering). One spacing is what turns a gradient between two colours into a mix whose mean is
/// the gradient; less leaves bands, more only adds grain. So a sea's crowded blues get a faint
/// dither and a sunset's sparser yellows a stronger one.
pub fn dither_to_palette(rgba: &[u8], width: usize, palette: &[[u8; 3]], max_amplitude: u8) -> Vec<u8> {
    debug_assert!((1..=256).contains(&palette.len()));
    // Offsets for an amplitude of 256 levels, in 1/256 levels: threshold t in [0, 63] becomes
    // (t + 1/2) / 64 - 1/2 of the amplitude, so the offsets are symmetric with mean zero.
    let offsets: [[i32; 8]; 8] =
        std::array::from_fn(|y| std::array::from_fn(|x| 2 * (2 * i32::from(BAYER_8[y][x]) - 63)));
    // Never under one table cell: colours closer than that share a cell, so the cells are the steps.
    let cell = 1u8 << (8 - TABLE_BITS);
    let amplitude: Vec<i32> = spacing(palette).into_iter().map(|s| i32::from(s.max(cell).min(max_amplitude))).collect();
    let mut table = vec![u16::MAX; 1 << (3 * TABLE_BITS)];
    let mut lookup = |r: i32, g: i32, b: i32| -> usize {
        let cell = |v: i32| (v.clamp(0, 255) as usize) >> (8 - TABLE_BITS);
        let key = cell(r) << (2 * TABLE_BITS) | cell(g) << TABLE_BITS | cell(b);
        if table[key] == u16::MAX {
            table[key] = nearest(palette, cell_centre(key)) as u16;
        }
        usize::from(table[key])
    };
    let mut indices = Vec::with_capacity(rgba.len() / 4);
    for (y, row) in rgba.chunks_exact(4 * width.max(1)).enumerate() {
        let offsets = &offsets[y % 8];
        for (x, p) in row.chunks_exact(4).enumerate() {
            let (r, g, b) = (i32::from(p[0]), i32::from(p[1]), i32::from(p[2]));
            let a = if max_amplitude == 0 { 0 } else { amplitude[lookup(r, g, b)] };
            // Rounded to the nearest level, as the table's cells are whole levels.
            let o = (offsets[x % 8] * a + 128) >> 8;
            indices.push(if a == 0 { lookup(r, g, b) } else { lookup(r + o, g + o, b + o) } as u8);
        }
    }
    indices
}

/// For each palette colour, the largest channel difference to its nearest other colour in that
/// measure (255 for a palette of one colour).
fn spacing(palette: &[[u8; 3]]) -> Vec<u8> {
    let chebyshev = |a: &[u8; 3], b: &[u8; 3]| (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0);
    palette
        .iter()
        .enumerate()
        .map(|(i, p)| {
            palette.iter().enumerate().filter(|&(j, _)| j != i).map(|(_, q)| chebyshev(p, q)).min().unwrap_or(255)
        })
        .collect()
}

/// Index of the `palette` colour nearest `rgb` (weighted squared distance; the first of equals).
fn nearest(palette: &[[u8; 3]], rgb: [i32; 3]) -> usize {
    let mut best = (i32::MAX, 0);
    for (i, p) in palette.iter().enumerate() {
        let mut d = 0;
        for c in 0..3 {
            let e = i32::from(p[c]) - rgb[c];
            d += CHANNEL_WEIGHTS[c] as i32 * e * e;
        }
        if d < best.0 {
            best = (d, i);
        }
    }
    best.1
}

/// The colour at the centre of table cell `key`, in levels.
fn cell_centre(key: usize) -> [i32; 3] {
    let mask = (1 << TABLE_BITS) - 1;
    let half = 1 << (7 - TABLE_BITS);
    std::array::from_fn(|c| (((key >> (TABLE_BITS as usize * (2 - c))) & mask) << (8 - TABLE_BITS)) as i32 + half)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bayer_matrix_holds_each_threshold_once() {
        let mut all: Vec<u8> = BAYER_8.iter().flatten().copied().collect();
        all.sort();
        assert_eq!(all, (0..64).collect::<Vec<u8>>());
    }

    #[test]
    fn without_dither_each_pixel_takes_its_nearest_colour() {
        let palette = [[0, 0, 0], [255, 255, 255], [200, 40, 40]];
        let rgba = [10, 10, 10, 255, 250, 240, 255, 255, 190, 50, 30, 255];
        assert_eq!(dither_to_palette(&rgba, 3, &palette, 0), [0, 1, 2]);
    }

    #[test]
    fn spacing_is_the_distance_to_the_nearest_other_colour() {
        assert_eq!(spacing(&[[0, 0, 0], [10, 4, 0], [100, 100, 100]]), [10, 10, 100]);
        assert_eq!(spacing(&[[7, 7, 7]]), [255]);
    }

    #[test]
    fn dithering_a_flat_grey_between_two_colours_keeps_its_mean() {
        // Greys between palette colours 64 and 128: an 8 x 8 block dithered with an amplitude of
        // their spacing takes the lighter one in proportion to the grey's distance from 64.
        let palette = [[64, 64, 64], [128, 128, 128]];
        for (grey, share) in [(80u8, 0.25), (96, 0.5), (112, 0.75)] {
            let rgba: Vec<u8> = (0..64).flat_map(|_| [grey, grey, grey, 255]).collect();
            let idx = dither_to_palette(&rgba, 8, &palette, 255);
            let ones = idx.iter().filter(|&&i| i == 1).count() as f64 / 64.0;
            assert!((ones - share).abs() <= 0.1, "grey {grey}: {ones} of the pixels took the lighter colour");
        }
    }

    #[test]
    fn cell_centres_are_inside_their_cells() {
        assert_eq!(cell_centre(0), [2, 2, 2]);
        assert_eq!(cell_centre((1 << 18) - 1), [254, 254, 254]);
        assert_eq!(cell_centre(1 << 12 | 2 << 6 | 3), [6, 10, 14]);
    }
}
