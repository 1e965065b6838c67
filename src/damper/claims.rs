//! What a paper says about its cases' damping, as checkable statements: "case A damps more
//! than case B" or "A and B damp about the same", each naming the two cases it compares.

use crate::error::{Error, Result};

/// How the two cases of a claim compare.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Relation {
    /// The first case damps more than the second.
    Greater,
    /// The damping the balls add (ζ − ζ_empty) of the two cases differs by at most
    /// `within` (a fraction) of the larger one.
    Similar {
        /// Largest difference, a fraction of the larger added damping.
        within: f64,
    },
}

impl Relation {
    /// The relation named `name` ("greater" or "similar"; `within` is needed by "similar"
    /// only). Errors: another name, a "similar" without a `within` in (0, 1], a "greater"
    /// with one (each naming `field`).
    pub fn parse(name: &str, within: Option<f64>, field: &str) -> Result<Relation> {
        match (name, within) {
            ("greater", None) => Ok(Relation::Greater),
            ("greater", Some(w)) => Err(Error::invalid(
                format!("{field}.within"),
                w,
                "no within for relation = \"greater\"",
            )),
            ("similar", Some(w)) if w > 0.0 && w <= 1.0 => Ok(Relation::Similar { within: w }),
            ("similar", w) => Err(Error::invalid(
                format!("{field}.within"),
                w.map_or("missing".into(), |w| w.to_string()),
                "a fraction in (0, 1] for relation = \"similar\"",
            )),
            (other, _) => Err(Error::invalid(
                format!("{field}.relation"),
                format!("{other:?}"),
                "\"greater\" or \"similar\"",
            )),
        }
    }

    /// Whether damping ratios `a` and `b` (fractions) of the two cases satisfy the
    /// relation, `empty` the empty structure's damping ratio.
    pub fn holds(&self, a: f64, b: f64, empty: f64) -> bool {
        match *self {
            Relation::Greater => a > b,
            Relation::Similar { within } => {
                let (da, db) = (a - empty, b - empty);
                (da - db).abs() <= within * da.abs().max(db.abs())
            }
        }
    }

    /// The relation as a sign between two names: `>` or `≈`.
    pub fn symbol(&self) -> &'static str {
        match self {
            Relation::Greater => ">",
            Relation::Similar { .. } => "≈",
        }
    }
}

/// One statement of the paper about two of its cases.
#[derive(Debug, Clone, PartialEq)]
pub struct Claim {
    /// What the paper says, in words (with where it says it).
    pub says: String,
    /// The two cases compared, by name.
    pub cases: [String; 2],
    /// How they compare.
    pub relation: Relation,
}

impl Claim {
    /// The comparison as text: `2-steel-9 > 5-steel-3`.
    pub fn compares(&self) -> String {
        format!(
            "{} {} {}",
            self.cases[0],
            self.relation.symbol(),
            self.cases[1]
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relations_compare_damping_ratios_and_added_damping() {
        let g = Relation::parse("greater", None, "claim[0]").unwrap();
        assert!(g.holds(0.0069, 0.0063, 0.0045));
        assert!(!g.holds(0.0063, 0.0069, 0.0045));
        let s = Relation::parse("similar", Some(0.25), "claim[0]").unwrap();
        // Table 2: 19 glass (0.63 %) and 7 alumina (0.61 %) add 0.18 and 0.16 points.
        assert!(s.holds(0.0063, 0.0061, 0.0045));
        // 0.455 % and 0.952 % add 0.005 and 0.502 points: not similar.
        assert!(!s.holds(0.00455, 0.00952, 0.0045));
        for (name, within, field) in [
            ("bigger", None, "claim[1].relation"),
            ("similar", None, "claim[1].within"),
            ("similar", Some(1.5), "claim[1].within"),
            ("greater", Some(0.1), "claim[1].within"),
        ] {
            let e = Relation::parse(name, within, "claim[1]")
                .unwrap_err()
                .to_string();
            assert!(e.contains(field), "{e}");
        }
    }
}
