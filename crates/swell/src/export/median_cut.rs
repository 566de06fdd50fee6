//! A palette of at most 256 colours for one image, by variance-minimising median cut (Heckbert
//! 1982, with Wan, Wong and Prusinkiewicz's 1988 choice of box and cut): GIF frames hold palette
//! indices, and the palette decides how much of a sea's smooth gradients survive.
//!
//! It replaces NeuQuant (`gif::Frame::from_rgba_speed` at speed 10), which took about 60 ms a
//! 1280 x 720 frame, three times the frame's rendering; this takes about 2.5 ms (the sort of a
//! quarter of the pixels), the dither 4 ms and the LZW compression 8 ms.

/// Weights of the red, green and blue differences in the colour distance the palette minimises
/// (the eye tells greens apart best and blues worst; the ratios of common quantisers, e.g. pngquant's).
pub const CHANNEL_WEIGHTS: [u32; 3] = [3, 4, 2];

/// Pixels the palette is computed from at most: larger images are sampled on a regular grid, which
/// keeps the sort below a few milliseconds while every colour region of a frame still counts.
const MAX_SAMPLES: usize = 1 << 18;

/// The palette of an RGBA8 image (`width` pixels a row, top row first, alpha ignored): at most
/// `max_colours` colours (in [1, 256]), each the mean of the sampled pixels in its box, in an
/// order fixed by the pixels alone. `exact` is true when the image holds no more than `max_colours` colours and
/// every pixel was looked at, so the palette holds each of them exactly.
pub fn median_cut_palette(rgba: &[u8], width: usize, max_colours: usize) -> (Vec<[u8; 3]>, bool) {
    debug_assert!((1..=256).contains(&max_colours));
    let pixels = rgba.len() / 4;
    let height = pixels / width.max(1);
    // A step s samples every s-th pixel of every s-th row, shifted by half a step on alternate
    // sampled rows so that vertical features are not all missed.
    let step = (1..).find(|s| (pixels / (s * s)) <= MAX_SAMPLES).unwrap_or(1);
    let mut colours: Vec<u32> = Vec::with_capacity(pixels.min(MAX_SAMPLES + width));
    for (i, y) in (0..height).step_by(step).enumerate() {
        let row = &rgba[4 * y * width..4 * (y + 1) * width];
        let shift = if i % 2 == 1 { step / 2 } else { 0 };
        for p in row.chunks_exact(4).skip(shift).step_by(step) {
            colours.push(u32::from(p[0]) << 16 | u32::from(p[1]) << 8 | u32::from(p[2]));
        }
    }
    colours.sort_unstable();
    let mut entries: Vec<Entry> = Vec::new();
    for c in colours {
        match entries.last_mut() {
            Some(e) if e.colour == c => e.count += 1,
            _ => entries.push(Entry { colour: c, count: 1 }),
        }
    }
    if entries.len() <= max_colours {
        let palette = entries.iter().map(|e| e.rgb()).collect();
        return (palette, step == 1);
    }
    let mut boxes = vec![ColourBox::new(&entries, 0, entries.len())];
    while boxes.len() < max_colours {
        // Split the box holding the largest squared error: where one more colour helps the most.
        let Some((i, _)) =
            boxes.iter().enumerate().filter(|(_, b)| b.end - b.start > 1).max_by(|a, b| a.1.sse.total_cmp(&b.1.sse))
        else {
            break;
        };
        let b = boxes.swap_remove(i);
        let (left, right) = b.split(&mut entries);
        boxes.push(left);
        boxes.push(right);
    }
    let palette = boxes.iter().map(ColourBox::mean).collect();
    (palette, false)
}

/// One distinct colour of the sample and how often it occurs.
#[derive(Clone, Copy)]
struct Entry {
    /// `r << 16 | g << 8 | b`.
    colour: u32,
    count: u32,
}

impl Entry {
    fn rgb(&self) -> [u8; 3] {
        [(self.colour >> 16) as u8, (self.colour >> 8) as u8, self.colour as u8]
    }
}

/// Running sums of a set of entries: count, per-channel sum and sum of squares.
#[derive(Clone, Copy, Default)]
struct Moments {
    count: u64,
    sum: [u64; 3],
    sum_sq: [u64; 3],
}

impl Moments {
    fn add(&mut self, e: &Entry) {
        let n = u64::from(e.count);
        self.count += n;
        for (c, v) in e.rgb().into_iter().enumerate() {
            let v = u64::from(v);
            self.sum[c] += n * v;
            self.sum_sq[c] += n * v * v;
        }
    }

    fn minus(&self, o: &Moments) -> Moments {
        Moments {
            count: self.count - o.count,
            sum: std::array::from_fn(|c| self.sum[c] - o.sum[c]),
            sum_sq: std::array::from_fn(|c| self.sum_sq[c] - o.sum_sq[c]),
        }
    }

    /// Weighted squared error of channel `c` about its mean.
    fn channel_sse(&self, c: usize) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let s = self.sum[c] as f64;
        f64::from(CHANNEL_WEIGHTS[c]) * (self.sum_sq[c] as f64 - s * s / self.count as f64)
    }

    /// Weighted squared error of the colours about their mean, all channels.
    fn sse(&self) -> f64 {
        (0..3).map(|c| self.channel_sse(c)).sum()
    }
}

/// The entries `start..end` (of the list being partitioned) and their moments.
struct ColourBox {
    start: usize,
    end: usize,
    moments: Moments,
    sse: f64,
}

impl ColourBox {
    fn new(entries: &[Entry], start: usize, end: usize) -> Self {
        let mut moments = Moments::default();
        entries[start..end].iter().for_each(|e| moments.add(e));
        Self::with_moments(start, end, moments)
    }

    fn with_moments(start: usize, end: usize, moments: Moments) -> Self {
        Self { start, end, moments, sse: moments.sse() }
    }

    /// The box's mean colour, rounded.
    fn mean(&self) -> [u8; 3] {
        let n = self.moments.count.max(1);
        std::array::from_fn(|c| ((self.moments.sum[c] + n / 2) / n).min(255) as u8)
    }

    /// Cuts the box across its channel of largest spread, where the two halves' summed squared
    /// error is least (not at the median count, which spends colours on crowded flat regions).
    fn split(self, entries: &mut [Entry]) -> (ColourBox, ColourBox) {
        let axis = (0..3).max_by(|&a, &b| self.moments.channel_sse(a).total_cmp(&self.moments.channel_sse(b)));
        let shift = 16 - 8 * axis.expect("three channels");
        let part = &mut entries[self.start..self.end];
        // Ties broken by the whole colour: the order, hence the palette, is the same on every run.
        part.sort_unstable_by_key(|e| ((e.colour >> shift) & 0xff, e.colour));
        let mut left = Moments::default();
        let mut best = (f64::INFINITY, 1, Moments::default());
        for (i, e) in part[..part.len() - 1].iter().enumerate() {
            left.add(e);
            // Cut only between different values of the axis, so both halves are boxes.
            if (e.colour >> shift) & 0xff == (part[i + 1].colour >> shift) & 0xff {
                continue;
            }
            let error = left.sse() + self.moments.minus(&left).sse();
            if error < best.0 {
                best = (error, i + 1, left);
            }
        }
        if !best.0.is_finite() {
            // Every entry has the same value on the axis of largest spread: impossible unless the
            // spread is zero there, and then any cut in the sorted order will do.
            let mut left = Moments::default();
            part[..part.len() / 2].iter().for_each(|e| left.add(e));
            best = (0.0, part.len() / 2, left);
        }
        let (_, at, left) = best;
        let mid = self.start + at;
        (
            ColourBox::with_moments(self.start, mid, left),
            ColourBox::with_moments(mid, self.end, self.moments.minus(&left)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(pixels: &[[u8; 3]]) -> Vec<u8> {
        pixels.iter().flat_map(|p| [p[0], p[1], p[2], 255]).collect()
    }

    #[test]
    fn few_colours_are_kept_exactly() {
        let px = [[10, 20, 30], [200, 100, 0], [10, 20, 30], [0, 0, 255]];
        let (palette, exact) = median_cut_palette(&image(&px), 2, 256);
        assert!(exact);
        assert_eq!(palette.len(), 3);
        for p in px {
            assert!(palette.contains(&p));
        }
    }

    #[test]
    fn a_gradient_gets_evenly_spread_colours() {
        // 1024 greys in a ramp, 16 colours: each should cover about 64 levels.
        let px: Vec<[u8; 3]> = (0..1024).map(|i| [(i / 4) as u8; 3]).collect();
        let (mut palette, exact) = median_cut_palette(&image(&px), 1024, 16);
        assert!(!exact);
        assert_eq!(palette.len(), 16);
        palette.sort();
        for w in palette.windows(2) {
            let gap = i32::from(w[1][0]) - i32::from(w[0][0]);
            assert!((12..=20).contains(&gap), "{palette:?}");
        }
    }

    #[test]
    fn the_palette_does_not_depend_on_the_input_order_of_equal_colours() {
        let px: Vec<[u8; 3]> =
            (0..4096u32).map(|i| [(i * 7 % 256) as u8, (i * 13 % 256) as u8, (i % 256) as u8]).collect();
        let mut rev = px.clone();
        rev.reverse();
        let mut a = median_cut_palette(&image(&px), 64, 256).0;
        let mut b = median_cut_palette(&image(&rev), 64, 256).0;
        a.sort();
        b.sort();
        assert_eq!(a, b);
    }
}
