//! The order of the reflector list: which column it is sorted by, and the sorted rows.

use std::cmp::Ordering;

use ppr_format::{Reflector, ReflectorSet};

/// A column of the reflector list.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SortColumn {
    /// File order.
    #[default]
    Index,
    /// Name, alphabetical.
    Name,
    /// Kind.
    Kind,
    /// Rectangle area.
    Area,
    /// Coverage (fit quality).
    Coverage,
    /// Number of occluders.
    Occluders,
}

impl SortColumn {
    /// Every column, in display order.
    pub const ALL: [SortColumn; 6] =
        [Self::Index, Self::Name, Self::Kind, Self::Area, Self::Coverage, Self::Occluders];

    /// Header text.
    pub fn title(self) -> &'static str {
        match self {
            Self::Index => "#",
            Self::Name => "Name",
            Self::Kind => "Kind",
            Self::Area => "Area m²",
            Self::Coverage => "Coverage",
            Self::Occluders => "Occluders",
        }
    }
}

/// How the list is sorted.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ReflectorSort {
    /// The column.
    pub column: SortColumn,
    /// Largest first.
    pub descending: bool,
}

impl ReflectorSort {
    /// Clicking a header: sort by it, or flip the order when it is already the column.
    pub fn click(&mut self, column: SortColumn) {
        if self.column == column {
            self.descending = !self.descending;
        } else {
            self.column = column;
            self.descending = false;
        }
    }

    fn compare(&self, a: (usize, &Reflector), b: (usize, &Reflector)) -> Ordering {
        let by = match self.column {
            SortColumn::Index => a.0.cmp(&b.0),
            SortColumn::Name => a.1.name.to_lowercase().cmp(&b.1.name.to_lowercase()),
            SortColumn::Kind => (a.1.kind as u8).cmp(&(b.1.kind as u8)),
            SortColumn::Area => a.1.area().total_cmp(&b.1.area()),
            SortColumn::Coverage => a.1.coverage.total_cmp(&b.1.coverage),
            SortColumn::Occluders => a.1.occluders.len().cmp(&b.1.occluders.len()),
        };
        let by = if self.descending { by.reverse() } else { by };
        by.then(a.0.cmp(&b.0))
    }

    /// Indices into `set.reflectors` in display order (ties keep file order).
    pub fn rows(&self, set: &ReflectorSet) -> Vec<usize> {
        let mut rows: Vec<usize> = (0..set.reflectors.len()).collect();
        rows.sort_by(|&a, &b| self.compare((a, &set.reflectors[a]), (b, &set.reflectors[b])));
        rows
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use ppr_format::ReflectorKind;

    use super::*;

    #[test]
    fn sorts_by_each_column_and_flips() {
        let mut set = ReflectorSet::new("x");
        for (i, (name, half, cov)) in
            [("b", 1.0, 0.5), ("A", 3.0, 0.9), ("c", 2.0, 0.1)].into_iter().enumerate()
        {
            let mut r = Reflector::new(
                i as u32,
                name,
                ReflectorKind::Opaque,
                DVec3::ZERO,
                DVec3::Y,
                DVec3::X,
                DVec2::splat(half),
            );
            r.coverage = cov;
            set.reflectors.push(r);
        }
        let mut sort = ReflectorSort::default();
        assert_eq!(sort.rows(&set), vec![0, 1, 2]);
        sort.click(SortColumn::Name);
        assert_eq!(sort.rows(&set), vec![1, 0, 2]);
        sort.click(SortColumn::Name);
        assert_eq!(sort.rows(&set), vec![2, 0, 1]);
        sort.click(SortColumn::Area);
        assert_eq!(sort.rows(&set), vec![0, 2, 1]);
        sort.click(SortColumn::Coverage);
        assert_eq!(sort.rows(&set), vec![2, 0, 1]);
    }
}
