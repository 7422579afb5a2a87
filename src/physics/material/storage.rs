//! Stored Gauss point states: what a [`PointState`] keeps between updates,
//! in storage whose twist part exists only in a model with twist.
//!
//! A [`PointState`] holds six stress and six plastic strain components (112
//! bytes); the last two of each (the shear of twist, σ_rθ, σ_zθ, εᵖ_rθ,
//! εᵖ_zθ) are zero unless the model has twist. [`GaussStates`] keeps the
//! first four of each with ε̄ᵖ and the yielding flag (80 bytes a point) and,
//! only with twist, the four twist components in a second vector (32 bytes a
//! point), so a model without twist pays for none of them. The material
//! routines compute with whole [`PointState`]s: a reader takes a copy
//! ([`GaussStates::get`], [`GaussRef::iter`]), a writer stores one back
//! ([`GaussStates::set`], [`GaussMut::set`]).

use super::PointState;
use std::ops::Range;

/// The part of a [`PointState`] every model stores (80 bytes).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Stored {
    stress: [f64; 4],
    plastic_strain: [f64; 4],
    peeq: f64,
    yielding: bool,
}

/// σ_rθ, σ_zθ, εᵖ_rθ, εᵖ_zθ of one point (a model with twist).
type Twist = [f64; 4];

fn split(s: &PointState) -> (Stored, Twist) {
    let (st, ep) = (&s.stress, &s.plastic_strain);
    (
        Stored {
            stress: [st[0], st[1], st[2], st[3]],
            plastic_strain: [ep[0], ep[1], ep[2], ep[3]],
            peeq: s.peeq,
            yielding: s.yielding,
        },
        [st[4], st[5], ep[4], ep[5]],
    )
}

fn join(b: &Stored, t: Option<&Twist>) -> PointState {
    let t = t.copied().unwrap_or([0.0; 4]);
    let (s, e) = (&b.stress, &b.plastic_strain);
    PointState {
        stress: [s[0], s[1], s[2], s[3], t[0], t[1]],
        plastic_strain: [e[0], e[1], e[2], e[3], t[2], t[3]],
        peeq: b.peeq,
        yielding: b.yielding,
    }
}

/// Gauss point states of a model, one per point: the twist components are
/// stored only when the model has twist (constructed with `twist`); without
/// it they read as zero and must be zero when stored.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GaussStates {
    base: Vec<Stored>,
    /// Empty without twist, else one per point.
    twist: Vec<Twist>,
    has_twist: bool,
}

impl GaussStates {
    /// `n` zero states (as [`PointState::default`]).
    pub fn new(n: usize, twist: bool) -> Self {
        GaussStates {
            base: vec![Stored::default(); n],
            twist: if twist { vec![[0.0; 4]; n] } else { Vec::new() },
            has_twist: twist,
        }
    }

    /// No states yet, room for `n`.
    pub(crate) fn with_capacity(n: usize, twist: bool) -> Self {
        GaussStates {
            base: Vec::with_capacity(n),
            twist: Vec::with_capacity(if twist { n } else { 0 }),
            has_twist: twist,
        }
    }

    /// The states of a model with (or without) twist, in order.
    #[cfg(test)]
    pub(crate) fn from_states(states: impl IntoIterator<Item = PointState>, twist: bool) -> Self {
        let mut g = Self::with_capacity(0, twist);
        for s in states {
            g.push(&s);
        }
        g
    }

    /// Whether the twist components are stored.
    pub fn twist(&self) -> bool {
        self.has_twist
    }

    pub fn len(&self) -> usize {
        self.base.len()
    }

    pub fn is_empty(&self) -> bool {
        self.base.is_empty()
    }

    /// A copy of state `i`.
    pub fn get(&self, i: usize) -> PointState {
        self.all().get(i)
    }

    /// Stores `s` as state `i`.
    pub fn set(&mut self, i: usize, s: &PointState) {
        self.range_mut(i..i + 1).set(0, s);
    }

    /// Changes state `i` by `f` (a copy, stored back).
    pub fn update(&mut self, i: usize, f: impl FnOnce(&mut PointState)) {
        let mut s = self.get(i);
        f(&mut s);
        self.set(i, &s);
    }

    /// Appends `s`.
    pub fn push(&mut self, s: &PointState) {
        let (b, t) = split(s);
        self.base.push(b);
        if self.has_twist {
            self.twist.push(t);
        } else {
            debug_assert_eq!(t, [0.0; 4], "twist components in a model without twist");
        }
    }

    /// Appends the states of `from`.
    pub(crate) fn extend_from(&mut self, from: GaussRef<'_>) {
        self.base.extend_from_slice(from.base);
        if self.has_twist {
            self.twist.extend_from_slice(from.twist);
        }
    }

    /// Every state.
    pub fn all(&self) -> GaussRef<'_> {
        GaussRef {
            base: &self.base,
            twist: &self.twist,
        }
    }

    /// Copies of every state, in order.
    pub fn iter(&self) -> Iter<'_> {
        self.all().iter()
    }

    /// States `r` (as a slice of a `Vec<PointState>` would be).
    pub fn range(&self, r: Range<usize>) -> GaussRef<'_> {
        GaussRef {
            base: &self.base[r.clone()],
            twist: if self.has_twist { &self.twist[r] } else { &[] },
        }
    }

    /// States `r`, to be written.
    pub(crate) fn range_mut(&mut self, r: Range<usize>) -> GaussMut<'_> {
        GaussMut {
            base: &mut self.base[r.clone()],
            twist: if self.has_twist {
                &mut self.twist[r]
            } else {
                &mut []
            },
        }
    }
}

impl<'a> IntoIterator for &'a GaussStates {
    type Item = PointState;
    type IntoIter = Iter<'a>;
    fn into_iter(self) -> Iter<'a> {
        self.all().iter()
    }
}

/// A run of stored states, read by copy.
#[derive(Clone, Copy, Debug, Default)]
pub struct GaussRef<'a> {
    base: &'a [Stored],
    /// Empty without twist.
    twist: &'a [Twist],
}

impl<'a> GaussRef<'a> {
    pub fn len(&self) -> usize {
        self.base.len()
    }

    pub fn is_empty(&self) -> bool {
        self.base.is_empty()
    }

    /// A copy of state `i` of the run.
    pub fn get(&self, i: usize) -> PointState {
        join(&self.base[i], self.twist.get(i))
    }

    /// Copies of the states of the run, in order.
    pub fn iter(&self) -> Iter<'a> {
        Iter { run: *self, at: 0 }
    }

    /// The first `n` states and the rest.
    pub(crate) fn split_at(&self, n: usize) -> (GaussRef<'a>, GaussRef<'a>) {
        let (b0, b1) = self.base.split_at(n);
        let (t0, t1) = self.twist.split_at(n.min(self.twist.len()));
        (
            GaussRef {
                base: b0,
                twist: t0,
            },
            GaussRef {
                base: b1,
                twist: t1,
            },
        )
    }

    /// States `r` of the run.
    pub fn range(&self, r: Range<usize>) -> GaussRef<'a> {
        GaussRef {
            base: &self.base[r.clone()],
            twist: if self.twist.is_empty() {
                &[]
            } else {
                &self.twist[r]
            },
        }
    }

    /// Copies the run into `out` (as long).
    pub fn load(&self, out: &mut [PointState]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.get(i);
        }
    }
}

impl<'a> IntoIterator for GaussRef<'a> {
    type Item = PointState;
    type IntoIter = Iter<'a>;
    fn into_iter(self) -> Iter<'a> {
        self.iter()
    }
}

/// Copies of the states of a [`GaussRef`].
#[derive(Clone, Debug)]
pub struct Iter<'a> {
    run: GaussRef<'a>,
    at: usize,
}

impl Iterator for Iter<'_> {
    type Item = PointState;
    fn next(&mut self) -> Option<PointState> {
        (self.at < self.run.len()).then(|| {
            self.at += 1;
            self.run.get(self.at - 1)
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.run.len() - self.at;
        (n, Some(n))
    }
}

impl ExactSizeIterator for Iter<'_> {}

/// A run of stored states, to be written.
#[derive(Debug, Default)]
pub(crate) struct GaussMut<'a> {
    base: &'a mut [Stored],
    /// Empty without twist.
    twist: &'a mut [Twist],
}

impl<'a> GaussMut<'a> {
    /// A copy of state `i` of the run.
    pub fn get(&self, i: usize) -> PointState {
        join(&self.base[i], self.twist.get(i))
    }

    /// Stores `s` as state `i` of the run.
    pub fn set(&mut self, i: usize, s: &PointState) {
        let (b, t) = split(s);
        self.base[i] = b;
        if self.twist.is_empty() {
            debug_assert_eq!(t, [0.0; 4], "twist components in a model without twist");
        } else {
            self.twist[i] = t;
        }
    }

    /// The first `n` states and the rest.
    pub(crate) fn split_at_mut(self, n: usize) -> (GaussMut<'a>, GaussMut<'a>) {
        let (b0, b1) = self.base.split_at_mut(n);
        let k = n.min(self.twist.len());
        let (t0, t1) = self.twist.split_at_mut(k);
        (
            GaussMut {
                base: b0,
                twist: t0,
            },
            GaussMut {
                base: b1,
                twist: t1,
            },
        )
    }

    /// States `r` of the run.
    pub(crate) fn range_mut(&mut self, r: Range<usize>) -> GaussMut<'_> {
        GaussMut {
            base: &mut self.base[r.clone()],
            twist: if self.twist.is_empty() {
                &mut []
            } else {
                &mut self.twist[r]
            },
        }
    }

    /// Copies the run into `out` (as long).
    pub fn load(&self, out: &mut [PointState]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.get(i);
        }
    }

    /// Stores `from` (as long) as the run.
    pub fn store(&mut self, from: &[PointState]) {
        for (i, s) in from.iter().enumerate() {
            self.set(i, s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(k: f64, twist: bool) -> PointState {
        let t = if twist { 1.0 } else { 0.0 };
        PointState {
            stress: [k, k + 1.0, k + 2.0, k + 3.0, t * (k + 4.0), t * (k + 5.0)],
            plastic_strain: [-k, -k - 1.0, -k - 2.0, -k - 3.0, t * -k, t * (k - 4.0)],
            peeq: 0.5 * k,
            yielding: k > 1.0,
        }
    }

    #[test]
    fn stored_point_is_80_bytes() {
        assert!(std::mem::size_of::<Stored>() <= 80);
        assert_eq!(std::mem::size_of::<Twist>(), 32);
    }

    #[test]
    fn round_trips_with_and_without_twist() {
        for twist in [false, true] {
            let all: Vec<_> = (0..7).map(|k| state(k as f64, twist)).collect();
            let mut g = GaussStates::from_states(all.iter().copied(), twist);
            assert_eq!(g.len(), 7);
            assert_eq!(g.twist(), twist);
            assert_eq!(g.iter().collect::<Vec<_>>(), all);
            assert_eq!(g.range(2..5).iter().collect::<Vec<_>>(), all[2..5]);
            let (a, b) = g.range(1..6).split_at(2);
            assert_eq!(a.iter().chain(b).collect::<Vec<_>>(), all[1..6]);
            g.set(3, &state(9.0, twist));
            assert_eq!(g.get(3), state(9.0, twist));
            let (mut m0, mut m1) = g.range_mut(0..7).split_at_mut(4);
            m0.store(&[state(10.0, twist)]);
            m1.set(0, &state(11.0, twist));
            assert_eq!(g.get(0), state(10.0, twist));
            assert_eq!(g.get(4), state(11.0, twist));
            let mut h = GaussStates::with_capacity(2, twist);
            h.extend_from(g.range(4..6));
            assert_eq!(h.get(0), state(11.0, twist));
            assert_eq!(h.get(1), all[5]);
            let n = GaussStates::new(3, twist);
            assert!(n.iter().all(|s| s == PointState::default()));
        }
    }
}
