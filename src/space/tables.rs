//! The 1D B-spline tables of one parametric direction at the Gauss points
//! of each knot span. An element's tables depend only on its own span in
//! each direction, so a row of elements shares its η tables and a column its
//! ξ tables: computed once per space, they take the Cox–de Boor work out of
//! the element loop.

use crate::nurbs::KnotVector;
use crate::quadrature;

/// One direction's Gauss rules and `[N, dN/du]` rows per knot span.
#[derive(Clone, Debug)]
pub(crate) struct SpanTables {
    /// Gauss points per span.
    order: usize,
    /// p + 1: the entries of one row.
    width: usize,
    /// Knot-span index → position in the tables, `None` for empty spans.
    position: Vec<Option<usize>>,
    /// Parametric extent of each span, to check a lookup against.
    ranges: Vec<[f64; 2]>,
    /// Per span, per point: (abscissa, weight).
    rule: Vec<(f64, f64)>,
    /// Per span, per point: the value row then the derivative row.
    ders: Vec<f64>,
}

/// One span's rule and rows, borrowed from the tables.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SpanRule<'a> {
    pub rule: &'a [(f64, f64)],
    ders: &'a [f64],
    width: usize,
}

impl SpanRule<'_> {
    /// `[N, dN/du]` at Gauss point `g`, N of the span's p + 1 functions.
    pub fn rows(&self, g: usize) -> [&[f64]; 2] {
        let at = 2 * g * self.width;
        [
            &self.ders[at..at + self.width],
            &self.ders[at + self.width..at + 2 * self.width],
        ]
    }
}

impl SpanTables {
    /// The tables of every non-empty span of `knots` for an `order`-point rule.
    pub fn new(knots: &KnotVector, order: usize) -> Self {
        let mut this = Self::empty(knots, order);
        for (span, a, b) in knots.spans() {
            this.push(knots, span, [a, b]);
        }
        this
    }

    /// The tables of one span alone, for an element the space's own tables
    /// do not describe.
    pub fn single(knots: &KnotVector, order: usize, span: usize, range: [f64; 2]) -> Self {
        let mut this = Self::empty(knots, order);
        this.push(knots, span, range);
        this
    }

    fn empty(knots: &KnotVector, order: usize) -> Self {
        Self {
            order,
            width: knots.degree() + 1,
            position: vec![None; knots.knots().len()],
            ranges: Vec::new(),
            rule: Vec::new(),
            ders: Vec::new(),
        }
    }

    fn push(&mut self, knots: &KnotVector, span: usize, range: [f64; 2]) {
        self.position[span] = Some(self.ranges.len());
        self.ranges.push(range);
        for (u, w) in quadrature::on_interval(self.order, range[0], range[1]) {
            let d = knots.basis_ders(span, u, 1);
            self.rule.push((u, w));
            self.ders.extend_from_slice(&d[0]);
            self.ders.extend_from_slice(&d[1]);
        }
    }

    /// The rule and rows of span `span` over `range` with `order` points,
    /// if these tables hold exactly that.
    pub fn lookup(&self, span: usize, range: [f64; 2], order: usize) -> Option<SpanRule<'_>> {
        let s = (*self.position.get(span)?)?;
        (order == self.order && self.ranges[s] == range).then(|| {
            let n = self.order;
            let len = 2 * n * self.width;
            SpanRule {
                rule: &self.rule[s * n..(s + 1) * n],
                ders: &self.ders[s * len..(s + 1) * len],
                width: self.width,
            }
        })
    }
}
