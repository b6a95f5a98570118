//! The units of the plots' axis labels (`[units] length = "mm", force =
//! "N"`): labels only, nothing is converted (the case file's numbers are in
//! the user's consistent units). A label names its unit only when the case
//! declares the units it is made of: `contact pressure (N/mm²)` with both,
//! `contact pressure` with either missing (never an empty `()` or a
//! dimension's name in place of a unit).

/// The physical dimension of a plotted quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// A length: displacements, gaps, abscissae.
    Length,
    /// A force: reactions.
    Force,
    /// Force per area: pressures and tractions.
    Stress,
    /// Force times length: reaction moments.
    Moment,
}

/// The length and force units of a case (`None`: not declared).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Units {
    pub length: Option<String>,
    pub force: Option<String>,
}

impl Units {
    /// The unit of `dimension`: `mm`, `N`, `N/mm²`; `None` when a unit it
    /// is made of is not declared.
    pub fn of(&self, dimension: Dimension) -> Option<String> {
        let length = self.length.as_deref();
        let force = self.force.as_deref();
        match dimension {
            Dimension::Length => length.map(str::to_string),
            Dimension::Force => force.map(str::to_string),
            Dimension::Stress => Some(format!("{}/{}²", force?, length?)),
            Dimension::Moment => Some(format!("{}·{}", force?, length?)),
        }
    }

    /// An axis label: `name (unit)`, e.g. `contact pressure (N/mm²)`, or
    /// `name` alone without the unit.
    pub fn label(&self, name: &str, dimension: Dimension) -> String {
        match self.of(dimension) {
            Some(unit) => format!("{name} ({unit})"),
            None => name.to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_with_and_without_units() {
        let declared = Units {
            length: Some("mm".into()),
            force: Some("N".into()),
        };
        assert_eq!(
            declared.label("contact pressure", Dimension::Stress),
            "contact pressure (N/mm²)"
        );
        assert_eq!(declared.label("gap", Dimension::Length), "gap (mm)");
        assert_eq!(declared.of(Dimension::Force).as_deref(), Some("N"));
        assert_eq!(declared.of(Dimension::Moment).as_deref(), Some("N·mm"));
        let none = Units::default();
        assert_eq!(
            none.label("contact pressure", Dimension::Stress),
            "contact pressure"
        );
        assert_eq!(none.label("reaction", Dimension::Force), "reaction");
        let length_only = Units {
            length: Some("m".into()),
            force: None,
        };
        assert_eq!(length_only.of(Dimension::Stress), None);
        assert_eq!(length_only.label("gap", Dimension::Length), "gap (m)");
        assert_eq!(length_only.label("pressure", Dimension::Stress), "pressure");
    }
}
