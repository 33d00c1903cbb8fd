//! `clap::ValueEnum` for [`ToneCurve`] (the `clap` feature): the command line accepts its short
//! names.

use super::ToneCurve;
use clap::builder::PossibleValue;
use clap::ValueEnum;

impl ValueEnum for ToneCurve {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self {
            ToneCurve::Clamp => "Clamp to [0, 1]",
            ToneCurve::Aces => "The ACES filmic fit",
            ToneCurve::AgX => "AgX",
        };
        Some(PossibleValue::new(self.short_name()).help(help))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_accepts_the_short_names() {
        for (name, curve) in [
            ("clamp", ToneCurve::Clamp),
            ("aces", ToneCurve::Aces),
            ("agx", ToneCurve::AgX),
        ] {
            assert_eq!(ToneCurve::from_str(name, false), Ok(curve));
        }
    }
}
