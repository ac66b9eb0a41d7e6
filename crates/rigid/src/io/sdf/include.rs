//! SDFormat's `<include>`: another file's model read as a nested model of the including one
//! (`<uri>` `model://NAME`, `file://PATH` or a path; `<name>` and `<pose>` override the model's
//! own).

use super::parse::{child, version_is_old, Frame, Joint, Link, Pose, Reader};
use super::{SdfError, SdfWarning};
use roxmltree::Node;
use std::path::{Path, PathBuf};

/// The folders `model://NAME` is looked up in before the including file's: Gazebo's and
/// SDFormat's resource paths.
const RESOURCE_PATHS: [&str; 4] = [
    "GZ_SIM_RESOURCE_PATH",
    "SDF_PATH",
    "IGN_GAZEBO_RESOURCE_PATH",
    "GAZEBO_MODEL_PATH",
];

impl Reader<'_> {
    /// `<include>` `n` in the model of scope `prefix`: the one model of the file its `<uri>`
    /// names read as a nested model, named by the include's `<name>` (else its own) and placed
    /// by the include's `<pose>` (else its own). Its links, joints and frames are added; returns
    /// its name and pose (relative to the including model's scope, as written). Errors and
    /// warnings from the included file name it and are reported at the include's line.
    pub(super) fn include(
        &mut self,
        n: Node,
        prefix: &str,
        links: &mut Vec<Link>,
        joints: &mut Vec<Joint>,
        frames: &mut Vec<Frame>,
    ) -> Result<(String, Pose), SdfError> {
        let what = || "<include>".to_string();
        let uri = child(n, "uri")
            .and_then(|u| u.text())
            .map(str::trim)
            .filter(|u| !u.is_empty())
            .ok_or_else(|| self.error(n, what(), "no <uri>"))?;
        let merge = child(n, "merge").and_then(|m| m.text()).map(str::trim);
        if matches!(merge, Some("true" | "1")) {
            return Err(self.error(
                n,
                what(),
                "<merge>true</merge> is not read (without it the model keeps its own scope, NAME::)",
            ));
        }
        let path = self
            .include_file(uri)
            .map_err(|e| self.error(n, what(), e))?;
        let file = path.display().to_string();
        let path = canonical(&path);
        if self.chain.contains(&path) {
            let names: Vec<String> = (self.chain.iter().chain([&path]))
                .map(|p| p.display().to_string())
                .collect();
            let message = format!("include loop: {}", names.join(" -> "));
            return Err(self.error(n, what(), message));
        }
        let text = std::fs::read_to_string(&path)
            .map_err(|e| self.error(n, what(), format!("{file}: {e}")))?;
        let doc = roxmltree::Document::parse(&text)
            .map_err(|e| self.error(n, what(), format!("{file}: {e}")))?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let mut inner = Reader {
            doc: &doc,
            dir,
            warnings: Vec::new(),
            chain: self.chain.iter().cloned().chain([path.clone()]).collect(),
            included: std::collections::HashMap::new(),
        };
        let in_file = |e: SdfError| self.error(n, what(), format!("in {file}: {e}"));
        let (m, version, _) = inner.the_model().map_err(in_file)?;
        let name = child(n, "name")
            .and_then(|t| t.text())
            .map(str::trim)
            .unwrap_or_else(|| m.attribute("name").unwrap_or("model"))
            .to_string();
        let pose = if child(n, "pose").is_some() {
            self.pose(n, &what())?
        } else {
            inner
                .pose(m, &format!("model \"{name}\""))
                .map_err(in_file)?
        };
        let scope = format!("{prefix}{name}::");
        let first = (links.len(), joints.len(), frames.len());
        // the included file's own version decides `use_parent_model_frame` and `frame`
        inner
            .collect(m, &scope, version_is_old(&version), links, joints, frames)
            .map_err(in_file)?;
        for l in &mut links[first.0..] {
            l.file.get_or_insert_with(|| path.clone());
        }
        // the innermost file first: a nested include recorded its own
        self.included.extend(inner.included.drain());
        let names = (links[first.0..].iter().map(|l| &l.name))
            .chain(joints[first.1..].iter().map(|j| &j.name))
            .chain(frames[first.2..].iter().map(|f| &f.name));
        for name in names {
            self.included
                .entry(name.clone())
                .or_insert_with(|| path.clone());
        }
        if child(n, "static").is_some() {
            self.warn(
                n,
                what(),
                "an include's <static> is not read (nor a nested model's): its links move as its \
                 joints say",
            );
        }
        if child(n, "placement_frame").is_some() {
            self.warn(
                n,
                what(),
                "<placement_frame> is not read: the model is placed by its own frame",
            );
        }
        let line = self.line(n);
        for w in inner.warnings {
            self.warnings.push(SdfWarning {
                line,
                element: what(),
                message: format!("{file}: {w}"),
            });
        }
        Ok((name, pose))
    }

    /// The file `<include>`'s `uri` names: `model://NAME/...` in the folders of
    /// [`RESOURCE_PATHS`], then in the including file's folder and the one above it (a
    /// `models/` folder of siblings); `file://PATH` and a plain path from the including file's
    /// folder. A folder is read through its `model.config` (the `<sdf>` of the highest
    /// version), else its `model.sdf`.
    fn include_file(&self, uri: &str) -> Result<PathBuf, String> {
        let candidates: Vec<PathBuf> = match uri.strip_prefix("model://") {
            Some(rest) => {
                let mut dirs: Vec<PathBuf> = RESOURCE_PATHS
                    .iter()
                    .filter_map(std::env::var_os)
                    .flat_map(|v| std::env::split_paths(&v).collect::<Vec<_>>())
                    .filter(|d| !d.as_os_str().is_empty())
                    .collect();
                // this file's folder made absolute, so that a relative one has a parent
                let here = canonical(if self.dir.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    self.dir
                });
                let above = here.parent().map(Path::to_path_buf);
                dirs.push(here);
                dirs.extend(above);
                dirs.into_iter().map(|d| d.join(rest)).collect()
            }
            None => vec![self.dir.join(uri.strip_prefix("file://").unwrap_or(uri))],
        };
        let mut why = None;
        for c in candidates {
            if c.is_file() {
                return Ok(c);
            }
            if c.is_dir() {
                match model_in_folder(&c) {
                    Ok(file) => return Ok(file),
                    Err(e) => why = why.or(Some(e)), // a folder of that name without a model
                }
            }
        }
        if let Some(e) = why {
            return Err(e);
        }
        Err(format!(
            "\"{uri}\" not found (model:// is looked up in {} and beside this file)",
            RESOURCE_PATHS.join(", ")
        ))
    }
}

/// The model file of a model's folder: the `<sdf>` of the highest version its `model.config`
/// lists, else `model.sdf`.
fn model_in_folder(dir: &Path) -> Result<PathBuf, String> {
    let config = dir.join("model.config");
    if let Ok(text) = std::fs::read_to_string(&config) {
        let doc =
            roxmltree::Document::parse(&text).map_err(|e| format!("{}: {e}", config.display()))?;
        let version = |n: &Node| -> Vec<u32> {
            let v = n.attribute("version").unwrap_or("0");
            v.split('.').filter_map(|p| p.parse().ok()).collect()
        };
        let best = doc
            .descendants()
            .filter(|n| n.has_tag_name("sdf"))
            .max_by(|a, b| version(a).cmp(&version(b)));
        if let Some(file) = best.and_then(|n| n.text()).map(str::trim) {
            return Ok(dir.join(file));
        }
        return Err(format!(
            "{}: no <sdf> names the model's file",
            config.display()
        ));
    }
    let sdf = dir.join("model.sdf");
    if sdf.is_file() {
        Ok(sdf)
    } else {
        Err(format!("{}: no model.config or model.sdf", dir.display()))
    }
}

/// `path` made absolute with its links resolved (as it is, if that fails), to tell a file met
/// again.
pub(super) fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}
