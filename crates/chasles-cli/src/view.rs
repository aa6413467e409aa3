//! `chasles view`: one self-contained HTML page that shows a rig skinned by LBS and by DQS
//! in the browser (WebGL2, the vertex shaders translated from the GPU skinning WGSL), or the
//! twisted cylinder with twist and bend sliders (`--artifacts`) — Kavan et al. 2006, §6,
//! Figures 1 and 6, live. See the `chasles-view` crate.

use crate::output::{check_extension, Pending};
use anyhow::{bail, Result};
use std::path::{Path, PathBuf};

/// Options of `chasles view`.
#[derive(Debug, clap::Args)]
pub struct ViewArgs {
    /// The rig: .glb, .gltf, or .json (the plain format of chasles_skin::json_rig).
    pub file: Option<PathBuf>,
    /// The clip shown first, by name or index (default: the first; every clip is in the page).
    #[arg(long)]
    pub clip: Option<String>,
    /// The page to write (.html).
    #[arg(long, default_value = "view.html")]
    pub out: PathBuf,
    /// The twisted two-bone cylinder (the candy wrapper) instead of a file, with twist and
    /// bend sliders.
    #[arg(long)]
    pub artifacts: bool,
    /// Frames a second the clips are sampled at (1 to 240).
    #[arg(long, default_value_t = chasles_view::DEFAULT_FPS)]
    pub fps: f32,
}

/// The licence and attribution to show with the model in `path`: a built-in model's own
/// (matched by its bytes), else the file's glTF `asset.copyright` if it has one (web
/// addresses kept as text without their scheme: the page names no URL), and that its own
/// licence applies.
fn credit_of(path: &Path) -> String {
    let name = path
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let Ok(bytes) = chasles_skin::bounded::read_file(path, chasles_skin::bounded::MAX_MODEL_BYTES)
    else {
        return format!("{name} (its own licence applies)");
    };
    if let Some(m) = chasles_models::ALL.iter().find(|m| m.bytes == &bytes[..]) {
        return m.credit.to_string();
    }
    let copyright = gltf::Gltf::from_slice(&bytes)
        .ok()
        .and_then(|g| g.document.as_json().asset.copyright.clone())
        .map(|c| format!(", {}", without_schemes(&c)))
        .unwrap_or_default();
    format!("{name}{copyright} (its own licence applies)")
}

/// `text` with every `scheme://` taken out (`https://example.org/x` → `example.org/x`).
fn without_schemes(text: &str) -> String {
    let mut out = text.to_string();
    while let Some(i) = out.find("://") {
        let start = out[..i]
            .rfind(|c: char| !c.is_ascii_alphanumeric() && c != '+' && c != '-' && c != '.')
            .map_or(0, |j| j + 1);
        out.replace_range(start..i + 3, "");
    }
    out
}

/// Runs `chasles view`.
pub fn run(args: ViewArgs) -> Result<()> {
    check_extension("--out", Some(&args.out), &["html", "htm"])?;
    let page = match (&args.file, args.artifacts) {
        (Some(_), true) => bail!("give a rig file or --artifacts, not both"),
        (None, false) => bail!("give a rig file (.glb, .gltf or .json) or --artifacts"),
        (None, true) => {
            if args.clip.is_some() {
                bail!("--clip is for a rig file (the cylinder has twist and bend sliders)");
            }
            chasles_view::cylinder()?
        }
        (Some(file), false) => {
            let rig = chasles_skin::load(file)?;
            chasles_view::character(&rig, args.clip.as_deref(), args.fps, &credit_of(file))?
        }
    };
    let detail = format!(
        "{} vertices, {} joints, {} frames, {:.1} MB; open it in a browser",
        page.vertices,
        page.joints,
        page.frames,
        page.html.len() as f64 / 1e6
    );
    let mut out = Pending::default();
    out.add(&args.out, page.html.into_bytes(), Some(detail));
    for line in out.write()? {
        println!("{line}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn credits_keep_addresses_as_text_without_schemes() {
        assert_eq!(
            super::without_schemes("© 2020 Someone, https://example.org/model and HTTP://x.y"),
            "© 2020 Someone, example.org/model and x.y"
        );
        assert_eq!(super::without_schemes("no address"), "no address");
        assert_eq!(super::without_schemes("://odd"), "odd");
    }
}
