//! One self-contained HTML page from a [`Scene`]: the template, its style and script
//! inline, the scene as one JSON value (numbers as base64 of little-endian arrays) in a
//! `<script type="application/json">` element, and the GLSL [`crate::shader`] made. The page
//! loads nothing: no URL, no server, no network ([`external_reference`] checks it).

use crate::scene::{Scene, FLOATS_PER_JOINT};
use crate::shader::Glsl;
use crate::ViewError;
use base64::Engine;
use serde::Serialize;

const TEMPLATE: &str = include_str!("page/page.html");
const STYLE: &str = include_str!("page/style.css");
const RENDER_JS: &str = include_str!("page/render.js");
const UI_JS: &str = include_str!("page/ui.js");

/// The mesh's arrays as base64.
#[derive(Serialize)]
struct Mesh {
    positions: String,
    normals: String,
    joints: String,
    weights: String,
    triangles: String,
}

/// The page's data, as the script reads it.
#[derive(Serialize)]
struct Data<'a> {
    title: &'a str,
    credit: &'a str,
    generator: String,
    joints: usize,
    vertices: usize,
    triangles: usize,
    bounds: [[f32; 3]; 2],
    clips: &'a [crate::scene::Clip],
    clip: usize,
    grid: Option<&'a crate::scene::Grid>,
    floats_per_joint: usize,
    glsl: &'a Glsl,
    mesh: Mesh,
    /// One per clip, or one for the cylinder's grid.
    palettes: Vec<String>,
}

fn b64<T: Copy>(items: &[T], bytes: impl Fn(T) -> [u8; 4]) -> String {
    let raw: Vec<u8> = items.iter().flat_map(|x| bytes(*x)).collect();
    base64::engine::general_purpose::STANDARD.encode(raw)
}

fn floats(x: &[f32]) -> String {
    b64(x, f32::to_le_bytes)
}

/// `s` with `& < > "` escaped for HTML text.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The page showing `scene`, its shaders `glsl`.
pub fn html(scene: &Scene, glsl: &Glsl) -> Result<String, ViewError> {
    let b = &scene.buffers;
    let joints: Vec<u8> = b.joints.iter().flat_map(|j| j.to_le_bytes()).collect();
    let palettes = match &scene.grid {
        Some(g) => vec![floats(&g.palettes)],
        None => scene.clips.iter().map(|c| floats(&c.palettes)).collect(),
    };
    let data = Data {
        title: &scene.title,
        credit: &scene.credit,
        generator: format!("chasles {}", env!("CARGO_PKG_VERSION")),
        joints: scene.joints,
        vertices: b.positions.len() / 3,
        triangles: b.triangles.len() / 3,
        bounds: scene.bounds,
        clips: &scene.clips,
        clip: scene.clip,
        grid: scene.grid.as_ref(),
        floats_per_joint: FLOATS_PER_JOINT,
        glsl,
        mesh: Mesh {
            positions: floats(&b.positions),
            normals: floats(&b.normals),
            joints: base64::engine::general_purpose::STANDARD.encode(joints),
            weights: floats(&b.weights),
            triangles: b64(&b.triangles, u32::to_le_bytes),
        },
        palettes,
    };
    // JSON inside <script>: no '<' may close the element early ("</script>"), and '<' only
    // occurs inside strings, where \u003c means the same.
    let json = serde_json::to_string(&data)
        .map_err(|e| ViewError::Page(e.to_string()))?
        .replace('<', "\\u003c");
    let script = format!("{RENDER_JS}\n{UI_JS}");
    let title = esc(&scene.title);
    let page = fill(
        TEMPLATE,
        &[
            ("STYLE", STYLE),
            ("TITLE", &title),
            ("SCRIPT", &script),
            ("DATA", &json),
        ],
    )?;
    if let Some(what) = external_reference(&page) {
        return Err(ViewError::Page(format!(
            "the page would refer outside itself ({what})"
        )));
    }
    Ok(page)
}

/// `template` with every `{{NAME}}` replaced by its value, in one pass: what is put in is
/// never searched again (a model named `{{DATA}}` stays a name).
fn fill(template: &str, values: &[(&str, &str)]) -> Result<String, ViewError> {
    let mut out =
        String::with_capacity(template.len() + values.iter().map(|v| v.1.len()).sum::<usize>());
    let mut rest = template;
    while let Some(start) = rest.find("{{") {
        let end = rest[start..]
            .find("}}")
            .ok_or_else(|| ViewError::Page("an unclosed {{ in the template".into()))?;
        let name = &rest[start + 2..start + end];
        let value = values
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| ViewError::Page(format!("no value for {{{{{name}}}}}")))?;
        out.push_str(&rest[..start]);
        out.push_str(value.1);
        rest = &rest[start + end + 2..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The first thing in `page` that could make a browser reach outside the file — a URL with
/// a scheme, an attribute or rule that loads a resource, a script API that fetches —
/// or `None` when there is none (case-insensitive, each at the start of a word).
pub fn external_reference(page: &str) -> Option<&'static str> {
    const LOADERS: [&str; 20] = [
        "http:",
        "https:",
        "ftp:",
        "ws://",
        "wss://",
        "file:",
        "data:",
        "blob:",
        "javascript:",
        "src=",
        "href=",
        "url(",
        "@import",
        "fetch(",
        "xmlhttprequest",
        "websocket",
        "eventsource",
        "sendbeacon",
        "import(",
        "<link",
    ];
    let lower = page.to_ascii_lowercase();
    // A match counts where it starts a word: `texelFetch(` is GLSL, `fetch(` a request.
    let starts_word = |pattern: &str| {
        lower.match_indices(pattern).any(|(i, _)| {
            !lower[..i]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
        })
    };
    LOADERS.iter().find(|l| starts_word(l)).copied()
}
