//! The order conditions of a splitting, composition, Runge-Kutta-Nyström or
//! Runge-Kutta tableau, in double-double arithmetic: a table typed from a
//! paper is checked against the algebra behind its claimed order before a
//! single ladder runs.
//!
//! ```
//! use stepladder::conditions;
//! use stepladder::scheme::{FOREST_RUTH, MCLACHLAN_ATELA4};
//!
//! // Forest-Ruth is fourth order for any two non-commuting flows
//! let c = conditions::splitting(&FOREST_RUTH)?;
//! assert_eq!((c.general_order(), c.nystrom_order()), (4, 4));
//! assert!(c.general.confirms(4) && c.nystrom.confirms(4));
//!
//! // McLachlan and Atela's table is fourth order only for q'' = a(q)
//! let c = conditions::splitting(&MCLACHLAN_ATELA4)?;
//! assert_eq!((c.general_order(), c.nystrom_order()), (3, 4));
//! println!("{}", c.nystrom); // h^1 defect/allowance ... h^5
//! # Ok::<(), stepladder::error::Error>(())
//! ```
//!
//! Three checks, one verdict per power of `h`:
//!
//! - a splitting or composition for any two non-commuting flows
//!   ([`splitting_general`]): the method's series in `h` against
//!   `exp(h (A + B))` on two random 6 x 6 matrices, which see every
//!   condition of the free Lie algebra of the two flows;
//! - a splitting ([`splitting_nystrom`]) or a Runge-Kutta-Nyström tableau
//!   ([`nystrom`]) for `q'' = a(q)` only: the method applied to power series
//!   against the Taylor series of the exact flow, on a polynomial force of
//!   degree 7 at four random points, which sees every Nyström condition up
//!   to `h^9`; and, for splittings, one numerical step at `h` and `h/2`
//!   ([`splitting_step_ratio`]);
//! - a Runge-Kutta tableau ([`runge_kutta`]): Butcher's tree conditions.
//!
//! Each defect is computed in double-double and comes with its allowance:
//! what rounding every coefficient to a double (one unit in the last place
//! each) and the double-double arithmetic can explain. A condition holds
//! when its defect is within the allowance, so weights a few units in the
//! last place off an exact solution (published digits not refined) fail,
//! and a condition is clearly violated when its defect is [`BEYOND_ORDER`]
//! times the allowance or more.

mod defect;
mod lie;
mod taylor;
mod trees;

use defect::uniform;
pub use defect::{BEYOND_ORDER, Defect, StepRatio, TreeDefect};

use crate::error::Error;
use crate::scheme::{Flow, NystromTable, SplittingTable};
use std::fmt;

/// The highest power of `h` the checks resolve. The Nyström problem's force
/// is a polynomial of degree 7, so its local error coefficients `E_k` see
/// every elementary differential (derivatives of the force of order up to
/// `k - 2`) through `k = 9`; the 6 x 6 matrices of the generic check see
/// every Lie polynomial through degree 11, and Butcher's trees are exact at
/// any order, but with one bound every check confirms an order up to 8 and
/// sees the condition beyond it.
pub const MAX_DEGREE: usize = 9;

/// The highest power of `h` the Runge-Kutta-Nyström check resolves: past
/// `h^9` it raises the force's degree to 11, so that `E_k` sees every
/// elementary differential through `k = 13`, a twelfth-order tableau's
/// conditions and the one beyond them.
pub const NYSTROM_MAX_DEGREE: usize = 13;

/// The conditions of one method at `h^1 .. h^degree`.
#[derive(Clone, Debug, PartialEq)]
pub struct Conditions {
    /// One entry per power of `h`, from `h^1` up.
    pub defects: Vec<Defect>,
}

impl Conditions {
    /// The highest power of `h` checked.
    pub fn degree(&self) -> usize {
        self.defects.len()
    }

    /// The order satisfied: the largest `p` such that every condition
    /// through `h^p` holds. Equal to [`Conditions::degree`], it is a lower
    /// bound only.
    pub fn order(&self) -> usize {
        self.defects.iter().take_while(|d| d.holds()).count()
    }

    /// The defect at `h^degree`, if checked.
    pub fn at(&self, degree: usize) -> Option<&Defect> {
        degree.checked_sub(1).and_then(|i| self.defects.get(i))
    }

    /// The defect with the largest ratio to its allowance among `h^1 ..
    /// h^degree`.
    pub fn worst_through(&self, degree: usize) -> Option<&Defect> {
        self.defects
            .iter()
            .take(degree)
            .max_by(|a, b| a.ratio().total_cmp(&b.ratio()))
    }

    /// The order is exactly `order`: every condition through `h^order`
    /// holds and the one at `h^(order+1)` is checked and clearly violated.
    pub fn confirms(&self, order: usize) -> bool {
        self.order() >= order && self.at(order + 1).is_some_and(Defect::clearly_fails)
    }
}

/// `h^1 3.1e-17/4.2e-16 h^2 ...`: each defect over its allowance.
impl fmt::Display for Conditions {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let items: Vec<String> = self
            .defects
            .iter()
            .map(|d| format!("h^{} {:.1e}/{:.1e}", d.degree, d.value, d.allowance))
            .collect();
        write!(f, "{}", items.join(" "))
    }
}

/// A splitting's or composition's conditions, for any two flows and for
/// `q'' = a(q)`.
#[derive(Clone, Debug, PartialEq)]
pub struct SplittingConditions {
    /// For the splitting of any two non-commuting flows.
    pub general: Conditions,
    /// For `q'' = a(q)` (drift `q' = v`, kick `v' = a(q)`), which satisfies
    /// `[B, [B, [B, A]]] = 0` and so has fewer conditions.
    pub nystrom: Conditions,
}

impl SplittingConditions {
    /// The order for any two non-commuting flows.
    pub fn general_order(&self) -> usize {
        self.general.order()
    }

    /// The order for `q'' = a(q)`, at least the general one.
    pub fn nystrom_order(&self) -> usize {
        self.nystrom.order()
    }
}

/// A Runge-Kutta-Nyström tableau's conditions for `q'' = a(q)`.
#[derive(Clone, Debug, PartialEq)]
pub struct NystromConditions {
    /// The main solution's.
    pub main: Conditions,
    /// The embedded solution's, for a pair, to the same degree.
    pub embedded: Option<Conditions>,
}

/// A Runge-Kutta tableau's Butcher tree conditions.
#[derive(Clone, Debug, PartialEq)]
pub struct RungeKuttaConditions {
    /// Per order, the tree with the largest ratio to its allowance.
    pub by_degree: Conditions,
    /// Every tree up to the degree checked, by order.
    pub trees: Vec<TreeDefect>,
}

impl RungeKuttaConditions {
    /// The order satisfied: every tree through this order holds.
    pub fn order(&self) -> usize {
        self.by_degree.order()
    }
}

/// A splitting or composition table's conditions through `h^(order+1)`,
/// with `order` its claimed order: for any two flows and for `q'' = a(q)`.
///
/// A table has its claimed order `p` when `nystrom.confirms(p)`, and, unless
/// it is marked [`SplittingTable::nystrom_only`], `general.confirms(p)`.
///
/// ```
/// use stepladder::conditions;
/// use stepladder::scheme::{Flow, SchemeMeta, SplittingTable};
///
/// // the drift-first triple jump of position Verlet, typed anew
/// const W: f64 = 1.351_207_191_959_657_5; // 1/(2 - 2^(1/3))
/// const TRIPLE: SplittingTable = SplittingTable::new(
///     SchemeMeta::new("triple", "drift-first triple jump", 4),
///     Flow::Drift,
///     &[0.5 * W, 0.5 * (1.0 - W), 0.5 * (1.0 - W), 0.5 * W],
///     &[W, 1.0 - 2.0 * W, W],
/// );
/// let c = conditions::splitting(&TRIPLE)?;
/// assert!(c.general.confirms(4) && c.nystrom.confirms(4));
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::InvalidTable`] for a table with no flows, a weight that is not
/// finite, weight lists whose lengths do not alternate, or weights so large
/// that the series overflow; [`Error::InvalidParameter`] for a claimed order
/// beyond `MAX_DEGREE - 1`.
pub fn splitting(table: &SplittingTable) -> Result<SplittingConditions, Error> {
    let (lead, lag) = match table.first {
        Flow::Drift => (table.drift.len(), table.kick.len()),
        Flow::Kick => (table.kick.len(), table.drift.len()),
    };
    if lead != lag && lead != lag + 1 {
        return Err(Error::InvalidTable(format!(
            "{}: the first flow has {lead} weights and the other {lag}: they alternate, so the first has as many or one more",
            table.meta.id
        )));
    }
    let flows = table.sequence();
    let degree = table.meta.order as usize + 1;
    Ok(SplittingConditions {
        general: splitting_general(&flows, degree)?,
        nystrom: splitting_nystrom(&flows, degree)?,
    })
}

/// The conditions of the flows `(flow, weight)`, in order of application,
/// for the splitting of any two non-commuting flows, through `h^degree`.
///
/// ```
/// use stepladder::conditions;
/// use stepladder::scheme::MCLACHLAN_ATELA4;
///
/// // a Nyström splitting: only third order for any two flows
/// let c = conditions::splitting_general(&MCLACHLAN_ATELA4.sequence(), 4)?;
/// assert_eq!(c.order(), 3);
/// assert!(c.confirms(3));
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::InvalidTable`] for no flows, a weight that is not finite or
/// weights so large that the series overflow; [`Error::InvalidParameter`]
/// for a degree outside `1..=MAX_DEGREE`.
pub fn splitting_general(flows: &[(Flow, f64)], degree: usize) -> Result<Conditions, Error> {
    check_flows(flows)?;
    check_degree(degree)?;
    finite(lie::defects(flows, degree))
}

/// The conditions of the flows `(flow, weight)`, in order of application,
/// for `q'' = a(q)` (drift `q += w h v`, kick `v += w h a(q)`), through
/// `h^degree`.
///
/// ```
/// use stepladder::conditions;
/// use stepladder::scheme::MCLACHLAN_ATELA4;
///
/// let c = conditions::splitting_nystrom(&MCLACHLAN_ATELA4.sequence(), 5)?;
/// assert!(c.confirms(4));
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// As [`splitting_general`].
pub fn splitting_nystrom(flows: &[(Flow, f64)], degree: usize) -> Result<Conditions, Error> {
    check_flows(flows)?;
    check_degree(degree)?;
    finite(taylor::defects(
        &taylor::Method::Flows(flows.to_vec()),
        degree,
    ))
}

/// The local error of one numerical step of the flows at `h` and `h/2` on
/// the Nyström test problem, against the range a method of order `order`
/// allows: a check of the order independent of the series, which a weight
/// off in its 8th digit fails too. The range lies within a factor `sqrt 2`
/// of `2^(order+1)` for every table of the catalogue.
///
/// ```
/// use stepladder::conditions;
/// use stepladder::scheme::FOREST_RUTH;
///
/// let r = conditions::splitting_step_ratio(&FOREST_RUTH.sequence(), 4)?;
/// assert!(r.holds(), "{r:?}");
/// assert!(r.low > 32.0 / 2f64.sqrt() && r.high < 32.0 * 2f64.sqrt());
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// As [`splitting_general`], with `order + 1` the degree; and
/// [`Error::InvalidTable`] when at no step from `2^-2` to `2^-59` does the
/// `h^(order+1)` term dominate what rounding and the higher terms allow
/// (the flows are not of this order).
pub fn splitting_step_ratio(flows: &[(Flow, f64)], order: usize) -> Result<StepRatio, Error> {
    check_flows(flows)?;
    check_degree(order.saturating_add(1))?;
    let ratio = taylor::step_ratio(flows, order).ok_or_else(|| {
        Error::InvalidTable(format!(
            "at no step does the h^{} term of the local error dominate: the flows are not of order {order}",
            order + 1
        ))
    })?;
    if ratio.measured.is_finite() && ratio.low.is_finite() && ratio.high.is_finite() {
        Ok(ratio)
    } else {
        Err(overflow())
    }
}

/// A Runge-Kutta-Nyström tableau's conditions for `q'' = a(q)` through
/// `h^(order+1)`, `order` its claimed order, for the main solution and the
/// embedded one.
///
/// ```
/// use stepladder::conditions;
/// use stepladder::scheme::{NystromTable, SchemeMeta};
///
/// // Nyström's fourth-order method, typed anew
/// const RKN4: NystromTable<3> = NystromTable::new(
///     SchemeMeta::new("rkn4", "Nystrom 4", 4),
///     [0.0, 0.5, 1.0],
///     [[0.0; 3], [0.125, 0.0, 0.0], [0.0, 0.5, 0.0]],
///     [1.0 / 6.0, 1.0 / 3.0, 0.0],
///     [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
///     None,
/// );
/// let c = conditions::nystrom(&RKN4)?;
/// assert!(c.main.confirms(4));
/// assert!(c.embedded.is_none());
///
/// // Dormand and Prince's pair: sixth order, its estimate fourth
/// let c = conditions::nystrom(&stepladder::scheme::DPRKN6)?;
/// assert!(c.main.confirms(6));
/// assert!(c.embedded.unwrap().confirms(4));
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// As [`nystrom_up_to`], with the claimed order plus one the degree.
pub fn nystrom<const S: usize>(table: &NystromTable<S>) -> Result<NystromConditions, Error> {
    nystrom_up_to(table, table.meta.order as usize + 1)
}

/// A Runge-Kutta-Nyström tableau's conditions for `q'' = a(q)` through
/// `h^degree`, for the main solution and the embedded one. The stages use
/// `a`'s strict lower triangle (explicit stages).
///
/// ```
/// use stepladder::conditions;
/// use stepladder::scheme::DPRKN8;
///
/// let c = conditions::nystrom_up_to(&DPRKN8, 9)?;
/// assert_eq!(c.main.order(), 8);
/// assert_eq!(c.embedded.unwrap().order(), 6);
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::InvalidTable`] for a tableau with no stages, a coefficient that
/// is not finite or coefficients so large that the series overflow;
/// [`Error::InvalidParameter`] for a degree outside
/// `1..=NYSTROM_MAX_DEGREE`.
pub fn nystrom_up_to<const S: usize>(
    table: &NystromTable<S>,
    degree: usize,
) -> Result<NystromConditions, Error> {
    if !(1..=NYSTROM_MAX_DEGREE).contains(&degree) {
        return Err(Error::InvalidParameter {
            name: "degree",
            value: degree as f64,
            expected: "a power of h from 1 to NYSTROM_MAX_DEGREE = 13 (a claimed order up to 12)",
        });
    }
    if S == 0 {
        return Err(Error::InvalidTable(format!(
            "{}: a tableau needs at least one stage",
            table.meta.id
        )));
    }
    let tableau = |b_bar: &[f64; S], b: &[f64; S]| taylor::Tableau {
        c: table.c.to_vec(),
        a: table.a.iter().map(|row| row.to_vec()).collect(),
        b_bar: b_bar.to_vec(),
        b: b.to_vec(),
    };
    let check = |t: taylor::Tableau| -> Result<Conditions, Error> {
        let coefficients = t.c.iter().chain(t.a.iter().flatten()).chain(&t.b_bar);
        if let Some(x) = coefficients.chain(&t.b).find(|x| !x.is_finite()) {
            return Err(Error::InvalidTable(format!(
                "{}: the coefficient {x} is not finite",
                table.meta.id
            )));
        }
        finite(taylor::defects(&taylor::Method::Nystrom(t), degree))
    };
    Ok(NystromConditions {
        main: check(tableau(&table.b_bar, &table.b))?,
        embedded: table
            .embedded
            .map(|e| check(tableau(&e.b_bar, &e.b)))
            .transpose()?,
    })
}

/// A Runge-Kutta tableau's Butcher tree conditions through order `degree`:
/// `a` the Runge-Kutta matrix (the whole matrix, so implicit tableaux too),
/// `b` the weights; the nodes enter as the row sums of `a`.
///
/// ```
/// use stepladder::conditions;
///
/// // the classical fourth-order method
/// let a = [
///     [0.0, 0.0, 0.0, 0.0],
///     [0.5, 0.0, 0.0, 0.0],
///     [0.0, 0.5, 0.0, 0.0],
///     [0.0, 0.0, 1.0, 0.0],
/// ];
/// let b = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];
/// let c = conditions::runge_kutta(&a, &b, 5)?;
/// assert_eq!(c.order(), 4);
/// assert!(c.by_degree.confirms(4));
/// assert_eq!(c.trees.len(), 1 + 1 + 2 + 4 + 9);
/// # Ok::<(), stepladder::error::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::InvalidTable`] for no stages, a coefficient that is not finite
/// or coefficients so large that the weights overflow;
/// [`Error::InvalidParameter`] for a degree outside `1..=MAX_DEGREE`.
pub fn runge_kutta<const S: usize>(
    a: &[[f64; S]; S],
    b: &[f64; S],
    degree: usize,
) -> Result<RungeKuttaConditions, Error> {
    check_degree(degree)?;
    if S == 0 {
        return Err(Error::InvalidTable(
            "a tableau needs at least one stage".into(),
        ));
    }
    if let Some(x) = a.iter().flatten().chain(b).find(|x| !x.is_finite()) {
        return Err(Error::InvalidTable(format!(
            "the coefficient {x} is not finite"
        )));
    }
    let rows: Vec<Vec<f64>> = a.iter().map(|row| row.to_vec()).collect();
    let trees = trees::defects(&rows, b, degree);
    let all: Vec<Defect> = trees.iter().map(|t| t.defect).collect();
    finite(all)?;
    let by_degree = (1..=degree)
        .filter_map(|k| {
            trees
                .iter()
                .map(|t| t.defect)
                .filter(|d| d.degree == k)
                .max_by(|x, y| x.ratio().total_cmp(&y.ratio()))
        })
        .collect();
    Ok(RungeKuttaConditions {
        by_degree: Conditions { defects: by_degree },
        trees,
    })
}

fn check_degree(degree: usize) -> Result<(), Error> {
    if (1..=MAX_DEGREE).contains(&degree) {
        Ok(())
    } else {
        Err(Error::InvalidParameter {
            name: "degree",
            value: degree as f64,
            expected: "a power of h from 1 to MAX_DEGREE = 9 (a claimed order up to 8)",
        })
    }
}

fn check_flows(flows: &[(Flow, f64)]) -> Result<(), Error> {
    if flows.is_empty() {
        return Err(Error::InvalidTable(
            "a splitting needs at least one flow".into(),
        ));
    }
    match flows.iter().position(|f| !f.1.is_finite()) {
        Some(i) => Err(Error::InvalidTable(format!(
            "flow {i} ({:?}) has the weight {}: every weight must be finite",
            flows[i].0, flows[i].1
        ))),
        None => Ok(()),
    }
}

fn overflow() -> Error {
    Error::InvalidTable("the coefficients are so large that the series overflow doubles".into())
}

/// The defects as [`Conditions`], or an error if the evaluation overflowed
/// (an infinite allowance would let any defect hold).
fn finite(defects: Vec<Defect>) -> Result<Conditions, Error> {
    if defects
        .iter()
        .all(|d| d.value.is_finite() && d.allowance.is_finite() && d.scale.is_finite())
    {
        Ok(Conditions { defects })
    } else {
        Err(overflow())
    }
}

#[cfg(test)]
mod tests;
