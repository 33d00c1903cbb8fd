//! Output paths checked before any rendering, so a typo fails at once instead of after the work.

use anyhow::{bail, Context as _};
use std::path::Path;

/// Checks that the file `path` given to `option` can be written: its extension (ignoring case)
/// is one of `extensions` and its folder exists. Returns the lower-case extension.
pub fn check_file(option: &str, path: &Path, extensions: &[&str]) -> anyhow::Result<String> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    if !extensions.contains(&extension.as_str()) {
        let names: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
        bail!(
            "{option} {} must end in {}",
            path.display(),
            names.join(" or ")
        );
    }
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(folder) = folder.filter(|f| !f.is_dir()) {
        bail!(
            "{option} {}: the folder {} does not exist",
            path.display(),
            folder.display()
        );
    }
    Ok(extension)
}

/// Creates the output folder `path` given to `option` (with its parents), before any work.
pub fn create_folder(option: &str, path: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(path)
        .with_context(|| format!("{option} {}: cannot create the folder", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_and_folders_are_checked() {
        assert_eq!(
            check_file("--out", Path::new("x.PNG"), &["png", "exr"]).unwrap(),
            "png"
        );
        let jpg = check_file("--out", Path::new("x.jpg"), &["png", "exr"]).unwrap_err();
        assert_eq!(jpg.to_string(), "--out x.jpg must end in .png or .exr");
        let missing = check_file("--json", Path::new("/no/such/dir/b.json"), &["json"]);
        assert_eq!(
            missing.unwrap_err().to_string(),
            "--json /no/such/dir/b.json: the folder /no/such/dir does not exist"
        );
        assert!(check_file("--json", &std::env::temp_dir().join("b.json"), &["json"]).is_ok());
    }
}
