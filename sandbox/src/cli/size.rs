//! Parsing of `WxH` image sizes.

/// An image size given as `WxH` on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl std::str::FromStr for Size {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (w, h) = s
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("{s:?} is not WxH (e.g. 1920x1080)"))?;
        let parse = |v: &str| {
            v.trim()
                .parse::<u32>()
                .ok()
                .filter(|&n| (1..=16384).contains(&n))
                .ok_or_else(|| format!("{v:?} in {s:?} is not a size from 1 to 16384"))
        };
        Ok(Self {
            width: parse(w)?,
            height: parse(h)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Size;

    #[test]
    fn parses_and_rejects_sizes() {
        assert_eq!(
            "64x32".parse::<Size>(),
            Ok(Size {
                width: 64,
                height: 32
            })
        );
        assert!("64".parse::<Size>().is_err());
        assert!("0x10".parse::<Size>().is_err());
        assert!("axb".parse::<Size>().is_err());
    }
}
