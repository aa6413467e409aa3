//! Headless Chromium for the viewer's tests: Debian's `chromium` (or `$CHASLES_CHROMIUM`),
//! software WebGL2 through ANGLE's SwiftShader, no network, a fresh profile each run. A page
//! is driven by its URL fragment; what it reports comes back through `--dump-dom` (the JSON
//! the page writes into `<pre id="chasles-debug">` when the fragment asks), what it shows
//! through `--screenshot`.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The flags every run takes: headless, software WebGL2, nothing fetched from anywhere.
const FLAGS: [&str; 10] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--hide-scrollbars",
];

/// The longest a run may take (a loaded 2-core machine, software rendering).
const TIMEOUT: Duration = Duration::from_secs(240);

/// A Chromium to run.
pub struct Browser {
    exe: PathBuf,
}

/// A screenshot: width, height, RGB bytes.
pub struct Shot {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
}

impl Shot {
    pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
        let i = 3 * (y * self.width + x);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// Whether pixel (x, y) differs from the background (the top-left corner's colour).
    pub fn drawn(&self, x: usize, y: usize) -> bool {
        let (p, bg) = (self.at(x, y), self.at(0, 0));
        p.iter().zip(bg).any(|(a, b)| a.abs_diff(b) > 20)
    }

    /// The share of pixels that differ from the background.
    pub fn coverage(&self) -> f64 {
        let mut n = 0;
        for y in 0..self.height {
            for x in 0..self.width {
                n += usize::from(self.drawn(x, y));
            }
        }
        n as f64 / (self.width * self.height) as f64
    }

    /// The drawn pixels of column x, from the first to the last (0 when none).
    pub fn column_extent(&self, x: usize) -> usize {
        let drawn: Vec<usize> = (0..self.height).filter(|y| self.drawn(x, *y)).collect();
        drawn.last().map_or(0, |l| l - drawn[0] + 1)
    }
}

impl Browser {
    /// `$CHASLES_CHROMIUM`, else the first of chromium, chromium-browser, google-chrome on
    /// the PATH (Debian's is /usr/bin/chromium); `None` says why the tests skip.
    pub fn find() -> Option<Browser> {
        if let Some(p) = std::env::var_os("CHASLES_CHROMIUM") {
            return Some(Browser { exe: p.into() });
        }
        let path = std::env::var_os("PATH").unwrap_or_default();
        for name in ["chromium", "chromium-browser", "google-chrome"] {
            for dir in std::env::split_paths(&path) {
                let exe = dir.join(name);
                if exe.is_file() {
                    return Some(Browser { exe });
                }
            }
        }
        say("skipping this browser test: no chromium on the PATH (Debian: apt-get install chromium; .ci/run installs it)");
        None
    }

    /// Runs Chromium with `args` on `url`, a fresh profile, killed past [`TIMEOUT`];
    /// its stdout.
    fn run(&self, args: &[String], url: &str) -> String {
        let profile = tempfile::tempdir().unwrap();
        let out = tempfile::NamedTempFile::new().unwrap();
        let mut child = Command::new(&self.exe)
            .args(FLAGS)
            .arg(format!("--user-data-dir={}", profile.path().display()))
            .args(args)
            .arg(url)
            .stdin(Stdio::null())
            .stdout(out.reopen().unwrap())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromium starts");
        let start = Instant::now();
        loop {
            if child.try_wait().unwrap().is_some() {
                break;
            }
            if start.elapsed() > TIMEOUT {
                let _ = child.kill();
                let _ = child.wait();
                panic!("chromium took over {TIMEOUT:?} on {url}");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        std::fs::read_to_string(out.path()).unwrap()
    }

    /// The JSON report the page at `url` writes (its fragment must ask for one: `debug=…`).
    pub fn report(&self, url: &str, size: (u32, u32)) -> serde_json::Value {
        let dom = self.run(
            &[
                "--dump-dom".into(),
                format!("--window-size={},{}", size.0, size.1),
            ],
            url,
        );
        let start = dom
            .find("<pre id=\"chasles-debug\"")
            .unwrap_or_else(|| panic!("no report in the page: {}", &dom[..dom.len().min(500)]));
        let text = &dom[start..];
        let text = &text[text.find('>').unwrap() + 1..text.find("</pre>").unwrap()];
        let json = text
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&amp;", "&");
        serde_json::from_str(&json).unwrap_or_else(|e| panic!("report: {e}: {json:.300}"))
    }

    /// A screenshot of `url` in a window of `size`.
    pub fn screenshot(&self, url: &str, size: (u32, u32), keep: &Path) -> Shot {
        self.run(
            &[
                format!("--screenshot={}", keep.display()),
                format!("--window-size={},{}", size.0, size.1),
            ],
            url,
        );
        let bytes = std::fs::read(keep).unwrap_or_else(|_| panic!("no screenshot of {url}"));
        let mut d = png::Decoder::new(std::io::Cursor::new(bytes));
        d.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut r = d.read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size().unwrap()];
        let info = r.next_frame(&mut buf).unwrap();
        let channels = info.color_type.samples();
        let rgb = buf[..info.buffer_size()]
            .chunks(channels)
            .flat_map(|c| [c[0], c[1 % channels], c[2 % channels]])
            .collect();
        Shot {
            width: info.width as usize,
            height: info.height as usize,
            rgb,
        }
    }
}

/// `line` on stderr even when the test harness captures output (it captures the print
/// macros, not the stream): a skip or a measurement must be seen.
pub fn say(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// The `file://` URL of `path` with `fragment`.
pub fn url(path: &Path, fragment: &str) -> String {
    format!(
        "file://{}#{fragment}",
        path.canonicalize().unwrap().display()
    )
}
