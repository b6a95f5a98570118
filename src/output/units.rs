//! The units of the plots' axis labels (`[units] length = "mm", force =
//! "N"`): labels only, nothing is converted (the case file's numbers are in
//! the user's consistent units). Without a unit the label names the
//! dimension instead, e.g. `contact pressure (force/length²)`.

/// The physical dimension of a plotted quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// A length: displacements, gaps, abscissae.
    Length,
    /// A force: reactions.
    Force,
    /// Force per area: pressures and tractions.
    Stress,
}

/// The length and force units of a case (`None`: not declared).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Units {
    pub length: Option<String>,
    pub force: Option<String>,
}

impl Units {
    /// The unit of `dimension`: `mm`, `N`, `N/mm²`; without a declared unit
    /// the dimension's name (`length`, `force`, `force/length²`).
    pub fn of(&self, dimension: Dimension) -> String {
        let length = self.length.as_deref().unwrap_or("length");
        let force = self.force.as_deref().unwrap_or("force");
        match dimension {
            Dimension::Length => length.to_string(),
            Dimension::Force => force.to_string(),
            Dimension::Stress => format!("{force}/{length}²"),
        }
    }

    /// An axis label: `name (unit)`, e.g. `contact pressure (N/mm²)`.
    pub fn label(&self, name: &str, dimension: Dimension) -> String {
        format!("{name} ({})", self.of(dimension))
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
        assert_eq!(declared.of(Dimension::Force), "N");
        let none = Units::default();
        assert_eq!(
            none.label("contact pressure", Dimension::Stress),
            "contact pressure (force/length²)"
        );
        assert_eq!(none.label("reaction", Dimension::Force), "reaction (force)");
        let length_only = Units {
            length: Some("m".into()),
            force: None,
        };
        assert_eq!(length_only.of(Dimension::Stress), "force/m²");
    }
}
