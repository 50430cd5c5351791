//! What the driver reports of a compiled pipeline: its executables (one per shader stage or
//! compiled variant) and each one's named statistics.

use std::fmt;

/// A statistic's value, in the format the driver gave it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StatValue {
    Bool(bool),
    Int(i64),
    Uint(u64),
    Float(f64),
}

impl fmt::Display for StatValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Bool(b) => write!(f, "{b}"),
            Self::Int(v) => write!(f, "{v}"),
            Self::Uint(v) => write!(f, "{v}"),
            Self::Float(v) => write!(f, "{v}"),
        }
    }
}

/// One named statistic of an executable.
#[derive(Clone, Debug, PartialEq)]
pub struct Statistic {
    /// The driver's name (`Register Count`, `Local Memory Size`, …).
    pub name: String,
    /// The driver's description.
    pub description: String,
    pub value: StatValue,
}

/// One executable of a pipeline and its statistics.
#[derive(Clone, Debug, PartialEq)]
pub struct ExecutableStats {
    /// The driver's name of the executable (a stage or a compiled variant).
    pub name: String,
    /// The driver's description.
    pub description: String,
    /// The subgroup size the executable runs with (0: the driver does not say).
    pub subgroup_size: u32,
    pub statistics: Vec<Statistic>,
}

/// How useful a statistic is for occupancy, by its name (lower first): registers, shared
/// memory, local memory and spills, then instruction counts; everything else after.
pub fn usefulness(name: &str) -> u32 {
    let n = name.to_ascii_lowercase();
    // Spills first: "Spilled SGPRs" is a spill, not a register count.
    let ranks: [(&[&str], u32); 6] = [
        (&["spill", "fill"], 3),
        (&["register", "vgpr", "sgpr", "gpr"], 0),
        (&["shared", "workgroup", "lds"], 1),
        (&["local memory", "scratch", "stack", "private"], 2),
        (&["instruction", "inst", "binary size", "code size"], 4),
        (&["occupancy", "wave", "warp", "thread"], 5),
    ];
    ranks.iter().find(|(words, _)| words.iter().any(|w| n.contains(w))).map_or(6, |&(_, rank)| rank)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registers_come_before_shared_memory_before_spills_before_instructions() {
        let mut names = ["Instruction Count", "Foo", "Spill Count", "Shared Memory Size", "Register Count"];
        names.sort_by_key(|n| usefulness(n));
        assert_eq!(
            names,
            ["Register Count", "Shared Memory Size", "Spill Count", "Instruction Count", "Foo"]
        );
        assert_eq!(StatValue::Bool(true).to_string(), "true");
        assert_eq!(StatValue::Uint(42).to_string(), "42");
    }
}
