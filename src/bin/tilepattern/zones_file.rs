//! `--zones FILE`: a bond per face (issue 20), e.g. a band of herringbone in a staggered
//! vault. Faces the file does not list take `--pattern`.
//!
//! Two formats, told apart by the first character that is not white space:
//! - text: one `FACE BOND` or `FIRST-LAST BOND` (both ends included) per line, the two
//!   separated by spaces, tabs or a comma; `#` starts a comment; blank lines are skipped;
//! - JSON: an object `{"FACE": "bond", "FIRST-LAST": "bond", ...}`, or an array with one bond
//!   name (or `null`: `--pattern`) per face.
//!
//! Bond names are those of `--pattern` (stack, staggered, running-bond, herringbone,
//! basket-weave). Faces are counted from 0 in file order, as everywhere on the command line.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, Result, bail};
use clap::ValueEnum;

use super::BondArg;

/// Reads `path` for a mesh of `faces` faces (`mesh` names it in messages: "quad mesh",
/// "input surface"): each face's bond, `None` where the file lists none.
pub fn read(path: &Path, faces: usize, mesh: &str) -> Result<Vec<Option<BondArg>>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the zones file {}", path.display()))?;
    parse(&text, faces, mesh).with_context(|| format!("zones file {}", path.display()))
}

/// The bond of each of `faces` faces from a zones file's text.
pub fn parse(text: &str, faces: usize, mesh: &str) -> Result<Vec<Option<BondArg>>> {
    let mut zones = Zones {
        bonds: vec![None; faces],
        mesh,
    };
    match text.trim_start().chars().next() {
        Some('[' | '{') => parse_json(text, &mut zones)?,
        _ => parse_text(text, &mut zones)?,
    }
    Ok(zones.into())
}

/// The bonds being read, with where each was set (to name both places of a conflict).
struct Zones<'a> {
    bonds: Vec<Option<(BondArg, String)>>,
    mesh: &'a str,
}

impl Zones<'_> {
    /// Gives faces `first..=last` the bond `bond`, read at `place` (e.g. "line 3").
    fn set(&mut self, [first, last]: [usize; 2], bond: BondArg, place: &str) -> Result<()> {
        let faces = self.bonds.len();
        if last >= faces {
            bail!(
                "{place}: face {last} is out of range: the {} has {faces} faces (0 to {})",
                self.mesh,
                faces.saturating_sub(1)
            );
        }
        for face in first..=last {
            match &self.bonds[face] {
                Some((other, at)) if other.name() != bond.name() => bail!(
                    "{place}: face {face} is {} here but {} at {at}; give each face one bond",
                    bond.name(),
                    other.name()
                ),
                _ => self.bonds[face] = Some((bond, place.to_owned())),
            }
        }
        Ok(())
    }
}

impl From<Zones<'_>> for Vec<Option<BondArg>> {
    fn from(zones: Zones<'_>) -> Self {
        zones.bonds.into_iter().map(|z| z.map(|(b, _)| b)).collect()
    }
}

fn parse_text(text: &str, zones: &mut Zones<'_>) -> Result<()> {
    let mut listed = 0;
    for (number, line) in text.lines().enumerate() {
        let place = format!("line {}", number + 1);
        let line = line.split('#').next().unwrap_or_default().trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let [faces, bond] = fields[..] else {
            bail!(
                "{place}: '{line}' is not a zone; write FACE BOND or FIRST-LAST BOND, e.g. 12 herringbone or 40-79 basket-weave"
            );
        };
        let faces = face_range(faces).with_context(|| place.clone())?;
        let bond = bond_named(bond).with_context(|| place.clone())?;
        zones.set(faces, bond, &place)?;
        listed += 1;
    }
    if listed == 0 {
        bail!("no zones found; write one FACE BOND or FIRST-LAST BOND line per zone");
    }
    Ok(())
}

fn parse_json(text: &str, zones: &mut Zones<'_>) -> Result<()> {
    let value: serde_json::Value = serde_json::from_str(text).context(
        "not a JSON zones file: write {\"FACE\": \"bond\", \"FIRST-LAST\": \"bond\", ...} or [\"bond\" or null, ...] with one item per face",
    )?;
    match value {
        serde_json::Value::Object(map) => {
            if map.is_empty() {
                bail!("no zones found; write {{\"FACE\": \"bond\", ...}}");
            }
            // Faces in order, whatever the order of the keys.
            let mut entries = Vec::with_capacity(map.len());
            for (key, bond) in &map {
                let place = format!("key \"{key}\"");
                let faces = face_range(key).with_context(|| place.clone())?;
                entries.push((faces, place, bond));
            }
            entries.sort_by_key(|(faces, _, _)| *faces);
            for (faces, place, bond) in entries {
                if let Some(bond) = json_bond(bond).with_context(|| place.clone())? {
                    zones.set(faces, bond, &place)?;
                }
            }
        }
        serde_json::Value::Array(items) => {
            let faces = zones.bonds.len();
            if items.len() != faces {
                bail!(
                    "the array gives {} zones for a {} of {faces} faces; give one bond name (or null) per face, or an object {{\"FACE\": \"bond\", ...}}",
                    items.len(),
                    zones.mesh
                );
            }
            for (face, bond) in items.iter().enumerate() {
                let place = format!("item {face}");
                if let Some(bond) = json_bond(bond).with_context(|| place.clone())? {
                    zones.set([face, face], bond, &place)?;
                }
            }
        }
        _ => bail!(
            "a JSON zones file is an object {{\"FACE\": \"bond\", ...}} or an array with one bond name (or null) per face"
        ),
    }
    Ok(())
}

/// A JSON bond: a name, or `null` for `--pattern`.
fn json_bond(value: &serde_json::Value) -> Result<Option<BondArg>> {
    match value {
        serde_json::Value::Null => Ok(None),
        serde_json::Value::String(name) => bond_named(name).map(Some),
        other => bail!("{other} is not a bond; write a bond name as a string, or null"),
    }
}

/// `FACE` or `FIRST-LAST` (both included).
fn face_range(text: &str) -> Result<[usize; 2]> {
    let face = |t: &str| {
        t.trim().parse::<usize>().map_err(|_| {
            anyhow::anyhow!(
                "'{text}' is not a face or a range of faces; write a face index counted from 0 (e.g. 12) or FIRST-LAST (e.g. 40-79)"
            )
        })
    };
    match text.split_once('-') {
        Some((first, last)) => {
            let (first, last) = (face(first)?, face(last)?);
            if first > last {
                bail!("range '{text}' runs backwards; write FIRST-LAST with FIRST <= LAST");
            }
            Ok([first, last])
        }
        None => face(text).map(|f| [f, f]),
    }
}

/// A bond by its `--pattern` name (any case).
fn bond_named(name: &str) -> Result<BondArg> {
    <BondArg as ValueEnum>::from_str(name.trim(), true).map_err(|_| {
        let names: Vec<&str> = BondArg::value_variants().iter().map(|b| b.name()).collect();
        anyhow::anyhow!("'{name}' is not a bond; write one of {}", names.join(", "))
    })
}

/// Faces per bond name, for the JSON output.
pub fn counts(bonds: &[BondArg]) -> BTreeMap<&'static str, usize> {
    let mut counts = BTreeMap::new();
    for b in bonds {
        *counts.entry(b.name()).or_default() += 1;
    }
    counts
}

/// `bonds` written back as a zones file: one `FIRST-LAST BOND` line per run of equal bonds.
pub fn to_text(bonds: &[BondArg]) -> String {
    let mut text =
        String::from("# face (or first-last, both included) and bond, one zone a line\n");
    let mut start = 0;
    for face in 1..=bonds.len() {
        if face == bonds.len() || bonds[face].name() != bonds[start].name() {
            let name = bonds[start].name();
            if face - 1 == start {
                text.push_str(&format!("{start} {name}\n"));
            } else {
                text.push_str(&format!("{start}-{} {name}\n", face - 1));
            }
            start = face;
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(zones: &[Option<BondArg>]) -> Vec<&'static str> {
        zones.iter().map(|z| z.map_or("-", BondArg::name)).collect()
    }

    #[test]
    fn text_lines_ranges_comments_and_separators() {
        let text = "# a band\n1 herringbone\n\n3-4,basket-weave # two faces\n  5\tStack\n";
        let zones = parse(text, 7, "quad mesh").unwrap();
        assert_eq!(
            names(&zones),
            [
                "-",
                "herringbone",
                "-",
                "basket-weave",
                "basket-weave",
                "stack",
                "-"
            ]
        );
    }

    #[test]
    fn json_objects_and_arrays() {
        let zones = parse(
            "{\"2\": \"running-bond\", \"0-1\": \"herringbone\", \"3\": null}",
            4,
            "quad mesh",
        )
        .unwrap();
        assert_eq!(
            names(&zones),
            ["herringbone", "herringbone", "running-bond", "-"]
        );
        let zones = parse(" [null, \"staggered\", \"stack\"]", 3, "quad mesh").unwrap();
        assert_eq!(names(&zones), ["-", "staggered", "stack"]);
    }

    #[test]
    fn errors_name_the_line_the_face_and_the_fix() {
        let err = |text: &str| format!("{:#}", parse(text, 10, "quad mesh").unwrap_err());
        let e = err("1 herringbone\n2 herringbon\n");
        assert!(
            e.contains("line 2")
                && e.contains("'herringbon' is not a bond")
                && e.contains("basket-weave"),
            "{e}"
        );
        let e = err("10 stack\n");
        assert!(
            e.contains("line 1")
                && e.contains("face 10 is out of range")
                && e.contains("10 faces (0 to 9)"),
            "{e}"
        );
        let e = err("0-12 stack\n");
        assert!(e.contains("face 12 is out of range"), "{e}");
        let e = err("3 stack extra\n");
        assert!(e.contains("line 1") && e.contains("FIRST-LAST BOND"), "{e}");
        let e = err("x stack\n");
        assert!(e.contains("'x' is not a face"), "{e}");
        let e = err("5-2 stack\n");
        assert!(e.contains("runs backwards"), "{e}");
        let e = err("0-3 stack\n3 herringbone\n");
        assert!(
            e.contains("line 2") && e.contains("face 3") && e.contains("line 1"),
            "{e}"
        );
        assert!(err("# nothing\n").contains("no zones"));
        assert!(err("{}").contains("no zones"));
        let e = err("[\"stack\"]");
        assert!(e.contains("1 zones for a quad mesh of 10 faces"), "{e}");
        let e = err("{\"1\": 3}");
        assert!(e.contains("key \"1\"") && e.contains("not a bond"), "{e}");
        let e = err("[1, 2");
        assert!(e.contains("not a JSON zones file"), "{e}");
        // Listing a face twice in the same bond is fine.
        assert!(parse("0-3 stack\n2 stack\n", 10, "quad mesh").is_ok());
    }

    #[test]
    fn written_zones_read_back() {
        let bonds = [
            BondArg::Staggered,
            BondArg::Staggered,
            BondArg::Herringbone,
            BondArg::Staggered,
        ];
        let text = to_text(&bonds);
        assert!(
            text.contains("0-1 staggered\n2 herringbone\n3 staggered\n"),
            "{text}"
        );
        let back: Vec<_> = parse(&text, 4, "quad mesh")
            .unwrap()
            .into_iter()
            .flatten()
            .collect();
        assert_eq!(
            names(&back.into_iter().map(Some).collect::<Vec<_>>()),
            ["staggered", "staggered", "herringbone", "staggered"]
        );
        assert_eq!(counts(&bonds)["staggered"], 3);
    }
}
