//! `subdivide --spectrum-weights FILE`: per-vertex weights of the Möbius–linear spectrum
//! (seed 000 §7.2; `nlsubdiv::subdivide_weighted`), a small text file beside the mesh with
//! one number per input vertex, in the mesh's vertex order:
//!
//! ```text
//! # comments and blank lines are ignored
//! 1        # vertex 0: the Möbius result (the convention of --spectrum)
//! 0        # vertex 1: the linear result
//! 0.25     # vertex 2: a quarter Möbius, three quarters linear
//! ```
//!
//! Each weight is that of the Möbius result, as `--spectrum W` is; they replace `--spectrum`.
//! The library carries them to every output vertex of every level (an old vertex keeps its
//! weight, an edge point takes the mean of its ends, a face point the mean of its corners).
//! The whole file is checked before anything is computed, and a bad one is refused naming the
//! file and line (exit 2): more than one field on a line, a number that does not parse, a
//! weight that is NaN or outside `[0, 1]` (naming its vertex too), and a count of weights that
//! is not the mesh's vertex count.

use std::path::Path;

use crate::error::{CliError, CliResult};

/// Reads the weights of `path` for a mesh of `num_vertices` vertices.
///
/// # Errors
/// Exit 2 naming the file (and the line) for a bad file; the read error of the file.
pub fn read(path: &Path, num_vertices: usize) -> CliResult<Vec<f64>> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        CliError::bad_input(format!(
            "{}: cannot read the spectrum weights: {e}",
            path.display()
        ))
    })?;
    parse(&text, num_vertices).map_err(|(line, msg)| {
        let at = line.map_or(String::new(), |l| format!(":{l}"));
        CliError::bad_input(format!("{}{at}: {msg}", path.display()))
    })
}

/// [`read`] on the file's text; errors are `(line, message)`.
fn parse(text: &str, num_vertices: usize) -> Result<Vec<f64>, (Option<usize>, String)> {
    let mut weights = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = Some(i + 1);
        let content = raw.split('#').next().unwrap_or("");
        let mut fields = content.split_whitespace();
        let Some(field) = fields.next() else {
            continue;
        };
        if fields.next().is_some() {
            return Err((line, "one weight per line".to_string()));
        }
        let v = weights.len();
        let w: f64 = field
            .parse()
            .map_err(|_| (line, format!("vertex {v}: {field:?} is not a number")))?;
        if !(0.0..=1.0).contains(&w) {
            return Err((
                line,
                format!("vertex {v}: weight {field} is not in [0, 1] (0 linear, 1 Möbius)"),
            ));
        }
        weights.push(w);
    }
    if weights.len() != num_vertices {
        return Err((
            None,
            format!(
                "{} spectrum weights for a mesh of {num_vertices} vertices (one per vertex)",
                weights.len()
            ),
        ));
    }
    Ok(weights)
}

#[cfg(test)]
mod tests {
    use super::parse;

    #[test]
    fn weights_and_comments() {
        let w = parse("# w\n1\n\n0 # linear\n  0.25\n", 3).unwrap_or_default();
        assert_eq!(w, vec![1.0, 0.0, 0.25]);
    }

    #[test]
    fn bad_files_name_the_line() {
        let line = |t: &str, n| parse(t, n).err().map(|(l, _)| l);
        assert_eq!(line("1\n0.5 0.5\n", 2), Some(Some(2)));
        assert_eq!(line("1\nx\n", 2), Some(Some(2)));
        assert_eq!(line("1\nNaN\n", 2), Some(Some(2)));
        assert_eq!(line("1\n1.5\n", 2), Some(Some(2)));
        assert_eq!(line("1\n-0.1\n", 2), Some(Some(2)));
        assert_eq!(line("1\n", 2), Some(None));
        assert_eq!(line("1\n1\n1\n", 2), Some(None));
    }
}
