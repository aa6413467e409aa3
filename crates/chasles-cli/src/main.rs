//! The `chasles` command-line tool.
//!
//! * `chasles tour` — the main job: a walk through both papers on built-in data.
//! * `chasles convert` — one rotation or rigid motion between representations
//!   (Dam et al. 1998, App. B; Kavan et al. 2006, §3).

mod convert;
mod repr;
mod tour;

use clap::{Parser, Subcommand};
use repr::Repr;

#[derive(Parser)]
#[command(
    name = "chasles",
    version,
    about = "Rotations and rigid motions: quaternions, dual quaternions, interpolation and blending"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Walk through the papers on built-in data, printing computed numbers.
    Tour {
        /// Random inputs per identity in the closing sweep.
        #[arg(long, default_value_t = 10_000)]
        samples: usize,
        /// Seed of the random inputs.
        #[arg(long, default_value_t = 1998)]
        seed: u64,
    },
    /// Convert one rotation or rigid motion between representations.
    ///
    /// Representations: quat (w x y z), matrix (9 or 16 numbers, row-major), matrix3,
    /// matrix4, euler:ORDER (three angles in radians; lower-case order = extrinsic/fixed axes,
    /// e.g. euler:xyz is Dam et al.'s R = Rz(γ)Ry(β)Rx(α); upper-case = intrinsic, e.g.
    /// euler:ZYX), axis-angle (ax ay az angle), rotvec (axis·angle), rt (rotation then
    /// translation: w x y z tx ty tz), dq (unit dual quaternion: w x y z we xe ye ze),
    /// screw (ax ay az px py pz angle translation: axis direction, a point on it, the turn and
    /// the slide). Quaternions print as [w, x, y, z].
    ///
    /// Examples:
    ///   chasles convert --from euler:xyz --to quat 0.1 0.2 0.3
    ///   chasles convert --from rt --to dq -- 1 0 0 0 -1 2 3
    ///   echo '{"quat": [0, 1, 0, 0]}' | chasles convert --jsonl --to matrix
    #[command(verbatim_doc_comment)]
    Convert {
        /// Input representation (needed for numbers and bare JSON arrays).
        #[arg(long, value_parser = parse_repr)]
        from: Option<Repr>,
        /// Output representation.
        #[arg(long, value_parser = parse_repr)]
        to: Repr,
        /// Read one JSON value per line from stdin, write one JSON result per line.
        #[arg(long)]
        jsonl: bool,
        /// Print numbers with this many decimals (default: shortest exact form).
        #[arg(long)]
        precision: Option<usize>,
        /// The numbers (negative ones are fine, or put them after `--`).
        #[arg(allow_negative_numbers = true, num_args = 0..)]
        values: Vec<String>,
    },
}

fn parse_repr(s: &str) -> Result<Repr, String> {
    s.parse().map_err(|e: anyhow::Error| e.to_string())
}

fn main() {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(), // --help, --version
        Err(e) => {
            // One line naming the problem; clap's usage hint would make it three.
            let text = e.render().to_string();
            eprintln!("{}", text.lines().next().unwrap_or("error: bad arguments"));
            std::process::exit(2);
        }
    };
    let result = match cli.command {
        Command::Tour { samples, seed } => tour::run(tour::TourArgs { samples, seed }).map(|_| 0),
        Command::Convert {
            from,
            to,
            jsonl,
            precision,
            values,
        } => convert::run(convert::ConvertArgs {
            from,
            to,
            values,
            jsonl,
            precision,
        }),
    };
    match result {
        Ok(code) => std::process::exit(code),
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::exit(2);
        }
    }
}
