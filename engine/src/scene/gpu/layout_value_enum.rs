//! `clap::ValueEnum` for [`BvhLayout`] (the `clap` feature): the command line accepts its names.

use super::BvhLayout;
use clap::builder::PossibleValue;
use clap::ValueEnum;

impl ValueEnum for BvhLayout {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            BvhLayout::Binary => "Binary nodes with float boxes (64 bytes)",
            BvhLayout::Wide => "Compressed 8-wide nodes with byte-quantized boxes (80 bytes)",
        };
        Some(PossibleValue::new(self.name()).help(help))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_accepts_the_names() {
        for layout in BvhLayout::ALL {
            assert_eq!(BvhLayout::from_str(layout.name(), false), Ok(layout));
        }
        assert!(BvhLayout::from_str("quad", false).is_err());
    }
}
