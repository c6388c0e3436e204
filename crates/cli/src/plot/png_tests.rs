use super::*;
use crate::plot::csv::parse;

/// The trace of `svg_tests.rs`: the SVG puts b's rising edge at x 325
/// (high y 15, low y 35), the `Up` band over x 140–510, y 125–149.
const TRACE: &str = "time,b,x,s\n\
T#0s,FALSE,0,A#Up\n\
T#10ms,TRUE,1,A#Up\n\
T#20ms,TRUE,2,A#Right\n\
T#30ms,FALSE,1,A#Right\n";

fn rgba(pm: &Pixmap, x: u32, y: u32) -> [u8; 4] {
    let c = pm
        .pixel(x, y)
        .unwrap_or_else(|| panic!("no pixel at {x},{y}"));
    [c.red(), c.green(), c.blue(), c.alpha()]
}

const WHITE: [u8; 4] = [255, 255, 255, 255];
const BLACK: [u8; 4] = [0, 0, 0, 255];
/// A pixel three quarters covered by a black 1.5 px line (255 / 4, with
/// tiny-skia's rounding; 64 on the first row of a horizontal line).
const GREY: [u8; 4] = [63, 63, 63, 255];
const GREY_64: [u8; 4] = [64, 64, 64, 255];

fn decoded() -> Pixmap {
    let bytes = render(&parse(TRACE).unwrap()).unwrap();
    assert_eq!(bytes.get(..8), Some(&b"\x89PNG\r\n\x1a\n"[..]));
    Pixmap::decode_png(&bytes).unwrap()
}

#[test]
fn the_png_has_the_svg_size_and_a_white_page() {
    let pm = decoded();
    assert_eq!((pm.width(), pm.height()), (900, 198));
    assert_eq!(rgba(&pm, 0, 0), WHITE);
    assert_eq!(rgba(&pm, 899, 197), WHITE);
    assert_eq!(rgba(&pm, 600, 25), WHITE);
}

#[test]
fn a_boolean_edge_is_where_the_svg_puts_it() {
    let pm = decoded();
    // The rising edge at x 325 is 1.5 px wide, centred on the line between
    // pixel columns 324 and 325: both are three quarters covered.
    let row: Vec<[u8; 4]> = (322..328).map(|x| rgba(&pm, x, 25)).collect();
    assert_eq!(row, [WHITE, WHITE, GREY, GREY, WHITE, WHITE]);
    // Low before the edge (y 35), high after it (y 15).
    assert_eq!(rgba(&pm, 200, 34), GREY_64);
    assert_eq!(rgba(&pm, 200, 35), GREY);
    assert_eq!(rgba(&pm, 200, 15), WHITE);
    assert_eq!(rgba(&pm, 400, 14), GREY_64);
    assert_eq!(rgba(&pm, 400, 15), GREY);
    assert_eq!(rgba(&pm, 400, 34), WHITE);
}

#[test]
fn labels_are_drawn_in_the_bitmap_font() {
    let pm = decoded();
    // `b` right-aligned at x 132 on baseline 29: its stem from (127, 22).
    let stem: Vec<[u8; 4]> = (22..29).map(|y| rgba(&pm, 127, y)).collect();
    assert_eq!(stem, [BLACK; 7]);
    assert_eq!(rgba(&pm, 128, 22), WHITE);
    // `Up` inside its band (fill #dde8f5) from x 143 on baseline 141.
    assert_eq!(rgba(&pm, 143, 134), BLACK);
    assert_eq!(rgba(&pm, 147, 134), BLACK);
    assert_eq!(rgba(&pm, 145, 134), [0xdd, 0xe8, 0xf5, 255]);
    assert_eq!(rgba(&pm, 300, 130), [0xdd, 0xe8, 0xf5, 255]);
    // The time axis is one sharp black row at y 162.
    assert_eq!(rgba(&pm, 500, 162), BLACK);
    assert_eq!(rgba(&pm, 500, 161), WHITE);
    assert_eq!(rgba(&pm, 500, 163), WHITE);
}
