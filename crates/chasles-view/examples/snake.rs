//! Writes the viewer's page for the synthetic snake (`chasles_view::synthetic`), to measure
//! the page on a large mesh: `cargo run --release -p chasles-view --example snake -- 100000
//! snake.html`, then open `snake.html#debug=bench` (the frame rate is in the page's
//! `<pre id="chasles-debug">`) or simply watch it play.

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let vertices: usize = args.next().as_deref().unwrap_or("100000").parse()?;
    let out = args.next().unwrap_or_else(|| "snake.html".into());
    let rig = chasles_view::synthetic::snake(vertices)?;
    let page = chasles_view::character(
        &rig,
        None,
        chasles_view::DEFAULT_FPS,
        "built in code (chasles_view::synthetic)",
    )?;
    std::fs::write(&out, &page.html)?;
    println!(
        "wrote {out}: {} vertices, {} joints, {} frames, {:.1} MB",
        page.vertices,
        page.joints,
        page.frames,
        page.html.len() as f64 / 1e6
    );
    Ok(())
}
