//! The message log: what the inspector tells the user (errors never panic, they land here).

use std::time::Instant;

/// How serious a message is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// Something happened.
    Info,
    /// Something was skipped or dropped.
    Warning,
    /// Something failed.
    Error,
}

/// One message.
#[derive(Clone, Debug)]
pub struct Message {
    /// How serious.
    pub severity: Severity,
    /// The text (names files and fields where it can).
    pub text: String,
    /// When it was logged.
    pub at: Instant,
}

/// Every message of the session, oldest first.
#[derive(Clone, Debug, Default)]
pub struct MessageLog {
    entries: Vec<Message>,
}

impl MessageLog {
    /// Logs a message.
    pub fn push(&mut self, severity: Severity, text: impl Into<String>) {
        self.entries.push(Message { severity, text: text.into(), at: Instant::now() });
    }

    /// Logs an information.
    pub fn info(&mut self, text: impl Into<String>) {
        self.push(Severity::Info, text);
    }

    /// Logs a warning.
    pub fn warning(&mut self, text: impl Into<String>) {
        self.push(Severity::Warning, text);
    }

    /// Logs an error.
    pub fn error(&mut self, text: impl Into<String>) {
        self.push(Severity::Error, text);
    }

    /// Every message, oldest first.
    pub fn entries(&self) -> &[Message] {
        &self.entries
    }

    /// The newest message.
    pub fn latest(&self) -> Option<&Message> {
        self.entries.last()
    }

    /// The newest error, if any.
    pub fn latest_error(&self) -> Option<&Message> {
        self.entries.iter().rev().find(|m| m.severity == Severity::Error)
    }

    /// Forgets every message.
    pub fn clear(&mut self) {
        self.entries.clear();
    }
}
