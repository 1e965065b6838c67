//! The list of laws: each law file exports a spec; the registry finds them by name and builds
//! them for a pair.

use super::pair::ContactPair;
use super::params::{ParamSpec, Params};
use super::validity::Validity;
use super::{NormalLaw, TangentialLaw};
use crate::error::{Error, Result};

/// Description and constructor of a contact law: `L` the law's trait object, `V` what the
/// spec says of where the law holds ([`Validity`] for a normal law, nothing for a tangential
/// one).
pub struct LawSpec<L: ?Sized, V> {
    /// Name used by `--law` or `--tangential`, e.g. `thornton`, `mindlin`.
    pub name: &'static str,
    /// One-line description.
    pub title: &'static str,
    /// Original source (authors, year, journal).
    pub source: &'static str,
    /// DEM codes that ship the law (as documented by them), or `none`.
    pub dem_codes: &'static str,
    /// Where the law holds (range, material class, source) and its check.
    pub validity: V,
    /// Parameters with units, ranges and defaults.
    pub params: &'static [ParamSpec],
    /// Builds the law for a pair from resolved parameters.
    pub build: fn(&ContactPair, &Params) -> Box<L>,
}

impl<L: ?Sized, V: Copy> Clone for LawSpec<L, V> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<L: ?Sized, V: Copy> Copy for LawSpec<L, V> {}

impl<L: ?Sized, V> LawSpec<L, V> {
    /// Builds the law for `pair` with parameter `overrides` (key, value) on its defaults.
    pub fn build_with(
        &self,
        overrides: &[(String, f64)],
        pair: &ContactPair,
    ) -> Result<(Box<L>, Params)> {
        let params = Params::resolve(self.name, self.params, overrides, pair)?;
        Ok(((self.build)(pair, &params), params))
    }
}

/// Description and constructor of a normal law.
pub type NormalSpec = LawSpec<dyn NormalLaw, Validity>;

/// Description and constructor of a tangential law (no validity range).
pub type TangentialSpec = LawSpec<dyn TangentialLaw, ()>;

/// The laws known to a run: the built-in ones plus any a program adds.
#[derive(Clone)]
pub struct Registry {
    /// Normal laws, in listing order.
    pub normal: Vec<NormalSpec>,
    /// Tangential laws, in listing order.
    pub tangential: Vec<TangentialSpec>,
}

impl Registry {
    /// Every law of the crate.
    pub fn builtin() -> Self {
        use super::*;
        Registry {
            normal: vec![
                hertz::SPEC,
                linear_dashpot::SPEC,
                hertz_damped::SPEC,
                hunt_crossley::SPEC,
                lankarani_nikravesh::SPEC,
                kuwabara_kono::SPEC,
                walton_braun::SPEC,
                thornton::SPEC,
                jackson_green::SPEC,
                tabor_hardening::SPEC,
                li_yang_shi::SPEC,
            ],
            tangential: vec![
                coulomb::SPEC,
                mindlin::SPEC,
                mindlin_coulomb::SPEC,
                thornton_yin::SPEC,
            ],
        }
    }

    /// Adds (or replaces, by name) a normal law.
    pub fn add_normal(&mut self, spec: NormalSpec) {
        self.normal.retain(|s| s.name != spec.name);
        self.normal.push(spec);
    }

    /// The normal law called `name`; the error lists the known names.
    pub fn normal(&self, name: &str) -> Result<&NormalSpec> {
        by_name(&self.normal, name, "--law", |s| s.name)
    }

    /// The tangential law called `name`; the error lists the known names.
    pub fn tangential(&self, name: &str) -> Result<&TangentialSpec> {
        by_name(&self.tangential, name, "--tangential", |s| s.name)
    }
}

/// The spec of `specs` whose `name_of` is `name`; the error names the option `flag` and lists
/// the known names.
fn by_name<'a, S>(
    specs: &'a [S],
    name: &str,
    flag: &str,
    name_of: impl Fn(&S) -> &'static str,
) -> Result<&'a S> {
    specs.iter().find(|s| name_of(s) == name).ok_or_else(|| {
        let names: Vec<&str> = specs.iter().map(name_of).collect();
        Error::invalid(flag, name, format!("one of {}", names.join(", ")))
    })
}
