//! A small layered layout of the derivation graph, drawn left to right (Sugiyama's
//! scheme): a claim sits one column right of the furthest claim it uses, a claim that
//! uses nothing sits just left of its nearest user, an edge that spans several columns
//! passes each column in a slot of its own (so it never runs through a node), and each
//! column is ordered to keep edges short (sweeps of barycentres, ties in input order).
//! Deterministic, no dependency.

/// A node's place: its column, its centre, its size (pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Place {
    pub column: usize,
    pub x: f64,
    pub y: f64,
    pub width: f64,
    pub height: f64,
}

/// The way of one edge: from the right side of the node used to the left side of its
/// user. `points` has an even length: `points[2i] → points[2i+1]` crosses the gap
/// between two columns (draw it as a curve), `points[2i+1] → points[2i+2]` crosses a
/// column in the edge's own slot (a horizontal line).
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    pub from: usize,
    pub to: usize,
    pub points: Vec<(f64, f64)>,
}

/// The whole drawing's size, every node's place and every edge's way, in the order of
/// `uses` (node by node, each node's uses in order).
#[derive(Clone, Debug)]
pub struct Layout {
    pub places: Vec<Place>,
    pub routes: Vec<Route>,
    pub width: f64,
    pub height: f64,
}

/// Node height (one line of label), the height of each further line, the height of an edge's slot, the vertical gap, the horizontal gap
/// between columns and the margin, in pixels.
const HEIGHT: f64 = 22.0;
const LINE: f64 = 14.0;
const SLOT: f64 = 4.0;
const GAP: f64 = 6.0;
const COLUMN_GAP: f64 = 40.0;
const MARGIN: f64 = 12.0;
/// Approximate width of a label character at the drawing's font size.
const CHAR: f64 = 7.2;
/// At most this many slots in one drawing.
const MAX_SLOTS: usize = 20_000;
/// Ordering sweeps (each alternates direction).
const SWEEPS: usize = 8;

/// Lays out `labels.len()` nodes; `uses[k]` are the nodes node k uses (indices below
/// `labels.len()`, acyclic). A node's box fits its label, whose lines are separated by
/// `\n`.
pub fn layered(labels: &[String], uses: &[Vec<usize>]) -> Layout {
    let n = labels.len();
    let used_by = users(uses);
    let column = columns(uses, &used_by);
    let columns = column.iter().max().map_or(0, |m| m + 1);
    // The drawing's vertices: the nodes, then one slot per column an edge crosses.
    let mut vertex_column = column.clone();
    let mut left: Vec<Vec<usize>> = uses.to_vec();
    let mut chains: Vec<(usize, usize, Vec<usize>)> = Vec::new();
    for k in 0..n {
        for (i, &u) in uses[k].iter().enumerate() {
            let mut slots = Vec::new();
            let mut previous = u;
            // Past the budget a long edge is drawn straight across, so that a crafted
            // graph cannot make the page grow with the square of its size.
            let span = column[k] - column[u] - 1;
            let crossed = if vertex_column.len() - n + span <= MAX_SLOTS {
                column[u] + 1..column[k]
            } else {
                0..0
            };
            for c in crossed {
                let s = vertex_column.len();
                vertex_column.push(c);
                left.push(vec![previous]);
                slots.push(s);
                previous = s;
            }
            left[k][i] = previous;
            chains.push((u, k, slots));
        }
    }
    let vertices = vertex_column.len();
    let mut right: Vec<Vec<usize>> = vec![Vec::new(); vertices];
    for (v, ls) in left.iter().enumerate() {
        for &u in ls {
            right[u].push(v);
        }
    }
    let order = ordered(&vertex_column, columns, &left, &right);
    let heights: Vec<f64> = labels
        .iter()
        .map(|l| HEIGHT + LINE * (l.lines().count().max(1) - 1) as f64)
        .collect();
    let size = |v: usize| if v < n { heights[v] } else { SLOT };
    let widths: Vec<f64> = labels
        .iter()
        .map(|l| l.lines().map(|t| t.chars().count()).max().unwrap_or(0) as f64 * CHAR + 16.0)
        .collect();
    let column_width: Vec<f64> = order
        .iter()
        .map(|col| {
            col.iter()
                .filter(|&&v| v < n)
                .map(|&v| widths[v])
                .fold(COLUMN_GAP / 2.0, f64::max)
        })
        .collect();
    let extent = |col: &Vec<usize>| {
        col.iter().map(|&v| size(v) + GAP).sum::<f64>() - if col.is_empty() { 0.0 } else { GAP }
    };
    let tallest = order.iter().map(extent).fold(0.0, f64::max);
    let height = (2.0 * MARGIN + tallest).max(HEIGHT + 2.0 * MARGIN);
    let mut centre = vec![(0.0, 0.0); vertices];
    let mut x = MARGIN;
    for (c, col) in order.iter().enumerate() {
        // Each column is centred vertically.
        let mut y = (height - extent(col)) / 2.0;
        for &v in col {
            centre[v] = (x + column_width[c] / 2.0, y + size(v) / 2.0);
            y += size(v) + GAP;
        }
        x += column_width[c] + COLUMN_GAP;
    }
    let places: Vec<Place> = (0..n)
        .map(|k| Place {
            column: column[k],
            x: centre[k].0,
            y: centre[k].1,
            width: widths[k],
            height: heights[k],
        })
        .collect();
    let routes = chains
        .into_iter()
        .map(|(u, k, slots)| {
            let (a, b) = (places[u], places[k]);
            let mut points = vec![(a.x + a.width / 2.0, a.y)];
            for s in slots {
                let (cx, cy) = centre[s];
                let half = column_width[vertex_column[s]] / 2.0;
                points.push((cx - half, cy));
                points.push((cx + half, cy));
            }
            points.push((b.x - b.width / 2.0, b.y));
            Route {
                from: u,
                to: k,
                points,
            }
        })
        .collect();
    Layout {
        places,
        routes,
        width: x - COLUMN_GAP + MARGIN,
        height,
    }
}

/// The nodes that use each node (`uses` read backwards), in order, each once.
pub fn users(uses: &[Vec<usize>]) -> Vec<Vec<usize>> {
    let mut used_by: Vec<Vec<usize>> = vec![Vec::new(); uses.len()];
    for (j, us) in uses.iter().enumerate() {
        for &k in us {
            if used_by[k].last() != Some(&j) {
                used_by[k].push(j);
            }
        }
    }
    used_by
}

/// Each node's column: one right of the furthest node it uses; a node that uses nothing
/// but is used sits one left of its nearest user, so that its edges stay short.
fn columns(uses: &[Vec<usize>], used_by: &[Vec<usize>]) -> Vec<usize> {
    let n = uses.len();
    let mut column = vec![0usize; n];
    // Longest path from a node that uses nothing (acyclic, so n passes settle).
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
    for k in 0..n {
        if uses[k].is_empty() {
            if let Some(nearest) = used_by[k].iter().map(|&j| column[j]).min() {
                column[k] = nearest - 1;
            }
        }
    }
    column
}

/// The vertices of each column, top to bottom: input order, then sweeps that sort each
/// column by the mean position of its neighbours in the column before (or after).
fn ordered(
    column: &[usize],
    columns: usize,
    left: &[Vec<usize>],
    right: &[Vec<usize>],
) -> Vec<Vec<usize>> {
    let mut order: Vec<Vec<usize>> = vec![Vec::new(); columns];
    for (v, &c) in column.iter().enumerate() {
        order[c].push(v);
    }
    let mut rank = vec![0.0f64; column.len()];
    for col in &order {
        for (i, &v) in col.iter().enumerate() {
            rank[v] = i as f64;
        }
    }
    for sweep in 0..SWEEPS {
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
                .map(|(i, &v)| {
                    let near = if forward { &left[v] } else { &right[v] };
                    let key = if near.is_empty() {
                        rank[v]
                    } else {
                        near.iter().map(|&j| rank[j]).sum::<f64>() / near.len() as f64
                    };
                    (key, i, v)
                })
                .collect();
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            order[c] = keyed.into_iter().map(|(_, _, v)| v).collect();
            for (i, &v) in order[c].iter().enumerate() {
                rank[v] = i as f64;
            }
        }
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(n: usize) -> Vec<String> {
        (0..n).map(|k| format!("claim{k}")).collect()
    }

    /// No two boxes of one column overlap, and every box lies inside the drawing.
    fn boxes_apart(l: &Layout) {
        for (i, p) in l.places.iter().enumerate() {
            assert!(p.x - p.width / 2.0 >= 0.0 && p.x + p.width / 2.0 <= l.width);
            assert!(p.y - p.height / 2.0 >= 0.0 && p.y + p.height / 2.0 <= l.height);
            for q in &l.places[i + 1..] {
                if p.column == q.column {
                    assert!((p.y - q.y).abs() >= HEIGHT);
                }
            }
        }
    }

    #[test]
    fn a_claim_sits_right_of_every_claim_it_uses_and_nodes_do_not_overlap() {
        // d uses b and c; c uses a; b uses a.
        let uses = vec![vec![], vec![0], vec![0], vec![1, 2]];
        let l = layered(&labels(4), &uses);
        for (k, us) in uses.iter().enumerate() {
            for &u in us {
                assert!(
                    l.places[u].x + l.places[u].width / 2.0
                        < l.places[k].x - l.places[k].width / 2.0
                );
            }
        }
        assert_eq!(l.places[1].column, l.places[2].column);
        boxes_apart(&l);
        assert_eq!(l.routes.len(), 4);
    }

    #[test]
    fn an_edge_across_columns_passes_each_in_a_slot_no_node_occupies() {
        // A chain 0 → 1 → 2 → 3 with three more nodes beside 1 and 2, and the long
        // edge 0 → 3 across both columns.
        let uses = vec![
            vec![],
            vec![0],
            vec![1],
            vec![2, 0],
            vec![0],
            vec![4],
            vec![0],
        ];
        let l = layered(&labels(7), &uses);
        boxes_apart(&l);
        let long = l.routes.iter().find(|r| (r.from, r.to) == (0, 3)).unwrap();
        assert_eq!(
            long.points.len(),
            2 + 2 * 2,
            "one slot in each of two columns"
        );
        for pair in long.points[1..long.points.len() - 1].chunks(2) {
            let ((x1, y), (x2, y2)) = (pair[0], pair[1]);
            assert_eq!(y, y2, "a slot is crossed horizontally");
            for p in &l.places {
                let across = x1 < p.x + p.width / 2.0 && p.x - p.width / 2.0 < x2;
                let within = (y - p.y).abs() < p.height / 2.0;
                assert!(!(across && within), "the edge runs through a node");
            }
        }
        // A node that uses nothing sits just left of its nearest user.
        let uses = vec![vec![], vec![0], vec![1], vec![2, 4], vec![]];
        let l = layered(&labels(5), &uses);
        assert_eq!(l.places[4].column, l.places[3].column - 1);
    }

    #[test]
    fn the_layout_is_deterministic() {
        let uses: Vec<Vec<usize>> = (0..40)
            .map(|k: usize| {
                (0..k)
                    .filter(|j| (k * 7 + j * 3).is_multiple_of(5))
                    .collect()
            })
            .collect();
        let (a, b) = (layered(&labels(40), &uses), layered(&labels(40), &uses));
        assert_eq!(a.places, b.places);
        assert_eq!(a.routes, b.routes);
        boxes_apart(&a);
    }
}
