//! The renderers, one per format, each a pure function from sections to text: the
//! terminal ([`terminal`]), Markdown ([`markdown`]), JSON ([`json`]) and the report page
//! ([`html`]). Numbers print through [`crate::Number`] and cells through
//! [`crate::Cell`]'s `Display`, so no renderer formats a number of its own.

pub mod html;
pub mod json;
pub mod markdown;
pub mod terminal;
