//! `ValidatedSet`: a reflector set known to hold every invariant of the format.

use std::ops::Deref;

use crate::{FormatError, ReflectorSet};

/// A [`ReflectorSet`] that passed [`ReflectorSet::validate`] and cannot be changed since:
/// what a renderer takes, so that it never sees a broken set (an occluder index out of
/// range, a parallel group that mixes orientations, a non-unit normal).
///
/// Read it through `Deref`; to edit, take the set out with [`Self::into_inner`], change
/// it and validate it again.
///
/// ```
/// use ppr_format::{Reflector, ReflectorKind, ReflectorSet, ValidatedSet};
/// use glam::{DVec2, DVec3};
///
/// let mut set = ReflectorSet::new("level.glb");
/// set.reflectors.push(Reflector::new(
///     0, "floor", ReflectorKind::Opaque, DVec3::ZERO, DVec3::Y, DVec3::X, DVec2::ONE,
/// ));
/// let set = ValidatedSet::new(set).unwrap();
/// assert_eq!(set.reflectors.len(), 1);
///
/// let mut broken = set.into_inner();
/// broken.reflectors[0].occluders = vec![5]; // no reflector 5
/// assert!(ValidatedSet::new(broken).is_err());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ValidatedSet(ReflectorSet);

impl ValidatedSet {
    /// Checks every invariant of the format.
    ///
    /// # Errors
    /// The [`FormatError`] of [`ReflectorSet::validate`], naming the first reflector and
    /// field that break one.
    pub fn new(set: ReflectorSet) -> Result<Self, FormatError> {
        set.validate()?;
        Ok(Self(set))
    }

    /// Parses and validates a set from JSON text ([`ReflectorSet::from_json_str`]).
    ///
    /// # Errors
    /// As [`ReflectorSet::from_json_str`].
    pub fn from_json_str(text: &str) -> Result<Self, FormatError> {
        ReflectorSet::from_json_str(text).map(Self)
    }

    /// Reads, parses and validates the set at `path` ([`ReflectorSet::load`]).
    ///
    /// # Errors
    /// As [`ReflectorSet::load`].
    pub fn load(path: impl AsRef<std::path::Path>) -> Result<Self, FormatError> {
        ReflectorSet::load(path).map(Self)
    }

    /// The set, to edit (validate it again to render it).
    pub fn into_inner(self) -> ReflectorSet {
        self.0
    }
}

impl Deref for ValidatedSet {
    type Target = ReflectorSet;

    fn deref(&self) -> &ReflectorSet {
        &self.0
    }
}

impl AsRef<ReflectorSet> for ValidatedSet {
    fn as_ref(&self) -> &ReflectorSet {
        &self.0
    }
}

impl TryFrom<ReflectorSet> for ValidatedSet {
    type Error = FormatError;

    fn try_from(set: ReflectorSet) -> Result<Self, FormatError> {
        Self::new(set)
    }
}
