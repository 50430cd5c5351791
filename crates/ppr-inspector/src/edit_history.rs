//! Undo and redo: a stack of applied changes, each holding the document before and after.
//!
//! Changes made by one continuous gesture (dragging a handle) share a gesture number and
//! are kept as one step.

use crate::document::Document;

/// One undoable change.
#[derive(Clone, Debug)]
pub struct HistoryEntry {
    /// What was done (`rename "floor" to "marble"`).
    pub label: String,
    /// The document before.
    pub before: Document,
    /// The document after.
    pub after: Document,
    /// Changes with the same gesture number are merged into one step.
    pub gesture: Option<u64>,
}

/// The undo and redo stacks.
#[derive(Clone, Debug, Default)]
pub struct EditHistory {
    undo: Vec<HistoryEntry>,
    redo: Vec<HistoryEntry>,
}

/// Most steps kept; the oldest are dropped beyond it.
pub const HISTORY_LIMIT: usize = 500;

impl EditHistory {
    /// Records a change; clears the redo stack. A change of the gesture of the last step
    /// extends that step instead of adding one.
    pub fn record(&mut self, entry: HistoryEntry) {
        self.redo.clear();
        if let (Some(g), Some(last)) = (entry.gesture, self.undo.last_mut())
            && last.gesture == Some(g)
        {
            last.after = entry.after;
            return;
        }
        self.undo.push(entry);
        if self.undo.len() > HISTORY_LIMIT {
            self.undo.remove(0);
        }
    }

    /// Steps back: the document to restore, if there is a step.
    pub fn undo(&mut self) -> Option<(String, Document)> {
        let entry = self.undo.pop()?;
        let restored = (entry.label.clone(), entry.before.clone());
        self.redo.push(entry);
        Some(restored)
    }

    /// Steps forward again: the document to restore, if a step was undone.
    pub fn redo(&mut self) -> Option<(String, Document)> {
        let entry = self.redo.pop()?;
        let restored = (entry.label.clone(), entry.after.clone());
        self.undo.push(entry);
        Some(restored)
    }

    /// Label of the step [`Self::undo`] would undo.
    pub fn undo_label(&self) -> Option<&str> {
        self.undo.last().map(|e| e.label.as_str())
    }

    /// Label of the step [`Self::redo`] would redo.
    pub fn redo_label(&self) -> Option<&str> {
        self.redo.last().map(|e| e.label.as_str())
    }

    /// Number of steps that can be undone.
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// Forgets everything (a new level or set was opened).
    pub fn clear(&mut self) {
        self.undo.clear();
        self.redo.clear();
    }
}
