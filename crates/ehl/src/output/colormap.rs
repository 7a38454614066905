//! Perceptually uniform colour maps for the pictures: viridis and inferno (van der Walt & Smith,
//! matplotlib 2.0, CC0), sampled at eleven evenly spaced stops and interpolated linearly in sRGB,
//! which stays within a few units of the full 256-entry tables.

/// A colour map: `color(t)` for `t` in [0, 1] (clamped), as 8-bit sRGB.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorMap {
    /// dark blue-violet (low) to yellow (high): used for film
    Viridis,
    /// black (low) through red to pale yellow (high): used for pressure
    Inferno,
}

const VIRIDIS: [u32; 11] = [
    0x440154, 0x482475, 0x414487, 0x355f8d, 0x2a788e, 0x21918c, 0x22a884, 0x44bf70, 0x7ad151,
    0xbddf26, 0xfde725,
];
const INFERNO: [u32; 11] = [
    0x000004, 0x160b39, 0x420a68, 0x6a176e, 0x932667, 0xbc3754, 0xdd513a, 0xf37819, 0xfca50a,
    0xf6d746, 0xfcffa4,
];

impl ColorMap {
    /// Colour at `t` in [0, 1]; values outside are clamped, NaN gives the low end.
    pub fn color(self, t: f64) -> (u8, u8, u8) {
        let stops = match self {
            ColorMap::Viridis => &VIRIDIS,
            ColorMap::Inferno => &INFERNO,
        };
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let s = t * (stops.len() - 1) as f64;
        let k = (s.floor() as usize).min(stops.len() - 2);
        let f = s - k as f64;
        let ch = |c: u32, shift: u32| ((c >> shift) & 0xff) as f64;
        let mix = |shift| {
            let a = ch(stops[k], shift);
            let b = ch(stops[k + 1], shift);
            (a + f * (b - a)).round() as u8
        };
        (mix(16), mix(8), mix(0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_and_monotone_lightness() {
        assert_eq!(ColorMap::Viridis.color(0.0), (0x44, 0x01, 0x54));
        assert_eq!(ColorMap::Viridis.color(1.0), (0xfd, 0xe7, 0x25));
        assert_eq!(ColorMap::Inferno.color(-3.0), (0, 0, 4));
        // perceptual maps are monotone in lightness: use the Rec. 709 luma as a proxy
        for map in [ColorMap::Viridis, ColorMap::Inferno] {
            let luma = |t: f64| {
                let (r, g, b) = map.color(t);
                0.2126 * r as f64 + 0.7152 * g as f64 + 0.0722 * b as f64
            };
            for k in 0..100 {
                let (a, b) = (k as f64 / 100.0, (k + 1) as f64 / 100.0);
                assert!(luma(b) >= luma(a) - 0.5, "{map:?} at {a}");
            }
        }
    }
}
