//! The particle damping index (eq. 44) and the paper's Table 1: computed ζ and η beside the
//! printed values, and the search for the reading of Table 1's η inputs.

use super::body::Body;
use super::collision::{collide_with_mu, Collision};
use crate::error::Result;
use crate::material::Material;

/// Particle damping index ζ = ν E ρ (v_n² + μ v_t²)/σ_s² (eq. 44), dimensionless in SI units
/// (E, σ_s in Pa, ρ in kg/m³, speeds in m/s). Table 1 prints ζ × 10³.
pub fn damping_index(m: &Material, v_n: f64, v_t: f64) -> f64 {
    m.nu * m.youngs * m.rho * (v_n * v_n + m.mu * v_t * v_t) / m.yield_strength.powi(2)
}

/// Table 1 prints ζ in units of 10⁻³.
pub const ZETA_TABLE_SCALE: f64 = 1e3;

/// Speeds at which Table 1 evaluates eq. 44: v_n = 1 m/s, v_t = 0.1 m/s (Section 5).
pub const TABLE1_SPEEDS: (f64, f64) = (1.0, 0.1);

/// Table 1 as printed: preset name, ζ × 10³ and η, as the printed strings (their number of
/// decimals is the printed precision).
pub const TABLE1_PRINTED: [(&str, &str, &str); 9] = [
    ("copper", "34.749", "0.147"),
    ("steel", "14.038", "0.139"),
    ("concrete", "13.134", "0.132"),
    ("cast-iron", "5.537", "0.129"),
    ("alumina", "4.748", "0.131"),
    ("glass", "4.342", "0.129"),
    ("wood", "1.317", "0.102"),
    ("aluminum", "0.7448", "0.087"),
    ("rubber", "0.056", "0.004"),
];

/// One unit of the last printed digit of a decimal string ("34.749" → 0.001).
fn last_digit_unit(s: &str) -> f64 {
    let decimals = s.split('.').nth(1).map_or(0, str::len);
    10f64.powi(-(decimals as i32))
}

/// Which η of a collision a reading uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EtaKind {
    /// Eq. 33 (normal impact only).
    Eq33,
    /// Eq. 43 (the paper's friction revision).
    Eq43,
    /// Eq. 33's definition with the Coulomb stick/slip impulse (translation + spin).
    Impulse,
}

impl EtaKind {
    /// The chosen η of a collision.
    pub fn of(self, c: &Collision) -> f64 {
        match self {
            EtaKind::Eq33 => c.eta,
            EtaKind::Eq43 => c.eta_friction,
            EtaKind::Impulse => c.eta_impulse,
        }
    }
}

/// One reading of the inputs behind Table 1's η: the velocities of the two (identical,
/// D = 20 mm) balls, or of one ball against a rigid wall, and which η.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EtaReading {
    /// Short description.
    pub label: &'static str,
    /// Ball 1 velocity [normal, tangential], m/s.
    pub v1: [f64; 2],
    /// Ball 2 velocity [normal, tangential], m/s (ignored for a wall: at rest).
    pub v2: [f64; 2],
    /// Ball 1 hits a rigid wall instead of a second ball.
    pub wall: bool,
    /// Which η.
    pub kind: EtaKind,
}

/// The candidate readings searched: normal speeds (±1, 1 on a ball at rest, ±0.5 (relative
/// speed 1), 1 onto a rigid wall) × {no tangential speed with eq. 33; Section 5's 0.1 m/s per
/// moving ball (signed like the normal speed) with eq. 43 or with the Coulomb impulse}.
pub fn candidate_readings() -> Vec<EtaReading> {
    let normals: [(&str, [f64; 2], [f64; 2], bool); 4] = [
        ("+1/-1", [1.0, 0.1], [-1.0, -0.1], false),
        ("+1/rest", [1.0, 0.1], [0.0, 0.0], false),
        ("+0.5/-0.5", [0.5, 0.05], [-0.5, -0.05], false),
        ("+1/wall", [1.0, 0.1], [0.0, 0.0], true),
    ];
    let labels: [[&str; 3]; 4] = [
        ["+1/-1 eq33", "+1/-1 vt+-0.1 eq43", "+1/-1 vt+-0.1 impulse"],
        [
            "+1/rest eq33",
            "+1/rest vt0.1 eq43",
            "+1/rest vt0.1 impulse",
        ],
        [
            "+-0.5 eq33",
            "+-0.5 vt+-0.05 eq43",
            "+-0.5 vt+-0.05 impulse",
        ],
        ["wall eq33", "wall vt0.1 eq43", "wall vt0.1 impulse"],
    ];
    let mut out = vec![];
    for (i, (_, v1, v2, wall)) in normals.into_iter().enumerate() {
        let v2 = if wall { [0.0, 0.0] } else { v2 };
        out.push(EtaReading {
            label: labels[i][0],
            v1: [v1[0], 0.0],
            v2: [v2[0], 0.0],
            wall,
            kind: EtaKind::Eq33,
        });
        for (j, kind) in [(1, EtaKind::Eq43), (2, EtaKind::Impulse)] {
            out.push(EtaReading {
                label: labels[i][j],
                v1,
                v2,
                wall,
                kind,
            });
        }
    }
    out
}

/// Diameter used for Table 1's η, m. η of two identical balls does not depend on it (δ₁/δ_max
/// and every energy ratio are scale-free), so the experiment's 20 mm is as good as any.
pub const TABLE1_DIAMETER: f64 = 0.02;

/// η of one Table 1 material under a reading.
pub fn reading_eta(m: &Material, r: &EtaReading) -> Result<f64> {
    let b = Body::ball(*m, TABLE1_DIAMETER, "ball1")?;
    let b2 = if r.wall { Body::RigidWall } else { b };
    let c = collide_with_mu(&b, &b2, r.v1, r.v2, m.mu)?;
    Ok(r.kind.of(&c))
}

/// A row of Table 1, computed beside printed.
#[derive(Debug, Clone, PartialEq)]
pub struct Table1Row {
    /// Preset name.
    pub material: String,
    /// ζ × 10³ computed by eq. 44 at v_n = 1, v_t = 0.1 m/s.
    pub zeta: f64,
    /// ζ × 10³ as printed.
    pub zeta_printed: f64,
    /// (computed − printed)/printed.
    pub zeta_rel_diff: f64,
    /// Computed ζ agrees with the printed digits (|Δ| < one unit of the last printed digit).
    pub zeta_agrees: bool,
    /// η computed under the chosen reading.
    pub eta: f64,
    /// η as printed.
    pub eta_printed: f64,
    /// (computed − printed)/printed.
    pub eta_rel_diff: f64,
    /// Computed η rounds to the printed value (|Δ| ≤ half a unit of the last digit).
    pub eta_agrees: bool,
}

/// Table 1 computed under reading `r`.
pub fn table1(r: &EtaReading) -> Result<Vec<Table1Row>> {
    let (vn, vt) = TABLE1_SPEEDS;
    TABLE1_PRINTED
        .iter()
        .map(|&(name, zs, es)| {
            let m = Material::preset(name)?;
            let zeta = damping_index(&m, vn, vt) * ZETA_TABLE_SCALE;
            let zeta_printed: f64 = zs.parse().unwrap_or(f64::NAN);
            let eta = reading_eta(&m, r)?;
            let eta_printed: f64 = es.parse().unwrap_or(f64::NAN);
            Ok(Table1Row {
                material: name.to_string(),
                zeta,
                zeta_printed,
                zeta_rel_diff: (zeta - zeta_printed) / zeta_printed,
                zeta_agrees: (zeta - zeta_printed).abs() < last_digit_unit(zs),
                eta,
                eta_printed,
                eta_rel_diff: (eta - eta_printed) / eta_printed,
                eta_agrees: (eta - eta_printed).abs() <= 0.5 * last_digit_unit(es) + 1e-12,
            })
        })
        .collect()
}

/// Relative tolerance of the looser agreement count used to rank readings.
pub const ETA_LOOSE_TOLERANCE: f64 = 0.05;

/// How well a reading reproduces Table 1's η.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReadingScore {
    /// Rows whose computed η rounds to the printed three decimals.
    pub exact: usize,
    /// Rows within [`ETA_LOOSE_TOLERANCE`] relative of the printed η.
    pub loose: usize,
    /// Median |relative difference| over the nine rows.
    pub median_rel: f64,
}

/// Score of a reading against the printed η column.
pub fn reading_score(r: &EtaReading) -> Result<ReadingScore> {
    let rows = table1(r)?;
    let exact = rows.iter().filter(|row| row.eta_agrees).count();
    let loose = rows
        .iter()
        .filter(|row| row.eta_rel_diff.abs() <= ETA_LOOSE_TOLERANCE)
        .count();
    let mut rel: Vec<f64> = rows.iter().map(|row| row.eta_rel_diff.abs()).collect();
    rel.sort_by(f64::total_cmp);
    Ok(ReadingScore {
        exact,
        loose,
        median_rel: rel[rel.len() / 2],
    })
}

/// The candidate reading that reproduces the most printed η: most rows to the printed digits,
/// then most rows within 5 %, then smallest median relative difference; the first candidate
/// wins exact ties.
pub fn best_reading() -> Result<(EtaReading, ReadingScore)> {
    let mut best: Option<(EtaReading, ReadingScore)> = None;
    for r in candidate_readings() {
        let s = reading_score(&r)?;
        let better = match &best {
            None => true,
            Some((_, b)) => {
                (s.exact, s.loose) > (b.exact, b.loose)
                    || ((s.exact, s.loose) == (b.exact, b.loose) && s.median_rel < b.median_rel)
            }
        };
        if better {
            best = Some((r, s));
        }
    }
    best.ok_or_else(|| crate::error::Error::Numerical("no Table 1 reading to score".into()))
}
