//! A directed graph of module names and a cycle finder.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

pub type Graph = BTreeMap<String, BTreeSet<String>>;

pub fn graph(edges: &[(&str, &str)]) -> Graph {
    let mut g = Graph::new();
    for &(a, b) in edges {
        g.entry(a.to_string()).or_default().insert(b.to_string());
        g.entry(b.to_string()).or_default();
    }
    g
}

/// Shortest path `from -> .. -> to` (both ends included) using only nodes
/// in `within`, if any.
fn shortest_path(
    g: &Graph,
    from: &str,
    to: &str,
    within: &BTreeSet<String>,
) -> Option<Vec<String>> {
    let mut parent: BTreeMap<&str, &str> = BTreeMap::new();
    let mut queue = VecDeque::from([from]);
    while let Some(n) = queue.pop_front() {
        for m in g.get(n).into_iter().flatten() {
            if !within.contains(m) || parent.contains_key(m.as_str()) {
                continue;
            }
            parent.insert(m, n);
            if m == to {
                let mut path = vec![to.to_string()];
                let mut cur = to;
                loop {
                    cur = parent[cur];
                    path.push(cur.to_string());
                    if cur == from {
                        break;
                    }
                }
                path.reverse();
                return Some(path);
            }
            queue.push_back(m);
        }
    }
    None
}

fn reachable(g: &Graph, from: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut stack = vec![from.to_string()];
    while let Some(n) = stack.pop() {
        for m in g.get(&n).into_iter().flatten() {
            if seen.insert(m.clone()) {
                stack.push(m.clone());
            }
        }
    }
    seen
}

/// One cycle per group of mutually reachable modules: the shortest cycle
/// through the group's first module, as `[a, b, .., a]`.
pub fn cycles(g: &Graph) -> Vec<Vec<String>> {
    let reach: BTreeMap<&String, BTreeSet<String>> =
        g.keys().map(|n| (n, reachable(g, n))).collect();
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for n in g.keys() {
        if done.contains(n) || !reach[n].contains(n) {
            continue;
        }
        let group: BTreeSet<String> = g
            .keys()
            .filter(|m| reach[n].contains(*m) && reach[*m].contains(n))
            .cloned()
            .collect();
        done.extend(group.iter().cloned());
        // n, then the shortest way back to n from one of its successors.
        let back = g[n]
            .iter()
            .filter(|m| group.contains(*m) && *m != n)
            .filter_map(|m| shortest_path(g, m, n, &group))
            .min_by_key(|p| p.len())
            .expect("a module on a cycle has a successor on it");
        out.push([vec![n.clone()], back].concat());
    }
    out
}

#[test]
fn finds_a_cycle_in_a_hand_made_graph() {
    let g = graph(&[
        ("load", "scene"),
        ("scene", "accel"),
        ("accel", "geometry"),
        ("geometry", "scene"),
        ("integrator", "scene"),
        ("image_io", "load"),
        ("load", "image_io"),
    ]);
    let found = cycles(&g);
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    assert_eq!(
        found,
        [
            s(&["accel", "geometry", "scene", "accel"]),
            s(&["image_io", "load", "image_io"]),
        ]
    );
}

#[test]
fn finds_no_cycle_in_layers() {
    let g = graph(&[
        ("load", "scene"),
        ("load", "geometry"),
        ("scene", "accel"),
        ("accel", "geometry"),
        ("integrator", "scene"),
    ]);
    assert!(cycles(&g).is_empty());
}
