//! The density budget: at most `max_per_cell` rectangles in every cube of `cell_m` metres
//! (a grid aligned with the world origin), chosen by what each buys against what it costs.
//!
//! Every shape costs the projection pass about the same per frame (it is one more shape
//! every pixel of its tiles tests), so the currency is square metres per shape:
//! - a region's first rectangle buys the reflective area it covers;
//! - each split of a non-convex region ([`crate::split::SplitStep`]) buys the rectangle area
//!   it saves (pixels tested for nothing, reflections written where nothing reflects),
//!   divided by the shapes it adds, and never more than what the steps before it bought.
//!
//! In each cube (the one holding the centre of the region's first rectangle), offers are
//! taken best value first while they fit; a split is taken only after its region and the
//! splits before it. What is left out is counted ([`BudgetReport`]) for the summary. The
//! budget depends only on the shapes in the same cube, so a room gives the same set
//! however large the level around it is (for copies moved by whole cubes).

use glam::DVec3;

use crate::int_hash::{CellMap, cell_of};
use crate::split::SplitStep;

/// The budget's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BudgetRule {
    /// Cube edge, metres.
    pub cell_m: f64,
    /// Most rectangles per cube.
    pub max_per_cell: usize,
}

/// One region's offer: where it is, what its first rectangle buys and its splits.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionOffer {
    /// World position of the first rectangle's centre.
    pub center: DVec3,
    /// Reflective area, m².
    pub area: f64,
    /// Its splits, in order.
    pub steps: Vec<SplitStep>,
}

/// What the budget keeps of one region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BudgetChoice {
    /// The region gets rectangles at all.
    pub keep: bool,
    /// How many of its splits it keeps (a prefix).
    pub steps: usize,
}

/// What the budget left out.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BudgetReport {
    /// Cubes that reached the cap.
    pub full_cells: usize,
    /// Regions dropped, and their reflective area, m².
    pub regions_dropped: usize,
    /// Their reflective area, m².
    pub area_dropped: f64,
    /// Splits not made, and the rectangle area they would have saved, m².
    pub splits_refused: usize,
    /// The rectangle area those splits would have saved, m².
    pub saving_refused: f64,
}

/// The choice for every offer (same order) and what was left out.
pub fn apply_budget(offers: &[RegionOffer], rule: &BudgetRule) -> (Vec<BudgetChoice>, BudgetReport) {
    let mut choices = vec![BudgetChoice { keep: false, steps: 0 }; offers.len()];
    let mut report = BudgetReport::default();
    // Offers grouped by cube, in a deterministic order of cubes.
    let mut cells: CellMap<Vec<u32>> = CellMap::default();
    for (i, o) in offers.iter().enumerate() {
        let c = o.center;
        cells
            .entry((cell_of(c.x, rule.cell_m), cell_of(c.y, rule.cell_m), cell_of(c.z, rule.cell_m)))
            .or_default()
            .push(i as u32);
    }
    let mut keys: Vec<(i64, i64, i64)> = cells.keys().copied().collect();
    keys.sort_unstable();
    for key in keys {
        // (value per shape in mm², place in the cube in mm, region, step: 0 = the first
        // rectangle, k = the k-th split). Values and places are rounded so that copies of a
        // room a whole number of cubes apart break ties alike.
        let corner = DVec3::new(key.0 as f64, key.1 as f64, key.2 as f64) * rule.cell_m;
        let mut items: Vec<(i64, [i64; 3], u32, usize)> = Vec::new();
        for &i in &cells[&key] {
            let o = &offers[i as usize];
            let place = ((o.center - corner) * 1e3).round().to_array().map(|x| x as i64);
            let mm2 = |v: f64| (v * 1e6).round() as i64;
            items.push((mm2(o.area), place, i, 0));
            let mut value = o.area;
            for (k, st) in o.steps.iter().enumerate() {
                value = value.min(st.area_saved / st.extra_shapes.max(1) as f64);
                items.push((mm2(value), place, i, k + 1));
            }
        }
        // Best value first; for equal values by place, then the earlier step (a step never
        // comes before the one it depends on).
        items.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)).then(a.3.cmp(&b.3)));
        let mut used = 0usize;
        for &(_, _, i, k) in &items {
            let o = &offers[i as usize];
            let choice = &mut choices[i as usize];
            let cost = if k == 0 { 1 } else { o.steps[k - 1].extra_shapes };
            let ready = if k == 0 { true } else { choice.keep && choice.steps == k - 1 };
            if ready && used + cost <= rule.max_per_cell {
                used += cost;
                if k == 0 {
                    choice.keep = true;
                } else {
                    choice.steps = k;
                }
            }
        }
        if used >= rule.max_per_cell {
            report.full_cells += 1;
        }
        for &i in &cells[&key] {
            let (o, c) = (&offers[i as usize], choices[i as usize]);
            if !c.keep {
                report.regions_dropped += 1;
                report.area_dropped += o.area;
            }
            for st in &o.steps[c.steps.min(o.steps.len())..] {
                if c.keep {
                    report.splits_refused += 1;
                    report.saving_refused += st.area_saved;
                }
            }
        }
    }
    (choices, report)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn offer(x: f64, area: f64, steps: &[(usize, f64)]) -> RegionOffer {
        RegionOffer {
            center: DVec3::new(x, 1.0, 1.0),
            area,
            steps: steps
                .iter()
                .map(|&(extra_shapes, area_saved)| SplitStep { extra_shapes, area_saved })
                .collect(),
        }
    }

    #[test]
    fn keeps_what_pays_most_per_cube() {
        let rule = BudgetRule { cell_m: 10.0, max_per_cell: 4 };
        let offers = vec![
            offer(1.0, 20.0, &[(1, 8.0), (2, 4.0)]), // a floor with two splits
            offer(2.0, 0.5, &[]),                    // a small shelf
            offer(3.0, 3.0, &[]),                    // a wall
            offer(4.0, 0.1, &[]),                    // a tiny tile
            offer(15.0, 0.1, &[]),                   // a tiny tile in the next cube
        ];
        let (choices, report) = apply_budget(&offers, &rule);
        // Cube 0: floor 20, wall 3, split 8 (after the floor), shelf 0.5 = 4 shapes; the
        // second split (2 shapes, 2 m² each) and the tile do not fit.
        assert_eq!(choices[0], BudgetChoice { keep: true, steps: 1 });
        assert!(choices[1].keep && choices[2].keep && !choices[3].keep && choices[4].keep);
        assert_eq!(report.full_cells, 1);
        assert_eq!((report.regions_dropped, report.splits_refused), (1, 1));
        assert!((report.area_dropped - 0.1).abs() < 1e-12 && (report.saving_refused - 4.0).abs() < 1e-12);
        // A larger budget keeps everything; a copy a whole cube away chooses alike.
        let (all, none) = apply_budget(&offers, &BudgetRule { cell_m: 10.0, max_per_cell: 100 });
        assert!(all.iter().all(|c| c.keep) && all[0].steps == 2 && none == BudgetReport::default());
        let moved: Vec<RegionOffer> = offers
            .iter()
            .map(|o| RegionOffer { center: o.center + DVec3::X * 1000.0, ..o.clone() })
            .collect();
        assert_eq!(apply_budget(&moved, &rule).0, choices);
    }
}
