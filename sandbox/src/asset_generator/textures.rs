//! The shipped material set: height fields from seeded procedures, albedo painted from the same
//! cells, normals by the plugin's Sobel filter at each material's height scale.

use pom::{HeightField, patterns};

/// Side of every shipped texture in texels.
pub const SIZE: u32 = 256;

/// One shipped material's maps and the parameters it is authored for.
pub struct MaterialMaps {
    /// Folder name under assets/.
    pub name: &'static str,
    /// The relief (1 = top).
    pub height: HeightField,
    /// sRGB albedo, row-major RGBA8.
    pub albedo: image::RgbaImage,
    /// Height range in texture units the normal map is made for.
    pub height_scale: f32,
}

/// A small, fast, seedable generator (SplitMix32), so the assets are the same on every machine.
pub struct Random(u32);

impl Random {
    /// A generator with `seed`.
    pub fn new(seed: u32) -> Self {
        Self(seed)
    }

    /// The next number in 0..1.
    pub fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9);
        let mut z = self.0;
        z = (z ^ (z >> 16)).wrapping_mul(0x85eb_ca6b);
        z = (z ^ (z >> 13)).wrapping_mul(0xc2b2_ae35);
        z ^= z >> 16;
        (z >> 8) as f32 / (1 << 24) as f32
    }
}

/// A deterministic value in 0..1 for an integer cell.
fn cell_noise(x: i32, y: i32, seed: u32) -> f32 {
    let mut random = Random::new(
        (x as u32).wrapping_mul(73_856_093) ^ (y as u32).wrapping_mul(19_349_663) ^ seed,
    );
    random.next()
}

/// Box blur with wrapping, `passes` times: T §5.6.1's advice to soften the height field so the
/// march misses fewer features.
fn soften(field: &HeightField, passes: u32) -> HeightField {
    let (width, height) = field.size();
    let mut current = field.clone();
    for _ in 0..passes {
        let values = (0..height as i64)
            .flat_map(|y| (0..width as i64).map(move |x| (x, y)))
            .map(|(x, y)| {
                let mut sum = 0.0;
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        sum += current.texel(x + dx, y + dy);
                    }
                }
                sum / 9.0
            })
            .collect();
        // Same size as the input, so this cannot fail.
        current = HeightField::new(width, height, values).expect("same size");
    }
    current
}

fn paint(field: &HeightField, color: impl Fn(u32, u32, f32) -> [f32; 3]) -> image::RgbaImage {
    image::RgbaImage::from_fn(SIZE, SIZE, |x, y| {
        let h = field.texel(i64::from(x), i64::from(y));
        let [r, g, b] = color(x, y, h);
        let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        image::Rgba([byte(r), byte(g), byte(b), 255])
    })
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    let t = t.clamp(0.0, 1.0);
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// Bricks with wide, soft grout (T §5.6.1): 4 × 8 running bond per tile.
pub fn bricks() -> MaterialMaps {
    let height = soften(&patterns::bricks(SIZE, 4.0, 8.0), 2);
    let albedo = paint(&height, |x, y, h| {
        let (u, v) = (x as f32 / SIZE as f32, y as f32 / SIZE as f32);
        let row = (v * 8.0).floor() as i32;
        let column = (u * 4.0 + if row % 2 == 0 { 0.0 } else { 0.5 }).floor() as i32;
        let tone = 0.8 + 0.35 * cell_noise(column.rem_euclid(4), row, 11);
        let grain = 0.92 + 0.08 * cell_noise(x as i32, y as i32, 12);
        let brick = [0.62 * tone * grain, 0.27 * tone * grain, 0.2 * tone * grain];
        mix([0.72, 0.7, 0.66], brick, h * 1.5)
    });
    MaterialMaps {
        name: "bricks",
        height,
        albedo,
        height_scale: 0.05,
    }
}

/// Cobblestones (T Fig. 1): 6 × 6 rounded stones per tile with grout at 0.08.
pub fn cobblestones() -> MaterialMaps {
    let height = soften(&patterns::cobblestones(SIZE, 6), 1);
    let albedo = paint(&height, |x, y, h| {
        // Stones keep their tone: look it up on the coarse cell the texel falls in.
        let cell = (x as i32 * 6 / SIZE as i32, y as i32 * 6 / SIZE as i32);
        let tone = 0.75 + 0.3 * cell_noise(cell.0, cell.1, 21);
        let grain = 0.9 + 0.1 * cell_noise(x as i32, y as i32, 22);
        let stone = [0.5 * tone * grain, 0.47 * tone * grain, 0.43 * tone * grain];
        mix([0.16, 0.15, 0.13], stone, (h - 0.08) * 4.0)
    });
    MaterialMaps {
        name: "cobblestone",
        height,
        albedo,
        height_scale: 0.04,
    }
}

/// Sharp cones (T Fig. 13b): 5 × 5 per tile.
pub fn cones() -> MaterialMaps {
    let height = patterns::cones(SIZE, 5.0);
    let albedo = paint(&height, |_, _, h| {
        mix([0.25, 0.3, 0.4], [0.75, 0.8, 0.85], h)
    });
    MaterialMaps {
        name: "cones",
        height,
        albedo,
        height_scale: 0.06,
    }
}

/// A dense field of thin blades (McGuire Fig. 3): 900 tapered spikes of random height.
pub fn fur() -> MaterialMaps {
    let mut random = Random::new(31);
    let blades: Vec<(f32, f32, f32, f32)> = (0..900)
        .map(|_| {
            (
                random.next(),
                random.next(),
                0.5 + 0.5 * random.next(),
                0.006 + 0.006 * random.next(),
            )
        })
        .collect();
    let height = HeightField::from_fn(SIZE, SIZE, |u, v| {
        blades.iter().fold(0.0_f32, |top, &(bu, bv, tall, radius)| {
            // Wrapped distance, so the tile repeats seamlessly.
            let du = (u - bu + 0.5).rem_euclid(1.0) - 0.5;
            let dv = (v - bv + 0.5).rem_euclid(1.0) - 0.5;
            let distance = (du * du + dv * dv).sqrt();
            top.max(tall * (1.0 - distance / radius).max(0.0))
        })
    });
    let albedo = paint(&height, |x, y, h| {
        let hue = cell_noise(x as i32 / 3, y as i32 / 3, 32);
        mix([0.08, 0.16, 0.04], [0.35 + 0.2 * hue, 0.6, 0.18], h)
    });
    MaterialMaps {
        name: "fur",
        height,
        albedo,
        height_scale: 0.08,
    }
}

/// 5 × 7 bitmap glyphs, one row per line, `#` = ink.
fn glyph(letter: char) -> [&'static str; 7] {
    match letter {
        'T' => [
            "#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#..",
        ],
        'O' => [
            ".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###.",
        ],
        'Y' => [
            "#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#..",
        ],
        'S' => [
            ".####", "#....", "#....", ".###.", "....#", "....#", "####.",
        ],
        'H' => [
            "#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#",
        ],
        'P' => [
            "####.", "#...#", "#...#", "####.", "#....", "#....", "#....",
        ],
        _ => ["....."; 7],
    }
}

/// Extruded letters for a shop sign (T Fig. 17): "TOY" over "SHOP", raised on a board.
pub fn sign() -> MaterialMaps {
    let lines = ["TOY", "SHOP"];
    let cell = 9.0; // texels per glyph dot
    let ink = |x: f32, y: f32| -> bool {
        for (line_index, line) in lines.iter().enumerate() {
            let width = line.len() as f32 * 6.0 * cell - cell;
            let left = (SIZE as f32 - width) / 2.0;
            let top = 40.0 + line_index as f32 * 100.0;
            let (gx, gy) = ((x - left) / cell, (y - top) / cell);
            if !(0.0..7.0).contains(&gy) || gx < 0.0 {
                continue;
            }
            let letter = (gx / 6.0).floor() as usize;
            let column = (gx - letter as f32 * 6.0).floor() as usize;
            if let Some(character) = line.chars().nth(letter)
                && column < 5
                && glyph(character)[gy as usize].as_bytes()[column] == b'#'
            {
                return true;
            }
        }
        false
    };
    let sharp = HeightField::from_fn(SIZE, SIZE, |u, v| {
        let (x, y) = (u * SIZE as f32, v * SIZE as f32);
        let border = x.min(y).min(SIZE as f32 - x).min(SIZE as f32 - y);
        if ink(x, y) {
            1.0
        } else if border < 10.0 {
            0.7
        } else {
            0.35
        }
    });
    let height = soften(&sharp, 1);
    let albedo = paint(&height, |x, y, h| {
        let grain = 0.85
            + 0.15
                * ((y as f32 * 0.7 + 3.0 * cell_noise(x as i32 / 16, y as i32 / 4, 41)).sin()
                    * 0.5
                    + 0.5);
        let wood = [0.42 * grain, 0.26 * grain, 0.14 * grain];
        mix(wood, [0.93, 0.84, 0.62], (h - 0.7) * 4.0)
    });
    MaterialMaps {
        name: "sign",
        height,
        albedo,
        height_scale: 0.06,
    }
}

/// The whole set, in a fixed order.
pub fn all() -> Vec<MaterialMaps> {
    vec![bricks(), cobblestones(), sign(), cones(), fur()]
}
