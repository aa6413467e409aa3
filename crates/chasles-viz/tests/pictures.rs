//! The pictures are what they claim: a valid SVG with one asterisk per inner key frame and
//! the curve's points; a valid PNG of the right size whose sphere is shaded inside its
//! silhouette, white outside, with the curve's points drawn in their colours.

use chasles::interp::{examples, interpolate, Hemisphere, KeyFrames, Method, Timing};
use chasles::Quat;
use chasles_viz::graph::velocity_svg;
use chasles_viz::sphere::{fixed_coordinate, render, Mark};

#[test]
fn velocity_graph_svg() {
    let v: Vec<f64> = (0..100).map(|i| 1.0 + (i as f64 * 0.1).sin()).collect();
    let s = velocity_svg(&v, &[0, 30, 60, 99], "a <test> & more");
    assert!(s.starts_with("<svg") && s.trim_end().ends_with("</svg>"));
    assert_eq!(
        s.matches("class=\"key\"").count(),
        2,
        "first and last key left out"
    );
    let poly = s.lines().find(|l| l.starts_with("<polyline")).unwrap();
    assert_eq!(
        poly.split_whitespace().filter(|t| t.contains(',')).count(),
        98,
        "inner frames only"
    );
    assert!(s.contains("a &lt;test&gt; &amp; more"));
    // Degenerate inputs do not break it.
    assert!(velocity_svg(&[], &[], "empty").contains("</svg>"));
    assert!(velocity_svg(&[1.0, f64::NAN, 1.0], &[1], "nan").contains("</svg>"));
}

#[test]
fn sphere_plot_png() {
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    let f = interpolate(Method::Squad, &keys, 200, Timing::Angle).unwrap();
    let q: Vec<Quat<f64>> = f.iter().map(|x| x.q).collect();
    assert_eq!(fixed_coordinate(&q), 3, "Table 5.1 keeps z = 0");
    let pts: Vec<(Quat<f64>, Mark)> = f
        .iter()
        .map(|x| {
            (
                x.q,
                match x.key {
                    Some(0) => Mark::FirstKey,
                    Some(_) => Mark::Key,
                    None => Mark::Frame,
                },
            )
        })
        .collect();
    let img = render(&pts, 3, 300);
    assert_eq!(img.rgb.len(), 300 * 300 * 3);
    let px = |x: usize, y: usize| &img.rgb[(y * 300 + x) * 3..(y * 300 + x) * 3 + 3];
    assert_eq!(px(2, 2), &[255, 255, 255], "background outside the sphere");
    let blue = img
        .rgb
        .chunks(3)
        .filter(|c| c[2] > 120 && c[0] < 80)
        .count();
    let red = img
        .rgb
        .chunks(3)
        .filter(|c| c[0] > 120 && c[1] < 60 && c[2] < 60)
        .count();
    assert!(blue > 300, "the curve is drawn ({blue} blue pixels)");
    assert!(red > 10, "the first key is drawn ({red} red pixels)");
    let greys: std::collections::BTreeSet<u8> = img
        .rgb
        .chunks(3)
        .filter(|c| c[0] == c[1])
        .map(|c| c[0])
        .collect();
    assert!(greys.len() > 50, "the sphere is shaded, not flat");
    // A valid PNG that decodes to the same pixels.
    let bytes = img.png();
    let dec = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (300, 300));
    assert_eq!(&buf[..info.buffer_size()], &img.rgb[..]);
}
