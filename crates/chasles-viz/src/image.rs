//! An RGB picture and its encodings: PNG through the `png` crate, animated GIF through the
//! `gif` crate (each frame quantised to its own 256-colour palette by NeuQuant).

use std::borrow::Cow;

/// An RGB image, row-major, 3 bytes a pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major RGB bytes, `width * height * 3` of them.
    pub rgb: Vec<u8>,
}

/// Why a picture could not be encoded.
#[derive(Debug, thiserror::Error)]
pub enum EncodeError {
    /// No frames, frames of different sizes, or a size a GIF cannot hold (65535 max).
    #[error("cannot encode the animation: {0}")]
    Frames(String),
    /// The encoder failed.
    #[error("encoder failed: {0}")]
    Encoder(String),
}

impl Image {
    /// A `width × height` image filled with one colour.
    pub fn filled(width: usize, height: usize, colour: [u8; 3]) -> Self {
        let mut rgb = Vec::with_capacity(width * height * 3);
        for _ in 0..width * height {
            rgb.extend_from_slice(&colour);
        }
        Image { width, height, rgb }
    }

    /// The pixel at `(x, y)`.
    pub fn pixel(&self, x: usize, y: usize) -> [u8; 3] {
        let k = (y * self.width + x) * 3;
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// Sets the pixel at `(x, y)`; outside the image nothing happens.
    pub fn set(&mut self, x: usize, y: usize, colour: [u8; 3]) {
        if x < self.width && y < self.height {
            let k = (y * self.width + x) * 3;
            self.rgb[k..k + 3].copy_from_slice(&colour);
        }
    }

    /// Images placed top to bottom on a white ground, left-aligned.
    pub fn stacked(images: &[Image]) -> Image {
        let width = images.iter().map(|i| i.width).max().unwrap_or(0);
        let height = images.iter().map(|i| i.height).sum();
        let mut out = Image::filled(width, height, [255, 255, 255]);
        let mut y0 = 0;
        for im in images {
            for y in 0..im.height {
                let src = &im.rgb[y * im.width * 3..(y + 1) * im.width * 3];
                let k = (y0 + y) * width * 3;
                out.rgb[k..k + im.width * 3].copy_from_slice(src);
            }
            y0 += im.height;
        }
        out
    }

    /// Images placed left to right on a white ground, top-aligned.
    pub fn side_by_side(images: &[Image]) -> Image {
        let width = images.iter().map(|i| i.width).sum();
        let height = images.iter().map(|i| i.height).max().unwrap_or(0);
        let mut out = Image::filled(width, height, [255, 255, 255]);
        let mut x0 = 0;
        for im in images {
            for y in 0..im.height {
                let src = &im.rgb[y * im.width * 3..(y + 1) * im.width * 3];
                let k = (y * width + x0) * 3;
                out.rgb[k..k + im.width * 3].copy_from_slice(src);
            }
            x0 += im.width;
        }
        out
    }

    /// PNG bytes.
    pub fn png(&self) -> Vec<u8> {
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, self.width as u32, self.height as u32);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            if let Ok(mut w) = enc.write_header() {
                let _ = w.write_image_data(&self.rgb);
            }
        }
        out
    }
}

/// An animated GIF of `frames` (all the same size), `delay_cs` hundredths of a second
/// each, looping forever.
pub fn gif(frames: &[Image], delay_cs: u16) -> Result<Vec<u8>, EncodeError> {
    let first = frames
        .first()
        .ok_or_else(|| EncodeError::Frames("no frames".into()))?;
    let (w, h) = (first.width, first.height);
    if w == 0 || h == 0 || w > 65535 || h > 65535 {
        return Err(EncodeError::Frames(format!("size {w}×{h}")));
    }
    if let Some(bad) = frames.iter().position(|f| (f.width, f.height) != (w, h)) {
        return Err(EncodeError::Frames(format!(
            "frame {bad} is {}×{}, frame 0 is {w}×{h}",
            frames[bad].width, frames[bad].height
        )));
    }
    let mut out = Vec::new();
    {
        let enc_err = |e: gif::EncodingError| EncodeError::Encoder(e.to_string());
        let mut enc = gif::Encoder::new(&mut out, w as u16, h as u16, &[]).map_err(enc_err)?;
        enc.set_repeat(gif::Repeat::Infinite).map_err(enc_err)?;
        for f in frames {
            let mut frame = gif::Frame::from_rgb_speed(w as u16, h as u16, &f.rgb, 10);
            frame.delay = delay_cs;
            frame.buffer = Cow::Owned(frame.buffer.into_owned());
            enc.write_frame(&frame).map_err(enc_err)?;
        }
    }
    Ok(out)
}
