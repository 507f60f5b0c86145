//! A small layered layout of the derivation graph, drawn left to right: a claim sits one
//! column right of the furthest claim it uses, and each column is ordered to keep edges
//! short (two sweeps of barycentres, ties in file order). Deterministic, no dependency.

/// A node's place: its column, its centre, its size (pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Place {
    pub column: usize,
    pub x: f64,
    pub y: f64,
    pub width: f64,
    pub height: f64,
}

/// The whole drawing's size and every node's place.
#[derive(Clone, Debug)]
pub struct Layout {
    pub places: Vec<Place>,
    pub width: f64,
    pub height: f64,
}

/// Node height, vertical gap, horizontal gap between columns and margin, in pixels.
const HEIGHT: f64 = 22.0;
const GAP: f64 = 8.0;
const COLUMN_GAP: f64 = 48.0;
const MARGIN: f64 = 12.0;
/// Approximate width of a label character at the drawing's font size.
const CHAR: f64 = 7.2;

/// Lays out `labels.len()` nodes; `uses[k]` are the nodes node k uses (indices below
/// `labels.len()`, acyclic). A node's width fits its label.
pub fn layered(labels: &[String], uses: &[Vec<usize>]) -> Layout {
    let n = labels.len();
    // Column: longest path from a node that uses nothing (acyclic, so n passes settle).
    let mut column = vec![0usize; n];
    for _ in 0..n {
        let mut changed = false;
        for k in 0..n {
            let c = uses[k].iter().map(|&u| column[u] + 1).max().unwrap_or(0);
            if c != column[k] {
                column[k] = c;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let columns = column.iter().max().map_or(0, |m| m + 1);
    let mut order: Vec<Vec<usize>> = vec![Vec::new(); columns];
    for k in 0..n {
        order[column[k]].push(k);
    }
    let used_by: Vec<Vec<usize>> = (0..n)
        .map(|k| (0..n).filter(|&j| uses[j].contains(&k)).collect())
        .collect();
    // Barycentre sweeps: right by the nodes used, then left by the users.
    let mut rank = vec![0.0f64; n];
    let set_ranks = |order: &Vec<Vec<usize>>, rank: &mut Vec<f64>| {
        for col in order {
            for (i, &k) in col.iter().enumerate() {
                rank[k] = i as f64;
            }
        }
    };
    set_ranks(&order, &mut rank);
    for sweep in 0..4 {
        let forward = sweep % 2 == 0;
        let cols: Vec<usize> = if forward {
            (1..columns).collect()
        } else {
            (0..columns.saturating_sub(1)).rev().collect()
        };
        for c in cols {
            let mut keyed: Vec<(f64, usize, usize)> = order[c]
                .iter()
                .enumerate()
                .map(|(i, &k)| {
                    let near = if forward { &uses[k] } else { &used_by[k] };
                    let key = if near.is_empty() {
                        rank[k]
                    } else {
                        near.iter().map(|&j| rank[j]).sum::<f64>() / near.len() as f64
                    };
                    (key, i, k)
                })
                .collect();
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            order[c] = keyed.into_iter().map(|(_, _, k)| k).collect();
            for (i, &k) in order[c].iter().enumerate() {
                rank[k] = i as f64;
            }
        }
    }
    let widths: Vec<f64> = labels
        .iter()
        .map(|l| l.chars().count() as f64 * CHAR + 16.0)
        .collect();
    let column_width: Vec<f64> = order
        .iter()
        .map(|col| col.iter().map(|&k| widths[k]).fold(0.0, f64::max))
        .collect();
    let tallest = order.iter().map(Vec::len).max().unwrap_or(0) as f64;
    let height = 2.0 * MARGIN + tallest * (HEIGHT + GAP) - GAP.min(tallest * GAP);
    let mut places = vec![
        Place {
            column: 0,
            x: 0.0,
            y: 0.0,
            width: 0.0,
            height: HEIGHT,
        };
        n
    ];
    let mut left = MARGIN;
    for (c, col) in order.iter().enumerate() {
        // Each column is centred vertically.
        let used = col.len() as f64 * (HEIGHT + GAP) - GAP;
        let top = (height - used) / 2.0;
        for (i, &k) in col.iter().enumerate() {
            places[k] = Place {
                column: c,
                x: left + column_width[c] / 2.0,
                y: top + i as f64 * (HEIGHT + GAP) + HEIGHT / 2.0,
                width: widths[k],
                height: HEIGHT,
            };
        }
        left += column_width[c] + COLUMN_GAP;
    }
    Layout {
        places,
        width: left - COLUMN_GAP + MARGIN,
        height: height.max(HEIGHT + 2.0 * MARGIN),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_claim_sits_right_of_every_claim_it_uses_and_nodes_do_not_overlap() {
        let labels: Vec<String> = ["a", "b", "c", "d"].map(String::from).to_vec();
        // d uses b and c; c uses a; b uses a.
        let uses = vec![vec![], vec![0], vec![0], vec![1, 2]];
        let l = layered(&labels, &uses);
        for (k, us) in uses.iter().enumerate() {
            for &u in us {
                assert!(
                    l.places[u].x + l.places[u].width / 2.0
                        < l.places[k].x - l.places[k].width / 2.0
                );
            }
        }
        let (b, c) = (l.places[1], l.places[2]);
        assert_eq!(b.column, c.column);
        assert!((b.y - c.y).abs() >= HEIGHT);
        for p in &l.places {
            assert!(p.x - p.width / 2.0 >= 0.0 && p.x + p.width / 2.0 <= l.width);
            assert!(p.y - p.height / 2.0 >= 0.0 && p.y + p.height / 2.0 <= l.height);
        }
    }
}
