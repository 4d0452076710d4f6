//! `subdivide --edit FILE`: the edits of differential-space subdivision (seed 001 §4.4) as a
//! small text file beside the mesh, one edit per line:
//!
//! ```text
//! # comments and blank lines are ignored; vertex indices are 0-based
//! curvature V S          # scale the mean curvature of control vertex V by S (δ_V ← S δ_V)
//! normal V NX NY NZ      # the surface normal control vertex V should have in the output
//! ```
//!
//! Every line is checked before anything is computed, and a bad one is refused naming the
//! file and line (exit 2): an unknown keyword, a wrong number of fields, a number that does
//! not parse or is not finite, a vertex not below the mesh's vertex count, a normal of length
//! 0 (the kernel would read it as "no edit"), a vertex edited twice the same way.

use std::path::Path;

use crate::error::{CliError, CliResult};
use crate::memory;

/// The edits of one file, as the kernel's per-vertex arrays (`DifferentialOptions::
/// curvature_scale`, `DifferentialOptions::normals`).
#[derive(Debug, Default)]
pub struct Edits {
    /// Per control vertex: the factor on its mean curvature (1 where the file says nothing);
    /// `None` when the file has no `curvature` line.
    pub curvature_scale: Option<Vec<f64>>,
    /// Per control vertex: the requested normal (0 where the file says nothing); `None` when
    /// the file has no `normal` line.
    pub normals: Option<Vec<[f64; 3]>>,
    /// Number of edit lines.
    pub count: usize,
}

/// Reads `path` for a mesh of `num_vertices` vertices.
///
/// # Errors
/// Exit 2 naming the file and line for a bad line; the read error of the file.
pub fn read(path: &Path, num_vertices: usize) -> CliResult<Edits> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        CliError::bad_input(format!(
            "{}: cannot read the edit file: {e}",
            path.display()
        ))
    })?;
    parse(&text, num_vertices)
        .map_err(|(line, msg)| CliError::bad_input(format!("{}:{line}: {msg}", path.display())))
}

/// [`read`] on the file's text; errors are `(line, message)`.
fn parse(text: &str, num_vertices: usize) -> Result<Edits, (usize, String)> {
    let mut edits = Edits::default();
    // Which vertices already have an edit of each kind (a repeated edit is a mistake, not an
    // override: the order of lines would silently decide the result).
    let mut seen_scale: Vec<bool> = Vec::new();
    let mut seen_normal: Vec<bool> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let content = raw.split('#').next().unwrap_or("");
        let fields: Vec<&str> = content.split_whitespace().collect();
        let Some((&keyword, rest)) = fields.split_first() else {
            continue;
        };
        let want = match keyword {
            "curvature" => 2,
            "normal" => 4,
            _ => {
                return Err((
                    line,
                    format!(
                        "unknown edit {}: 'curvature V S' or 'normal V NX NY NZ'",
                        crate::error::quote(keyword.as_bytes())
                    ),
                ))
            }
        };
        if rest.len() != want {
            return Err((
                line,
                format!(
                    "'{keyword}' takes {want} values (a vertex and {}), found {}",
                    if want == 2 {
                        "a factor"
                    } else {
                        "three coordinates"
                    },
                    rest.len()
                ),
            ));
        }
        let v = vertex(rest.first().copied().unwrap_or(""), num_vertices).map_err(|m| (line, m))?;
        let nums = rest
            .get(1..)
            .unwrap_or(&[])
            .iter()
            .map(|s| number(s))
            .collect::<Result<Vec<f64>, String>>()
            .map_err(|m| (line, m))?;
        let (seen, kind) = if keyword == "curvature" {
            (&mut seen_scale, "a curvature")
        } else {
            (&mut seen_normal, "a normal")
        };
        if seen.is_empty() {
            *seen = memory::filled(num_vertices, false, "the edit file")
                .map_err(|e| (line, e.to_string()))?;
        }
        match seen.get_mut(v) {
            Some(s) if *s => {
                return Err((line, format!("vertex {v} has {kind} edit already")));
            }
            Some(s) => *s = true,
            None => return Err((line, format!("vertex {v} is out of range"))),
        }
        if keyword == "curvature" {
            let scale = edits
                .curvature_scale
                .get_or_insert_with(|| vec![1.0; num_vertices]);
            if let (Some(slot), Some(&s)) = (scale.get_mut(v), nums.first()) {
                *slot = s;
            }
        } else {
            let n = [
                nums.first().copied().unwrap_or(0.0),
                nums.get(1).copied().unwrap_or(0.0),
                nums.get(2).copied().unwrap_or(0.0),
            ];
            if n == [0.0; 3] {
                return Err((
                    line,
                    format!("the normal of vertex {v} has length 0 (give a direction)"),
                ));
            }
            let normals = edits
                .normals
                .get_or_insert_with(|| vec![[0.0; 3]; num_vertices]);
            if let Some(slot) = normals.get_mut(v) {
                *slot = n;
            }
        }
        edits.count += 1;
    }
    Ok(edits)
}

/// A vertex index below `n`.
fn vertex(s: &str, n: usize) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(v) if v < n => Ok(v),
        Ok(v) => Err(format!(
            "vertex {v} is out of range: the mesh has {n} vertices (0-based indices)"
        )),
        Err(_) => Err(format!(
            "{} is not a vertex index",
            crate::error::quote(s.as_bytes())
        )),
    }
}

/// A finite number.
fn number(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!(
            "{} is not finite",
            crate::error::quote(s.as_bytes())
        )),
        Err(_) => Err(format!(
            "{} is not a number",
            crate::error::quote(s.as_bytes())
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_become_per_vertex_arrays() {
        let e = parse(
            "# two edits\ncurvature 1 2.5\n\nnormal 3 0 0 2 # tilt\ncurvature 0 -1\n",
            5,
        )
        .unwrap_or_default();
        assert_eq!(e.count, 3);
        assert_eq!(
            e.curvature_scale.as_deref(),
            Some(&[-1.0, 2.5, 1.0, 1.0, 1.0][..])
        );
        let n = e.normals.unwrap_or_default();
        assert_eq!(n.get(3), Some(&[0.0, 0.0, 2.0]));
        assert_eq!(n.first(), Some(&[0.0; 3]));
    }

    #[test]
    fn bad_lines_name_the_line() {
        for (text, line, part) in [
            ("curvature 0 1\nbend 0 1\n", 2, "unknown edit"),
            ("curvature 0\n", 1, "takes 2 values"),
            ("normal 0 1 2\n", 1, "takes 4 values"),
            ("curvature 9 1\n", 1, "out of range"),
            ("curvature -1 1\n", 1, "not a vertex index"),
            ("curvature 0 nan\n", 1, "not finite"),
            ("curvature 0 inf\n", 1, "not finite"),
            ("curvature 0 x\n", 1, "not a number"),
            ("normal 0 0 0 0\n", 1, "length 0"),
            ("normal 1 0 0 1\nnormal 1 1 0 0\n", 2, "already"),
            ("curvature 1 2\ncurvature 1 3\n", 2, "already"),
        ] {
            match parse(text, 4) {
                Err((l, m)) => {
                    assert_eq!(l, line, "{text:?}: {m}");
                    assert!(m.contains(part), "{text:?}: {m}");
                }
                Ok(_) => panic!("{text:?} accepted"),
            }
        }
        // A curvature and a normal on the same vertex are two different edits.
        assert!(parse("curvature 1 2\nnormal 1 0 0 1\n", 4).is_ok());
    }
}
