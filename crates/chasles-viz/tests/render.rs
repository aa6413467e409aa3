//! The renderer draws what it is given: the extruded R is an R (stem, the bowl's hole, the
//! gap under the bowl, the leg — and not its mirror image), the nearer surface wins, lit
//! faces are brighter than grazing ones, bad triangles are skipped without a panic; GIFs
//! decode to the frames written; line plots zoom to a small variation; the PNG velocity
//! graph marks its keys.

use chasles::{Quat, Vec3};
use chasles_viz::graph::velocity_png;
use chasles_viz::letter::{animate, letter_r};
use chasles_viz::plot::{lines_svg, Series};
use chasles_viz::raster::{Canvas, View};
use chasles_viz::{font, gif, EncodeError, Image};

const BG: [u8; 3] = [255, 255, 255];

/// The R seen straight on (from +z, y up), 20 pixels a unit, 200 × 200.
fn front_r(q: Quat<f64>) -> Image {
    let (v, t) = letter_r(1.0);
    let v: Vec<Vec3<f64>> = v.iter().map(|p| q.rotate(*p)).collect();
    let view = View::new(
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::zero(),
        20.0,
    );
    let mut c = Canvas::new(200, 200, BG);
    c.mesh(&view, &v, &t, |_| [200, 40, 40]);
    c.finish()
}

/// Whether the point (x, y) of the letter's centred frame is drawn.
fn drawn(img: &Image, x: f64, y: f64) -> bool {
    let (px, py) = ((100.0 + x * 20.0) as usize, (100.0 - y * 20.0) as usize);
    img.pixel(px, py) != BG
}

#[test]
fn the_letter_is_an_r() {
    let img = front_r(Quat::identity());
    // Letter coordinates are centred on (1.7, 2.5).
    assert!(drawn(&img, 0.5 - 1.7, 0.5 - 2.5), "stem");
    assert!(drawn(&img, 1.7 - 1.7, 4.5 - 2.5), "top bar");
    assert!(!drawn(&img, 1.6 - 1.7, 3.7 - 2.5), "the bowl's hole");
    assert!(drawn(&img, 2.6 - 1.7, 3.7 - 2.5), "the bowl's right side");
    assert!(drawn(&img, 2.4 - 1.7, 1.0 - 2.5), "the leg");
    assert!(
        !drawn(&img, 1.4 - 1.7, 1.0 - 2.5),
        "the gap between stem and leg"
    );
    assert!(!drawn(&img, 3.3 - 1.7, 4.8 - 2.5), "outside, top right");
    // Turned half a turn about y, the letter is seen mirrored: the stem is on the right,
    // and where it stood (left, just below the middle) is empty.
    let back =
        front_r(Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), std::f64::consts::PI).unwrap());
    assert!(drawn(&back, 1.2, -2.0), "mirrored stem");
    assert!(!drawn(&back, -1.2, -0.4), "no stem on the left");
    assert_ne!(img, back, "an R is not its mirror image");
}

#[test]
fn nearer_surface_wins_and_light_shades() {
    let view = View::new(
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::zero(),
        40.0,
    );
    let quad = |z: f64| {
        vec![
            Vec3::new(-1.0, -1.0, z),
            Vec3::new(1.0, -1.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(-1.0, 1.0, z),
        ]
    };
    let tris = [[0u32, 1, 2], [0, 2, 3]];
    for near_first in [true, false] {
        let mut c = Canvas::new(100, 100, BG);
        let (a, b) = if near_first { (0.5, -0.5) } else { (-0.5, 0.5) };
        let colour_of = |z: f64| if z > 0.0 { [0, 200, 0] } else { [0, 0, 200] };
        c.mesh(&view, &quad(a), &tris, |_| colour_of(a));
        c.mesh(&view, &quad(b), &tris, |_| colour_of(b));
        let p = c.finish().pixel(50, 50);
        assert!(
            p[1] > 0 && p[2] == 0,
            "near (green) face wins, drawn first: {near_first}"
        );
    }
    // A face square to the viewer-side light is brighter than one seen edge-on-ish.
    let brightness = |tilt: f64| {
        let q = Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), tilt).unwrap();
        let v: Vec<Vec3<f64>> = quad(0.0).iter().map(|p| q.rotate(*p)).collect();
        let mut c = Canvas::new(100, 100, [0, 0, 0]);
        c.mesh(&view, &v, &tris, |_| [250, 250, 250]);
        c.finish().pixel(50, 50)[0]
    };
    assert!(brightness(-0.6) > brightness(1.3));
    // Bad triangles are skipped.
    let mut c = Canvas::new(50, 50, BG);
    let v = vec![
        Vec3::new(f64::NAN, 0.0, 0.0),
        Vec3::zero(),
        Vec3::new(1.0, 0.0, 0.0),
    ];
    c.mesh(&view, &v, &[[0, 1, 2], [1, 2, 7], [1, 1, 2]], |_| [0, 0, 0]);
    assert!(c.finish().rgb.iter().all(|x| *x == 255));
}

#[test]
fn gif_holds_the_frames() {
    let frames = animate(
        &[
            Quat::identity(),
            Quat::from_axis_angle(Vec3::new(0.0, 1.0, 0.0), 1.0).unwrap(),
            Quat::identity(),
        ],
        64,
    );
    let bytes = gif(&frames, 7).unwrap();
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut d = opts.read_info(std::io::Cursor::new(&bytes)).unwrap();
    assert_eq!((d.width(), d.height()), (64, 64));
    let mut n = 0;
    while let Some(f) = d.read_next_frame().unwrap() {
        assert_eq!(f.delay, 7);
        n += 1;
    }
    assert_eq!(n, 3);
    assert!(matches!(gif(&[], 5), Err(EncodeError::Frames(_))));
    let odd = [Image::filled(4, 4, BG), Image::filled(5, 4, BG)];
    assert!(matches!(gif(&odd, 5), Err(EncodeError::Frames(m)) if m.contains("frame 1")));
}

#[test]
fn font_and_side_by_side() {
    assert_eq!(font::width("ab"), 7);
    assert_eq!(font::dots("I").len(), 9);
    assert_eq!(font::dots("lbs"), font::dots("LBS"));
    let a = Image::filled(2, 3, [1, 2, 3]);
    let b = Image::filled(3, 2, [4, 5, 6]);
    let s = Image::side_by_side(&[a, b]);
    assert_eq!((s.width, s.height), (5, 3));
    assert_eq!(s.pixel(1, 2), [1, 2, 3]);
    assert_eq!(s.pixel(4, 1), [4, 5, 6]);
    assert_eq!(s.pixel(4, 2), BG);
}

#[test]
fn line_plot_zooms_to_small_variation_and_keeps_zero_otherwise() {
    let small: Vec<(f64, f64)> = (0..=10)
        .map(|k| (k as f64 / 10.0, 0.9588 + 0.0015 * (k as f64 / 10.0).powi(2)))
        .collect();
    let s = lines_svg(
        &[Series {
            name: "measured",
            colour: "#00f",
            dashed: false,
            points: small,
        }],
        "zoom & <check>",
        "t",
        "w",
    );
    assert!(s.contains("zoom &amp; &lt;check&gt;") && s.contains(">measured<"));
    assert!(!s.contains(">0.0000<"), "zoomed, not from 0");
    let big: Vec<(f64, f64)> = (0..=10).map(|k| (k as f64, k as f64)).collect();
    let s = lines_svg(
        &[Series {
            name: "a",
            colour: "#f00",
            dashed: true,
            points: big,
        }],
        "t",
        "x",
        "y",
    );
    assert!(s.contains(">0.0000<") && s.contains("stroke-dasharray"));
    assert!(lines_svg(&[], "empty", "x", "y").ends_with("</svg>\n"));
}

#[test]
fn velocity_png_marks_keys() {
    let v: Vec<f64> = (0..60).map(|i| 1.0 + (i as f64 * 0.2).sin()).collect();
    let img = velocity_png(&v, &[0, 20, 40, 59], 400, 200);
    assert_eq!((img.width, img.height), (400, 200));
    let red = img.rgb.chunks(3).filter(|c| c == &[192, 57, 43]).count();
    assert!(red >= 2 * 13, "two asterisks of 13 dots, 9 px each: {red}");
    let blue = img.rgb.chunks(3).filter(|c| c == &[31, 95, 191]).count();
    assert!(blue > 300, "the curve: {blue}");
}

#[test]
fn grid_and_bars() {
    use chasles_viz::bars::bars_svg;
    use chasles_viz::grid::{grid_svg, GridCell};
    let c = |value: f64, holds: bool, agrees: bool| GridCell {
        value,
        holds,
        agrees,
    };
    let s = grid_svg(
        &["a", "b"],
        &["p", "q"],
        &[
            vec![c(1e-15, true, true), c(0.3, false, false)],
            vec![c(0.0, false, true), c(f64::NAN, false, true)],
        ],
        "t",
    );
    assert_eq!(s.matches("class=\"cell\"").count(), 4);
    assert!(
        s.contains(">1e-15<") && s.contains(">3e-1<") && s.contains(">no<") && s.contains(">—<")
    );
    assert_eq!(
        s.matches("stroke=\"black\" stroke-width=\"3\"").count(),
        1,
        "one disagreement framed"
    );
    let b = bars_svg(
        &["0".into(), "1".into(), "2".into()],
        &[0, 64, 136],
        "dib",
        "updates",
    );
    assert_eq!(b.matches("class=\"bar\"").count(), 3);
    assert!(b.contains(">136<"));
    assert!(bars_svg(&[], &[], "empty", "x").ends_with("</svg>\n"));
}
