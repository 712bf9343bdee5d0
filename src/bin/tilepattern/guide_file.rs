//! `--guides FILE`: guide curves, polylines in the mesh's units that the quad rows follow
//! (see [`GuideCurves`]).
//!
//! Two formats, told apart by the first character that is not white space:
//! - JSON: `[[[x, y, z], ...], ...]` (a list of polylines) or `{"curves": [...]}`;
//! - text: one point per line as `x y z` (spaces, tabs, commas or semicolons between the
//!   numbers), polylines separated by one or more blank lines; lines starting with `#` are
//!   comments (they do not separate polylines).

use std::path::Path;

use anyhow::{Context, Result, bail};
use tilepattern::mesh::PolyMesh;
use tilepattern::remesh::GuideCurves;

/// Share of a guide curve's length off the surface above which it is reported.
const OFF_SURFACE_WARNING: f64 = 0.1;

/// Reads `path` as guide curves with the share `weight`, checked on their own; curves lying
/// partly off `surface` (for quads of edge `target_edge`) get a warning, curves wholly off it
/// are refused by the remesh.
pub fn read(path: &Path, weight: f64, surface: &PolyMesh, target_edge: f64) -> Result<GuideCurves> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the guides file {}", path.display()))?;
    let curves = parse(&text).with_context(|| format!("guides file {}", path.display()))?;
    let guides = GuideCurves { curves, weight };
    guides
        .check()
        .with_context(|| format!("guides file {}", path.display()))?;
    if target_edge.is_finite() && target_edge > 0.0 {
        for (curve, share) in guides.off_surface(surface, target_edge) {
            if share > OFF_SURFACE_WARNING && share < 1.0 {
                eprintln!(
                    "warning: guide curve {curve} of {}: {:.0} % of its length lies farther than 2 target edges ({:.3}) from the surface and pulls nothing there; draw or project it onto the surface",
                    path.display(),
                    100.0 * share,
                    2.0 * target_edge
                );
            }
        }
    }
    Ok(guides)
}

/// The polylines of a guides file's text.
pub fn parse(text: &str) -> Result<Vec<Vec<[f64; 3]>>> {
    match text.trim_start().chars().next() {
        Some('[' | '{') => parse_json(text),
        _ => parse_text(text),
    }
}

fn parse_json(text: &str) -> Result<Vec<Vec<[f64; 3]>>> {
    #[derive(serde::Deserialize)]
    #[serde(untagged)]
    enum File {
        Bare(Vec<Vec<Vec<f64>>>),
        Object { curves: Vec<Vec<Vec<f64>>> },
    }
    let file: File = serde_json::from_str(text).context(
        "not JSON guides: write [[[x, y, z], ...], ...] (a list of polylines) or {\"curves\": [...]}",
    )?;
    let (File::Bare(curves) | File::Object { curves }) = file;
    if curves.is_empty() {
        bail!("no guide curves found");
    }
    curves
        .into_iter()
        .enumerate()
        .map(|(c, points)| {
            points
                .into_iter()
                .enumerate()
                .map(|(i, p)| match p[..] {
                    [x, y, z] => Ok([x, y, z]),
                    _ => bail!(
                        "point {i} of curve {c} has {} numbers; every point is [x, y, z]",
                        p.len()
                    ),
                })
                .collect()
        })
        .collect()
}

fn parse_text(text: &str) -> Result<Vec<Vec<[f64; 3]>>> {
    let mut curves: Vec<Vec<[f64; 3]>> = Vec::new();
    let mut current: Vec<[f64; 3]> = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.starts_with('#') {
            continue;
        }
        if line.is_empty() {
            if !current.is_empty() {
                curves.push(std::mem::take(&mut current));
            }
            continue;
        }
        let numbers: Option<Vec<f64>> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .map(|f| f.parse().ok())
            .collect();
        match numbers.as_deref() {
            Some(&[x, y, z]) => current.push([x, y, z]),
            _ => bail!(
                "line {}: '{line}' is not a point; write x y z per line, a blank line between curves",
                number + 1
            ),
        }
    }
    if !current.is_empty() {
        curves.push(current);
    }
    if curves.is_empty() {
        bail!("no guide curves found; write x y z per line, a blank line between curves");
    }
    Ok(curves)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_curves_split_at_blank_lines() {
        let text = "# ridge\n0 0 0\n1,0,0.5\n\n\n# valley\n0 1 0\n1\t1\t0\n2;1;0\n";
        assert_eq!(
            parse(text).unwrap(),
            vec![
                vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.5]],
                vec![[0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [2.0, 1.0, 0.0]]
            ]
        );
        let err = parse("0 0 0\n1 0\n").unwrap_err().to_string();
        assert!(err.contains("line 2"), "{err}");
        assert!(parse("# nothing\n\n").is_err());
    }

    #[test]
    fn json_bare_and_in_an_object() {
        let curves = vec![vec![[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]]];
        assert_eq!(parse("[[[0,0,0],[1,2,3]]]").unwrap(), curves);
        assert_eq!(parse("{\"curves\": [[[0,0,0],[1,2,3]]]}").unwrap(), curves);
        let err = format!("{:#}", parse("[[[0,0,0]],[[1,2,3],[4,5]]]").unwrap_err());
        assert!(err.contains("point 1 of curve 1"), "{err}");
        assert!(parse("[[0,0,0],[1,2,3]]").is_err());
        assert!(parse("[]").is_err());
    }
}
