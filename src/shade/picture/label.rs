//! A 3×5 pixel font for the contact sheet's material names (ASCII letters, digits and a
//! little punctuation; anything else draws as `?`).

use image::{Rgb, RgbImage};

/// Each glyph: five rows of three pixels, top to bottom, `1` = ink.
const GLYPHS: &[(char, &str)] = &[
    ('0', "111101101101111"),
    ('1', "010110010010111"),
    ('2', "111001111100111"),
    ('3', "111001111001111"),
    ('4', "101101111001001"),
    ('5', "111100111001111"),
    ('6', "111100111101111"),
    ('7', "111001001001001"),
    ('8', "111101111101111"),
    ('9', "111101111001111"),
    ('A', "010101111101101"),
    ('B', "110101110101110"),
    ('C', "011100100100011"),
    ('D', "110101101101110"),
    ('E', "111100110100111"),
    ('F', "111100110100100"),
    ('G', "011100101101011"),
    ('H', "101101111101101"),
    ('I', "111010010010111"),
    ('J', "001001001101010"),
    ('K', "101101110101101"),
    ('L', "100100100100111"),
    ('M', "101111111101101"),
    ('N', "110101101101101"),
    ('O', "010101101101010"),
    ('P', "110101110100100"),
    ('Q', "010101101110011"),
    ('R', "110101110101101"),
    ('S', "011100010001110"),
    ('T', "111010010010010"),
    ('U', "101101101101111"),
    ('V', "101101101101010"),
    ('W', "101101111111101"),
    ('X', "101101010101101"),
    ('Y', "101101010010010"),
    ('Z', "111001010100111"),
    ('-', "000000111000000"),
    ('_', "000000000000111"),
    ('.', "000000000000010"),
    (' ', "000000000000000"),
    ('?', "111001010000010"),
];

fn glyph(c: char) -> &'static str {
    let upper = c.to_ascii_uppercase();
    GLYPHS
        .iter()
        .find(|(g, _)| *g == upper)
        .or_else(|| GLYPHS.iter().find(|(g, _)| *g == '?'))
        .map_or("", |(_, bits)| bits)
}

/// Draws `text` with its top-left corner at (x, y), `scale` pixels per font pixel, clipped
/// to the image and to `max_width` pixels.
pub(crate) fn draw(
    image: &mut RgbImage,
    text: &str,
    (x, y): (u32, u32),
    scale: u32,
    max_width: u32,
) {
    let advance = 4 * scale;
    for (i, c) in text.chars().enumerate() {
        let left = x + i as u32 * advance;
        if left + 3 * scale > x + max_width {
            break;
        }
        for (bit, ink) in glyph(c).bytes().enumerate() {
            if ink != b'1' {
                continue;
            }
            let (gx, gy) = (bit as u32 % 3, bit as u32 / 3);
            for dy in 0..scale {
                for dx in 0..scale {
                    let (px, py) = (left + gx * scale + dx, y + gy * scale + dy);
                    if px < image.width() && py < image.height() {
                        image.put_pixel(px, py, Rgb([235, 235, 235]));
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_drawn_inside_its_box_and_unknown_characters_show() {
        let mut image = RgbImage::new(40, 10);
        draw(&mut image, "Ab1é", (1, 1), 1, 38);
        let inked: Vec<(u32, u32)> = image
            .enumerate_pixels()
            .filter(|(_, _, p)| p.0[0] > 0)
            .map(|(x, y, _)| (x, y))
            .collect();
        assert!(!inked.is_empty());
        assert!(inked
            .iter()
            .all(|&(x, y)| (1..17).contains(&x) && (1..6).contains(&y)));
        // "A" starts with its apex in the middle column of the first glyph.
        assert_eq!(image.get_pixel(2, 1).0[0], 235);
        assert_eq!(image.get_pixel(1, 1).0[0], 0);
    }
}
