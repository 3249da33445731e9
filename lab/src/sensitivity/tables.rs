//! The catalogue's schemes as data: each coefficient a step reads, by the
//! name its source gives it, and the same scheme rebuilt with other values.
//!
//! A table is rebuilt the way its source builds it, so what is derived
//! from the coefficients is derived again: a composition's kicks from its
//! weights, the force evaluations per step from the weights (one fewer
//! when the last stage is the next step's first). Coefficients no step
//! reads are not listed: a Runge-Kutta tableau's nodes (every scene is
//! autonomous, and the stepper never forms `t + c h`) and a pair's embedded
//! weights (read only by the adaptive controller).
//!
//! Three catalogue schemes are written out rather than tabulated; the map
//! perturbs their tableau twins, the same method as data: explicit Euler
//! (`b = 1`), RK4 (Kutta's tableau) and the implicit midpoint rule
//! (`a = 1/2, b = 1`). The two-step Störmer-Verlet and leap-frog have no
//! coefficient as data at all: their updates are velocity Verlet's one-step
//! map carried in other variables, so velocity Verlet's row stands for
//! them.

use stepladder::conditions;
use stepladder::scheme::{
    BLANES_MOAN_SRKN11, DPRKN6, EULER_CROMER, Euler, ExplicitRk, FOREST_RUTH, Flow,
    ImplicitMidpoint, ImplicitRk, KAHAN_LI8, MCLACHLAN_ATELA4, MCLACHLAN_SB3A4, MCLACHLAN_SB3A5,
    NYSTROM4, NystromTable, PEFRL, POSITION_VERLET, Rk4, Scheme, SchemeMeta, SplittingTable,
    VELOCITY_VERLET, YOSHIDA6,
};

/// A scheme whose coefficients are data.
pub trait Coefficients: Scheme + Clone + Send + Sync + 'static {
    /// The coefficients a step reads, each with its name in the source.
    fn coefficients(&self) -> Vec<(String, f64)>;
    /// The same scheme with `values` in place of [`Coefficients::coefficients`]'s.
    fn with(&self, values: &[f64]) -> Self;
    /// Index ranges `[start, end)` of the coefficients that are stages of
    /// one kind: a swap of two of them is a swap of two stages.
    fn stage_groups(&self) -> Vec<(usize, usize)>;
    /// The order the order conditions give the table, from
    /// [`stepladder::conditions`] (for `q'' = a(q)`).
    fn conditions_order(&self) -> Option<usize>;
    /// The coefficients moved by the relative `delta` along a family of
    /// methods that keeps every order condition through the claimed order,
    /// where the map knows one.
    fn along_its_family(&self, _delta: f64) -> Option<Vec<f64>> {
        None
    }
}

/// A leaked copy: the catalogue's splitting tables hold `'static` slices,
/// and a map makes a few thousand small ones for the life of the command.
fn leaked(values: &[f64]) -> &'static [f64] {
    Box::leak(values.to_vec().into_boxed_slice())
}

impl Coefficients for SplittingTable {
    fn coefficients(&self) -> Vec<(String, f64)> {
        match self.composition {
            Some(w) => named("w", w, 1),
            None => [named("drift", self.drift, 1), named("kick", self.kick, 1)].concat(),
        }
    }

    fn with(&self, values: &[f64]) -> Self {
        let rebuilt = match self.composition {
            Some(_) => {
                let weights = leaked(values);
                let mut kicks = vec![0.5 * weights[0]];
                kicks.extend(weights.windows(2).map(|w| 0.5 * (w[0] + w[1])));
                kicks.push(0.5 * weights[weights.len() - 1]);
                SplittingTable {
                    composition: Some(weights),
                    ..SplittingTable::new(self.meta, Flow::Kick, weights, leaked(&kicks))
                }
            }
            None => {
                let (drift, kick) = values.split_at(self.drift.len());
                SplittingTable {
                    composition: None,
                    ..SplittingTable::new(self.meta, self.first, leaked(drift), leaked(kick))
                }
            }
        };
        SplittingTable {
            nystrom_only: self.nystrom_only,
            ..rebuilt
        }
    }

    fn stage_groups(&self) -> Vec<(usize, usize)> {
        match self.composition {
            Some(w) => vec![(0, w.len())],
            None => vec![
                (0, self.drift.len()),
                (self.drift.len(), self.drift.len() + self.kick.len()),
            ],
        }
    }

    fn conditions_order(&self) -> Option<usize> {
        let c =
            conditions::splitting_nystrom(&self.sequence(), self.meta.order as usize + 1).ok()?;
        Some(c.order())
    }
}

/// `name[i]` for each entry, counted from `first`.
fn named(name: &str, values: &[f64], first: usize) -> Vec<(String, f64)> {
    values
        .iter()
        .enumerate()
        .map(|(i, &x)| (format!("{name}[{}]", i + first), x))
        .collect()
}

/// The strict lower triangle of `a`, row by row, named `a[i][j]`.
fn lower<const S: usize>(a: &[[f64; S]; S]) -> Vec<(String, f64)> {
    (0..S)
        .flat_map(|i| (0..i).map(move |j| (i, j)))
        .map(|(i, j)| (format!("a[{}][{}]", i + 1, j + 1), a[i][j]))
        .collect()
}

fn set_lower<const S: usize>(a: &mut [[f64; S]; S], values: &[f64]) {
    let mut next = values.iter();
    for (i, row) in a.iter_mut().enumerate() {
        for x in &mut row[..i] {
            *x = *next
                .next()
                .expect("one value per entry of the lower triangle");
        }
    }
}

fn array<const S: usize>(values: &[f64]) -> [f64; S] {
    std::array::from_fn(|i| values[i])
}

impl<const S: usize> Coefficients for NystromTable<S> {
    /// `c`, the lower triangle of `a`, `b_bar`, `b`.
    fn coefficients(&self) -> Vec<(String, f64)> {
        // c_1 = 0 is the force at the step's start, not a coefficient
        [
            named("c", &self.c[1..], 2),
            lower(&self.a),
            named("b_bar", &self.b_bar, 1),
            named("b", &self.b, 1),
        ]
        .concat()
    }

    fn with(&self, values: &[f64]) -> Self {
        let triangle = S * (S - 1) / 2;
        let (c, rest) = values.split_at(S - 1);
        let (a, rest) = rest.split_at(triangle);
        let (b_bar, b) = rest.split_at(S);
        let mut nodes = [0.0; S];
        nodes[1..].copy_from_slice(c);
        let mut matrix = self.a;
        set_lower(&mut matrix, a);
        NystromTable::new(
            self.meta,
            nodes,
            matrix,
            array(b_bar),
            array(b),
            self.embedded,
        )
    }

    fn stage_groups(&self) -> Vec<(usize, usize)> {
        let triangle = S * (S - 1) / 2;
        let start = S - 1 + triangle;
        vec![(start, start + S), (start + S, start + 2 * S)]
    }

    fn conditions_order(&self) -> Option<usize> {
        let c = conditions::nystrom(self).ok()?;
        Some(c.main.order())
    }
}

impl<const S: usize> Coefficients for ExplicitRk<S> {
    fn coefficients(&self) -> Vec<(String, f64)> {
        [lower(&self.a), named("b", &self.b, 1)].concat()
    }

    fn with(&self, values: &[f64]) -> Self {
        let (a, b) = values.split_at(S * (S - 1) / 2);
        let mut matrix = self.a;
        set_lower(&mut matrix, a);
        ExplicitRk::new(self.meta, matrix, array(b), self.c)
    }

    fn stage_groups(&self) -> Vec<(usize, usize)> {
        let start = S * (S - 1) / 2;
        vec![(start, start + S)]
    }

    fn conditions_order(&self) -> Option<usize> {
        let c = conditions::runge_kutta(&self.a, &self.b, self.meta.order as usize + 1).ok()?;
        Some(c.order())
    }

    fn along_its_family(&self, delta: f64) -> Option<Vec<f64>> {
        (self.meta.id == Rk4::META.id && S == 4).then(|| rk4_family(delta))
    }
}

impl<const S: usize> Coefficients for ImplicitRk<S> {
    fn coefficients(&self) -> Vec<(String, f64)> {
        let a = (0..S)
            .flat_map(|i| (0..S).map(move |j| (i, j)))
            .map(|(i, j)| (format!("a[{}][{}]", i + 1, j + 1), self.a[i][j]));
        a.chain(named("b", &self.b, 1)).collect()
    }

    fn with(&self, values: &[f64]) -> Self {
        let (a, b) = values.split_at(S * S);
        let matrix = std::array::from_fn(|i| std::array::from_fn(|j| a[i * S + j]));
        ImplicitRk::new(self.meta, matrix, array(b), self.c)
    }

    fn stage_groups(&self) -> Vec<(usize, usize)> {
        vec![(S * S, S * S + S)]
    }

    fn conditions_order(&self) -> Option<usize> {
        let c = conditions::runge_kutta(&self.a, &self.b, self.meta.order as usize + 1).ok()?;
        Some(c.order())
    }
}

/// Explicit Euler as a one-stage tableau.
pub const EULER_TABLE: ExplicitRk<1> = ExplicitRk::new(Euler::META, [[0.0]], [1.0], [0.0]);

/// RK4 as Kutta's tableau.
pub const RK4_TABLE: ExplicitRk<4> = ExplicitRk::new(
    Rk4::META,
    [
        [0.0, 0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    [0.0, 0.5, 0.5, 1.0],
);

/// The implicit midpoint rule as a one-stage tableau.
pub const MIDPOINT_TABLE: ImplicitRk<1> =
    ImplicitRk::new(ImplicitMidpoint::META, [[0.5]], [1.0], [0.5]);

/// RK4's coefficients (in [`Coefficients::coefficients`]' order: `a_21,
/// a_31, a_32, a_41, a_42, a_43, b_1 .. b_4`) moved along the family of
/// four-stage explicit methods of order 4 with `c_2 = c_3 = 1/2` (Hairer,
/// Nørsett and Wanner, Solving Ordinary Differential Equations I, II.1): with
/// `b_3` free, `b = (1/6, 2/3 - b_3, b_3, 1/6)`, `a_32 = 1/(6 b_3)`, `a_31 =
/// 1/2 - a_32`, `a_42 = 1 - 3 b_3`, `a_43 = 3 b_3`. Every order condition
/// through order 4 holds for every `b_3`; classical RK4 is `b_3 = 1/3`,
/// here moved by the relative `delta`.
pub fn rk4_family(delta: f64) -> Vec<f64> {
    let b3 = (1.0 + delta) / 3.0;
    let a32 = 1.0 / (6.0 * b3);
    vec![
        0.5,
        0.5 - a32,
        a32,
        0.0,
        1.0 - 3.0 * b3,
        3.0 * b3,
        1.0 / 6.0,
        2.0 / 3.0 - b3,
        b3,
        1.0 / 6.0,
    ]
}

/// What stands in the map for a catalogue scheme.
pub enum Stand {
    /// The scheme's own table.
    Own,
    /// A tableau twin of a scheme written out.
    Twin,
    /// Another scheme's row: this one has no coefficient as data.
    RowOf(&'static str),
}

/// Every catalogue scheme with what stands for it in the map.
pub fn catalogue_stands() -> Vec<(&'static SchemeMeta, Stand)> {
    use stepladder::scheme::{Leapfrog, StormerVerlet};
    let velocity_verlet = VELOCITY_VERLET.meta().id;
    stepladder::scheme::catalogue()
        .into_iter()
        .map(|meta| {
            let stand =
                if [Euler::META.id, Rk4::META.id, ImplicitMidpoint::META.id].contains(&meta.id) {
                    Stand::Twin
                } else if [StormerVerlet.meta().id, Leapfrog.meta().id].contains(&meta.id) {
                    Stand::RowOf(velocity_verlet)
                } else {
                    Stand::Own
                };
            (meta, stand)
        })
        .collect()
}

/// Something to do with every table the map perturbs.
pub trait TableVisitor {
    /// What one visit produces.
    type Output;
    /// Called with one table.
    fn visit<T: Coefficients>(&mut self, table: &T) -> Self::Output;
}

/// Runs `visitor` on every table the map perturbs, in catalogue order.
pub fn visit_tables<V: TableVisitor>(visitor: &mut V) -> Vec<V::Output> {
    vec![
        visitor.visit(&EULER_TABLE),
        visitor.visit(&EULER_CROMER),
        visitor.visit(&VELOCITY_VERLET),
        visitor.visit(&POSITION_VERLET),
        visitor.visit(&MIDPOINT_TABLE),
        visitor.visit(&RK4_TABLE),
        visitor.visit(&FOREST_RUTH),
        visitor.visit(&PEFRL),
        visitor.visit(&YOSHIDA6),
        visitor.visit(&KAHAN_LI8),
        visitor.visit(&MCLACHLAN_ATELA4),
        visitor.visit(&MCLACHLAN_SB3A4),
        visitor.visit(&MCLACHLAN_SB3A5),
        visitor.visit(&BLANES_MOAN_SRKN11),
        visitor.visit(&NYSTROM4),
        visitor.visit(&DPRKN6),
    ]
}

struct Id;

impl TableVisitor for Id {
    type Output = &'static str;

    fn visit<T: Coefficients>(&mut self, table: &T) -> &'static str {
        table.meta().id
    }
}

/// The ids of the tables the map perturbs.
pub fn table_ids() -> Vec<&'static str> {
    visit_tables(&mut Id)
}
