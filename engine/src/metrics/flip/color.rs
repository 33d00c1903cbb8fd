//! Colour spaces used by FLIP: linear sRGB, CIE XYZ (D65), the YCxCz
//! opponent space, and Hunt-adjusted CIELAB with the HyAB distance.

/// Linear sRGB → XYZ (D65), the exact rational form of the sRGB matrix.
const RGB_TO_XYZ: [[f32; 3]; 3] = [
    [
        10_135_552.0 / 24_577_794.0,
        8_788_810.0 / 24_577_794.0,
        4_435_075.0 / 24_577_794.0,
    ],
    [
        2_613_072.0 / 12_288_897.0,
        8_788_810.0 / 12_288_897.0,
        887_015.0 / 12_288_897.0,
    ],
    [
        1_425_312.0 / 73_733_382.0,
        8_788_810.0 / 73_733_382.0,
        70_074_185.0 / 73_733_382.0,
    ],
];

/// XYZ (D65) → linear sRGB, the inverse of [`RGB_TO_XYZ`].
const XYZ_TO_RGB: [[f32; 3]; 3] = [
    [3.241_003_3, -1.537_398_9, -0.498_615_86],
    [-0.969_224_3, 1.875_930_1, 0.041_554_224],
    [0.055_639_423, -0.204_011_2, 1.057_148_9],
];

/// XYZ of the D65 white point (the image of RGB (1, 1, 1)).
const WHITE: [f32; 3] = [0.950_428_5, 1.0, 1.088_900_4];

#[inline]
fn mul(m: &[[f32; 3]; 3], v: [f32; 3]) -> [f32; 3] {
    let row = |r: &[f32; 3]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    [row(&m[0]), row(&m[1]), row(&m[2])]
}

/// Linear sRGB → YCxCz: the linear-luminance opponent space that FLIP's
/// contrast-sensitivity filters operate in.
pub(super) fn linear_rgb_to_ycxcz(rgb: [f32; 3]) -> [f32; 3] {
    let [x, y, z] = mul(&RGB_TO_XYZ, rgb);
    let (x, y, z) = (x / WHITE[0], y / WHITE[1], z / WHITE[2]);
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// YCxCz → linear sRGB, the inverse of [`linear_rgb_to_ycxcz`].
pub(super) fn ycxcz_to_linear_rgb(ycxcz: [f32; 3]) -> [f32; 3] {
    let y = (ycxcz[0] + 16.0) / 116.0;
    let xyz = [
        (y + ycxcz[1] / 500.0) * WHITE[0],
        y * WHITE[1],
        (y - ycxcz[2] / 200.0) * WHITE[2],
    ];
    mul(&XYZ_TO_RGB, xyz)
}

/// Relative luminance in `[0, 1]` carried by a YCxCz value's first channel.
pub(super) fn ycxcz_luminance(y: f32) -> f32 {
    (y + 16.0) / 116.0
}

/// Linear sRGB → CIELAB (D65) with FLIP's Hunt adjustment, which scales the
/// chromatic axes by `L / 100` so that colour differences shrink in the dark.
pub(super) fn linear_rgb_to_hunt_lab(rgb: [f32; 3]) -> [f32; 3] {
    const DELTA: f32 = 6.0 / 29.0;
    let f = |t: f32| {
        if t > DELTA * DELTA * DELTA {
            t.cbrt()
        } else {
            t / (3.0 * DELTA * DELTA) + 4.0 / 29.0
        }
    };
    let [x, y, z] = mul(&RGB_TO_XYZ, rgb);
    let (fx, fy, fz) = (f(x / WHITE[0]), f(y / WHITE[1]), f(z / WHITE[2]));
    let l = 116.0 * fy - 16.0;
    let hunt = 0.01 * l;
    [l, hunt * 500.0 * (fx - fy), hunt * 200.0 * (fy - fz)]
}

/// The HyAB distance: city-block in lightness plus Euclidean in the
/// chromatic plane.
pub(super) fn hyab(p: [f32; 3], q: [f32; 3]) -> f32 {
    let (dl, da, db) = (p[0] - q[0], p[1] - q[1], p[2] - q[2]);
    dl.abs() + (da * da + db * db).sqrt()
}
