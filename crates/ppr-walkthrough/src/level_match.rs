//! Whether a reflector set belongs to the level the walkthrough shows: its `source.hash`
//! against the level file's (`ReflectorSet::check_source`), refused unless the user accepts
//! the mismatch (`--accept-level-mismatch`, as in `ppr-render`).

use std::path::PathBuf;

use ppr_format::ReflectorSet;

/// The level a set must have been extracted from, and whether a mismatch is accepted.
#[derive(Clone, Debug)]
pub struct LevelMatch {
    /// The set file (named in the messages).
    pub set_path: PathBuf,
    /// The level file.
    pub level_path: PathBuf,
    /// `blake3:<hex>` of the level file's bytes (empty: not checked).
    pub level_hash: String,
    /// Use a mismatched set anyway, with a warning.
    pub accept_mismatch: bool,
}

/// What [`LevelMatch::check`] decided about a set.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MatchOutcome {
    /// The set was extracted from this level (or cannot be checked).
    Matches,
    /// It was not, and the user accepted that: the warning to show.
    Accepted(String),
    /// It was not: the message that refuses it (names both files and the flag).
    Refused(String),
}

impl LevelMatch {
    /// Checks `set` against the level.
    pub fn check(&self, set: &ReflectorSet) -> MatchOutcome {
        match set.check_source(&self.set_path, &self.level_path, &self.level_hash) {
            Ok(()) => MatchOutcome::Matches,
            Err(mismatch) if self.accept_mismatch => MatchOutcome::Accepted(format!("{mismatch} (accepted)")),
            Err(mismatch) => MatchOutcome::Refused(format!(
                "{mismatch}; to use it anyway, accept the mismatch (ppr-walkthrough --accept-level-mismatch)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hot_reload::{ReflectorSetState, ReloadEvent, SetStatus};

    fn set_with_hash(hash: &str) -> Box<ppr_format::ValidatedSet> {
        let mut set = ReflectorSet::new("room.glb");
        set.source.hash = hash.to_owned();
        Box::new(ppr_format::ValidatedSet::new(set).expect("an empty set is valid"))
    }

    fn state(accept_mismatch: bool) -> ReflectorSetState {
        ReflectorSetState::new("starting").with_level_match(LevelMatch {
            set_path: "room.ppr.json".into(),
            level_path: "room.glb".into(),
            level_hash: "blake3:aa".into(),
            accept_mismatch,
        })
    }

    #[test]
    fn a_set_of_another_level_is_refused_and_the_last_good_one_kept() {
        let mut sets = state(false);
        assert!(sets.apply(ReloadEvent::Loaded(set_with_hash("blake3:aa"))).is_some());
        assert!(sets.apply(ReloadEvent::Loaded(set_with_hash("blake3:bb"))).is_none());
        let SetStatus::Refused { message, keeping } = sets.status() else { panic!("{:?}", sets.status()) };
        assert_eq!(*keeping, Some(0));
        for needle in ["room.ppr.json", "room.glb", "--accept-level-mismatch"] {
            assert!(message.contains(needle), "{message}");
        }
        assert_eq!(sets.take_warning(), None);
    }

    #[test]
    fn an_accepted_mismatch_is_used_with_a_warning() {
        let mut sets = state(true);
        assert!(sets.apply(ReloadEvent::Loaded(set_with_hash("blake3:bb"))).is_some());
        assert!(matches!(sets.status(), SetStatus::Current { .. }));
        assert!(sets.take_warning().is_some_and(|w| w.contains("accepted")));
        assert_eq!(sets.take_warning(), None, "the warning is given once");
        assert!(sets.apply(ReloadEvent::Loaded(set_with_hash(""))).is_some(), "a set without a hash passes");
    }
}
