//! A bounding-box tree over the master side's faces: the closest face to a
//! slave point in O(log n) face tests for a well-spread side, instead of
//! testing every face (O(slave × master) over the interface).
//!
//! Each face's box holds its nodes and a 5 × 5 sample of its surface (a
//! quadratic face bulges beyond its nodes), padded by 5 % of its diagonal.
//! The tree splits the faces at the median of their boxes' centres along the
//! longest side of the centres' extent, down to [`LEAF`] faces a leaf. A
//! query walks it nearest box first and skips a box farther from the point
//! than the nearest face found so far.

use crate::numbers::vec3::dot;

/// The most faces of a leaf.
const LEAF: usize = 4;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Aabb {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

impl Aabb {
    pub(crate) const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    pub(crate) fn grow(&mut self, x: [f64; 3]) {
        self.lo = std::array::from_fn(|c| self.lo[c].min(x[c]));
        self.hi = std::array::from_fn(|c| self.hi[c].max(x[c]));
    }

    fn join(a: Aabb, b: Aabb) -> Aabb {
        Aabb {
            lo: std::array::from_fn(|c| a.lo[c].min(b.lo[c])),
            hi: std::array::from_fn(|c| a.hi[c].max(b.hi[c])),
        }
    }

    /// The box grown by `pad` on every side.
    pub(crate) fn padded(self, pad: f64) -> Aabb {
        Aabb {
            lo: self.lo.map(|v| v - pad),
            hi: self.hi.map(|v| v + pad),
        }
    }

    pub(crate) fn diagonal(&self) -> f64 {
        let d: [f64; 3] = std::array::from_fn(|c| self.hi[c] - self.lo[c]);
        dot(d, d).sqrt()
    }

    fn centre(&self) -> [f64; 3] {
        std::array::from_fn(|c| 0.5 * (self.lo[c] + self.hi[c]))
    }

    /// The squared distance from `p` to the box (0 inside).
    fn dist2(&self, p: [f64; 3]) -> f64 {
        (0..3)
            .map(|c| {
                let d = (self.lo[c] - p[c]).max(p[c] - self.hi[c]).max(0.0);
                d * d
            })
            .sum()
    }
}

/// A node of the tree: its box and either two children or a run of faces.
struct Node {
    aabb: Aabb,
    /// Children (indices into `nodes`), or usize::MAX for a leaf.
    kids: [usize; 2],
    /// A leaf's faces: `order[from..to]`.
    from: usize,
    to: usize,
}

/// The tree (module text).
pub(crate) struct Tree {
    nodes: Vec<Node>,
    order: Vec<usize>,
}

impl Tree {
    /// The tree over boxes `boxes` (one a face, in the faces' order).
    pub(crate) fn new(boxes: &[Aabb]) -> Tree {
        let mut tree = Tree {
            nodes: Vec::new(),
            order: (0..boxes.len()).collect(),
        };
        if !boxes.is_empty() {
            tree.build(boxes, 0, boxes.len());
        }
        tree
    }

    /// Builds the node over `order[from..to]`, returns its index.
    fn build(&mut self, boxes: &[Aabb], from: usize, to: usize) -> usize {
        let aabb = self.order[from..to]
            .iter()
            .fold(Aabb::EMPTY, |a, &f| Aabb::join(a, boxes[f]));
        let me = self.nodes.len();
        self.nodes.push(Node {
            aabb,
            kids: [usize::MAX; 2],
            from,
            to,
        });
        if to - from <= LEAF {
            return me;
        }
        let mut centres = Aabb::EMPTY;
        for &f in &self.order[from..to] {
            centres.grow(boxes[f].centre());
        }
        let axis = (0..3)
            .max_by(|&a, &b| {
                (centres.hi[a] - centres.lo[a]).total_cmp(&(centres.hi[b] - centres.lo[b]))
            })
            .unwrap_or(0);
        let mid = from + (to - from) / 2;
        self.order[from..to].select_nth_unstable_by(mid - from, |&a, &b| {
            boxes[a].centre()[axis]
                .total_cmp(&boxes[b].centre()[axis])
                .then(a.cmp(&b))
        });
        let left = self.build(boxes, from, mid);
        let right = self.build(boxes, mid, to);
        self.nodes[me].kids = [left, right];
        me
    }

    /// Calls `test(face)` for every face whose box lies within the current
    /// bound of `p`, nearest box first; `test` returns the squared distance
    /// of the face's closest point, which tightens the bound. Returns the
    /// final bound.
    pub(crate) fn nearest(&self, p: [f64; 3], mut test: impl FnMut(usize) -> f64) -> f64 {
        let mut bound = f64::INFINITY;
        if self.nodes.is_empty() {
            return bound;
        }
        let mut stack = vec![0usize];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k];
            if node.aabb.dist2(p) > bound {
                continue;
            }
            if node.kids[0] == usize::MAX {
                for &f in &self.order[node.from..node.to] {
                    bound = bound.min(test(f));
                }
                continue;
            }
            let [a, b] = node.kids;
            let (da, db) = (self.nodes[a].aabb.dist2(p), self.nodes[b].aabb.dist2(p));
            // the nearer child is popped first
            if da <= db {
                stack.extend([b, a]);
            } else {
                stack.extend([a, b]);
            }
        }
        bound
    }
}
