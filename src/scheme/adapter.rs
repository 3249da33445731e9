//! The shapes integrators come in, adapted to a [`BlackBox`]: a first-order
//! system on `y = [q, v]`, a step on canonical `(q, p)`, and a step on the
//! integrator's own vector type. Each constructor writes the copy-in, call,
//! copy-out glue once, so that a wrapper is the call to the integrator and
//! nothing else.
//!
//! The vector types an adapter hands to the step implement [`Vector`]:
//! `Vec<T>`, nalgebra's `SVector` and `DVector` (of the nalgebra this crate
//! re-exports), and ndarray's `Array1` with the `ndarray` feature. A heap
//! vector is allocated afresh each step, as the integrator itself would;
//! `SVector` allocates nothing. A vector type this crate cannot implement
//! [`Vector`] for (another nalgebra version's) goes through
//! [`Shape::first_order_on_slices`], lending its elements as slices: no
//! copy per force call. A fixed-size type of another length than the
//! scene's state fails the first step with [`StepFailure::Unfit`], naming
//! the type and the length.

use super::SchemeMeta;
use super::StepFailure;
use super::black_box::{BlackBox, BlackBoxStep, Float, Force, StepReturn};
use nalgebra::{DVector, SVector};

/// A vector type an integrator works on: contiguous storage of `Scalar`s
/// that the adapters can make, read and write as a slice.
pub trait Vector: Sized {
    /// The element type.
    type Scalar: Float;
    /// A vector of `len` zeros, or `None` when the type's length is fixed
    /// and differs.
    fn zeros(len: usize) -> Option<Self>;
    /// The elements.
    fn as_slice(&self) -> &[Self::Scalar];
    /// The elements, writable.
    fn as_mut_slice(&mut self) -> &mut [Self::Scalar];
}

impl<T: Float> Vector for Vec<T> {
    type Scalar = T;
    fn zeros(len: usize) -> Option<Self> {
        Some(vec![T::default(); len])
    }
    fn as_slice(&self) -> &[T] {
        self
    }
    fn as_mut_slice(&mut self) -> &mut [T] {
        self
    }
}

impl<T: Float, const N: usize> Vector for SVector<T, N> {
    type Scalar = T;
    fn zeros(len: usize) -> Option<Self> {
        (len == N).then(|| SVector::from_element(T::default()))
    }
    fn as_slice(&self) -> &[T] {
        nalgebra::Matrix::as_slice(self)
    }
    fn as_mut_slice(&mut self) -> &mut [T] {
        nalgebra::Matrix::as_mut_slice(self)
    }
}

impl<T: Float> Vector for DVector<T> {
    type Scalar = T;
    fn zeros(len: usize) -> Option<Self> {
        Some(DVector::from_element(len, T::default()))
    }
    fn as_slice(&self) -> &[T] {
        nalgebra::Matrix::as_slice(self)
    }
    fn as_mut_slice(&mut self) -> &mut [T] {
        nalgebra::Matrix::as_mut_slice(self)
    }
}

#[cfg(feature = "ndarray")]
impl<T: Float> Vector for ndarray::Array1<T> {
    type Scalar = T;
    fn zeros(len: usize) -> Option<Self> {
        Some(ndarray::Array1::from_elem(len, T::default()))
    }
    fn as_slice(&self) -> &[T] {
        // the inherent method lives on `ArrayRef` (ndarray 0.17), which the
        // array derefs to; `ArrayBase::as_slice` would name this trait method
        ndarray::ArrayRef::as_slice(self)
            .expect("stepladder: an Array1 handed back by the step must be contiguous")
    }
    fn as_mut_slice(&mut self) -> &mut [T] {
        ndarray::ArrayBase::as_slice_mut(self)
            .expect("stepladder: an Array1 handed back by the step must be contiguous")
    }
}

/// The right-hand side of a first-order system, `f(y, dy)`: writes
/// `dy/dt` at `y` into `dy`. The scenes are autonomous, so it takes no time.
pub type Rhs<'a, V> = dyn Fn(&V, &mut V) + 'a;

/// The force on the integrator's own vector type: `force(q, a)` writes the
/// acceleration at `q` into `a`.
pub type VectorForce<'a, V> = dyn Fn(&V, &mut V) + 'a;

/// The two halves of Hamilton's equations for `H = p^T M^-1 p / 2 + V(q)`
/// with a diagonal mass matrix, as a `(q, p)` integrator asks for them.
pub struct Hamiltonian<'a, V: Vector> {
    masses: &'a [f64],
    force: &'a Force<'a, V::Scalar>,
}

impl<V: Vector> Hamiltonian<'_, V> {
    /// `dq/dt = dH/dp = M^-1 p` at `p`, into `out`.
    pub fn dq_dt(&self, p: &V, out: &mut V) {
        for (i, (o, &p)) in out.as_mut_slice().iter_mut().zip(p.as_slice()).enumerate() {
            *o = V::Scalar::from_f64(p.to_f64() / mass(self.masses, i));
        }
    }

    /// `dp/dt = -dV/dq = M a(q)` at `q`, into `out`: one force evaluation.
    pub fn dp_dt(&self, q: &V, out: &mut V) {
        (self.force)(q.as_slice(), out.as_mut_slice());
        for (i, o) in out.as_mut_slice().iter_mut().enumerate() {
            *o = V::Scalar::from_f64(o.to_f64() * mass(self.masses, i));
        }
    }
}

/// The mass of coordinate `i`: one when `masses` is empty (unit masses),
/// whose length is otherwise checked against the scene's dimension.
fn mass(masses: &[f64], i: usize) -> f64 {
    masses.get(i).copied().unwrap_or(1.0)
}

/// A fresh `V` of `len` elements, or the failure naming the mismatch (the
/// step's vector type cannot hold the scene's state: a fixed-size type of
/// the wrong length).
fn fresh<V: Vector>(len: usize, what: &str) -> Result<V, StepFailure> {
    V::zeros(len).ok_or_else(|| StepFailure::Unfit {
        message: format!(
            "the {what} vector type `{}` cannot hold the {len} numbers the scene needs",
            std::any::type_name::<V>()
        ),
    })
}

/// A scratch slice of `len` elements for the call `f`: on the stack up to
/// [`STACK_LEN`], on the heap (once per step) beyond.
fn with_scratch<T: Float, R>(len: usize, f: impl FnOnce(&mut [T]) -> R) -> R {
    if len <= STACK_LEN {
        f(&mut [T::default(); STACK_LEN][..len])
    } else {
        f(&mut vec![T::default(); len])
    }
}

/// Up to 32 bodies in three dimensions, `[q, v]` on the stack.
const STACK_LEN: usize = 192;

/// The shapes an integrator's step comes in, each turned into a step on the
/// scene's position and velocity slices that keeps `K` between steps: the
/// pieces that [`BlackBox::stateful`] and [`BlackBox::implicit`] take, so
/// that shape, kept state and solve reporting combine freely. A shape's
/// step returns what the wrapped step returns (nothing, a [`super::Solve`],
/// or a `Result`), and fails with [`StepFailure::Unfit`] where its vector
/// type cannot hold the scene's state. [`BlackBox::first_order`],
/// [`BlackBox::canonical`] and [`BlackBox::on_vectors`] are the shapes with
/// nothing kept.
///
/// ```
/// use stepladder::guard;
/// use stepladder::scene::KeplerCircular;
/// use stepladder::scheme::{BlackBox, Force, Rk4, Scheme, Shape};
///
/// /// An integrator object on first-order systems over slices, with a
/// /// cache it keeps between steps (here: the step count).
/// #[derive(Clone, Default)]
/// struct TheirRk4 { steps: u64 }
/// impl TheirRk4 {
///     fn step(&mut self, y: &mut [f64], h: f64, f: &dyn Fn(&[f64], &mut [f64])) {
///         let n = y.len();
///         let mut k = vec![vec![0.0; n]; 4];
///         let mut stage = y.to_vec();
///         for s in 0..4 {
///             if s > 0 {
///                 let c = if s == 3 { 1.0 } else { 0.5 };
///                 stage = (0..n).map(|i| y[i] + c * h * k[s - 1][i]).collect();
///             }
///             f(&stage, &mut k[s]);
///         }
///         for i in 0..n {
///             y[i] += h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
///         }
///         self.steps += 1;
///     }
/// }
/// let theirs = BlackBox::stateful(
///     *Rk4.meta(),
///     TheirRk4::default,
///     Shape::first_order_on_slices(|rk: &mut TheirRk4, y: &mut [f64], h: f64, f: &Force<f64>| {
///         rk.step(y, h, f)
///     }),
/// );
/// guard::assert_order(&theirs, &KeplerCircular);
/// guard::assert_evaluations(&theirs, &KeplerCircular);
/// ```
pub struct Shape;

// The returned step's type is spelled out in full: it is what
// `BlackBox::stateful` and `BlackBox::implicit` take, and a user reads it.
#[allow(clippy::type_complexity)]
impl Shape {
    /// A step of a first-order system `y' = f(y)` on `y = [q, v]` of the
    /// integrator's vector type `V`: `step(kept, y, h, f)`, with
    /// `f(y) = [v, a(q)]` (one force evaluation per call).
    pub fn first_order<T, K, V, S, O, R>(
        step: S,
    ) -> impl Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> Result<R, StepFailure>
    where
        T: Float,
        V: Vector<Scalar = T>,
        S: Fn(&mut K, &mut V, T, &Rhs<'_, V>) -> O,
        O: StepReturn<R>,
    {
        move |kept: &mut K, q: &mut [T], v: &mut [T], h: T, force: &Force<'_, T>| {
            let d = q.len();
            let mut y: V = fresh(2 * d, "first-order")?;
            y.as_mut_slice()[..d].copy_from_slice(q);
            y.as_mut_slice()[d..].copy_from_slice(v);
            let f = |y: &V, dy: &mut V| first_order_rhs(force, y.as_slice(), dy.as_mut_slice());
            let out = step(kept, &mut y, h, &f).into_step()?;
            q.copy_from_slice(&y.as_slice()[..d]);
            v.copy_from_slice(&y.as_slice()[d..]);
            Ok(out)
        }
    }

    /// A step of a first-order system on slices, for an integrator whose
    /// right-hand side takes `&[T]` (or any vector type that lends its
    /// elements as a slice, such as another nalgebra version's): `step(kept,
    /// y, h, f)` with `f(y, dy)` on slices of `y`'s length. Nothing is
    /// copied per force call, and nothing allocated per step up to 96
    /// coordinates.
    pub fn first_order_on_slices<T, K, S, O, R>(
        step: S,
    ) -> impl Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> Result<R, StepFailure>
    where
        T: Float,
        S: Fn(&mut K, &mut [T], T, &Force<'_, T>) -> O,
        O: StepReturn<R>,
    {
        move |kept: &mut K, q: &mut [T], v: &mut [T], h: T, force: &Force<'_, T>| {
            let d = q.len();
            with_scratch(2 * d, |y: &mut [T]| {
                y[..d].copy_from_slice(q);
                y[d..].copy_from_slice(v);
                let f = |y: &[T], dy: &mut [T]| first_order_rhs(force, y, dy);
                let out = step(kept, y, h, &f).into_step()?;
                q.copy_from_slice(&y[..d]);
                v.copy_from_slice(&y[d..]);
                Ok(out)
            })
        }
    }

    /// A step on canonical coordinates `(q, p)` with a diagonal mass
    /// matrix: `masses` per coordinate (empty for unit masses), `p = M v`.
    /// `step(kept, q, p, h, hamiltonian)` advances by one step, calling
    /// [`Hamiltonian::dq_dt`] and [`Hamiltonian::dp_dt`] (one force
    /// evaluation) for Hamilton's equations. A `masses` whose length is not
    /// the scene's dimension fails the step with [`StepFailure::Unfit`].
    pub fn canonical<T, K, V, S, O, R>(
        masses: &[f64],
        step: S,
    ) -> impl Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> Result<R, StepFailure>
    where
        T: Float,
        V: Vector<Scalar = T>,
        S: Fn(&mut K, &mut V, &mut V, T, &Hamiltonian<'_, V>) -> O,
        O: StepReturn<R>,
    {
        let masses = masses.to_vec();
        move |kept: &mut K, q: &mut [T], v: &mut [T], h: T, force: &Force<'_, T>| {
            let masses = masses.as_slice();
            let d = q.len();
            if !(masses.is_empty() || masses.len() == d) {
                return Err(StepFailure::Unfit {
                    message: format!(
                        "{} masses given for a scene of dimension {d} (one per coordinate, \
                         or none for unit masses)",
                        masses.len()
                    ),
                });
            }
            let (mut qv, mut p): (V, V) = (fresh(d, "position")?, fresh(d, "momentum")?);
            qv.as_mut_slice().copy_from_slice(q);
            for (i, (p, &v)) in p.as_mut_slice().iter_mut().zip(v.iter()).enumerate() {
                *p = T::from_f64(mass(masses, i) * v.to_f64());
            }
            let hamiltonian = Hamiltonian { masses, force };
            let out = step(kept, &mut qv, &mut p, h, &hamiltonian).into_step()?;
            q.copy_from_slice(qv.as_slice());
            for (i, (v, &p)) in v.iter_mut().zip(p.as_slice()).enumerate() {
                *v = T::from_f64(p.to_f64() / mass(masses, i));
            }
            Ok(out)
        }
    }

    /// A step on the integrator's own vector type: `step(kept, q, v, h,
    /// force)` as for [`BlackBox::new`], with `q`, `v` and the force's
    /// arguments of type `V`.
    pub fn on_vectors<T, K, V, S, O, R>(
        step: S,
    ) -> impl Fn(&mut K, &mut [T], &mut [T], T, &Force<'_, T>) -> Result<R, StepFailure>
    where
        T: Float,
        V: Vector<Scalar = T>,
        S: Fn(&mut K, &mut V, &mut V, T, &VectorForce<'_, V>) -> O,
        O: StepReturn<R>,
    {
        move |kept: &mut K, q: &mut [T], v: &mut [T], h: T, force: &Force<'_, T>| {
            let d = q.len();
            let (mut qv, mut vv): (V, V) = (fresh(d, "position")?, fresh(d, "velocity")?);
            qv.as_mut_slice().copy_from_slice(q);
            vv.as_mut_slice().copy_from_slice(v);
            let f = |q: &V, a: &mut V| force(q.as_slice(), a.as_mut_slice());
            let out = step(kept, &mut qv, &mut vv, h, &f).into_step()?;
            q.copy_from_slice(qv.as_slice());
            v.copy_from_slice(vv.as_slice());
            Ok(out)
        }
    }
}

/// `dy = [v, a(q)]` at `y = [q, v]`: one force evaluation.
fn first_order_rhs<T: Float>(force: &Force<'_, T>, y: &[T], dy: &mut [T]) {
    let d = y.len() / 2;
    dy[..d].copy_from_slice(&y[d..]);
    force(&y[..d], &mut dy[d..]);
}

impl<T: Float> BlackBox<T, ()> {
    /// Wraps a step of a first-order system `y' = f(y)` on `y = [q, v]`:
    /// `step(y, h, f)` advances `y` by one step of size `h`; the adapter
    /// supplies `f(y) = [v, a(q)]` (one force evaluation per call).
    ///
    /// ```
    /// use stepladder::guard;
    /// use stepladder::scene::KeplerCircular;
    /// use stepladder::scheme::{BlackBox, Rhs, Rk4, Scheme};
    ///
    /// /// Somebody's classical Runge-Kutta on `Vec<f64>`.
    /// fn rk4(y: &mut Vec<f64>, h: f64, f: &Rhs<Vec<f64>>) {
    ///     let n = y.len();
    ///     let mut k = vec![vec![0.0; n]; 4];
    ///     let mut stage = y.clone();
    ///     for s in 0..4 {
    ///         if s > 0 {
    ///             let c = if s == 3 { 1.0 } else { 0.5 };
    ///             stage = (0..n).map(|i| y[i] + c * h * k[s - 1][i]).collect();
    ///         }
    ///         f(&stage, &mut k[s]);
    ///     }
    ///     for i in 0..n {
    ///         y[i] += h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
    ///     }
    /// }
    /// let theirs = BlackBox::first_order(*Rk4.meta(), rk4);
    /// guard::assert_order(&theirs, &KeplerCircular);
    /// guard::assert_evaluations(&theirs, &KeplerCircular);
    /// ```
    pub fn first_order<V, S>(
        meta: SchemeMeta,
        step: S,
    ) -> BlackBox<T, impl BlackBoxStep<T, Kept = ()>>
    where
        V: Vector<Scalar = T>,
        S: Fn(&mut V, T, &Rhs<'_, V>),
    {
        let step =
            Shape::first_order(move |_: &mut (), y: &mut V, h: T, f: &Rhs<'_, V>| step(y, h, f));
        BlackBox::stateful(meta, || (), step)
    }

    /// Wraps a step on canonical coordinates `(q, p)` with a diagonal mass
    /// matrix: `masses` per coordinate (empty for unit masses), `p = M v`.
    /// `step(q, p, h, hamiltonian)` advances by one step, calling
    /// [`Hamiltonian::dq_dt`] and [`Hamiltonian::dp_dt`] (one force
    /// evaluation) for Hamilton's equations.
    ///
    /// ```
    /// use stepladder::guard;
    /// use stepladder::scene::KeplerCircular;
    /// use stepladder::scheme::{BlackBox, Hamiltonian, Scheme, EULER_CROMER};
    /// use stepladder::nalgebra::Vector2;
    ///
    /// /// Symplectic Euler on (q, p), kick first, on nalgebra vectors.
    /// fn kick_drift(q: &mut Vector2<f64>, p: &mut Vector2<f64>, h: f64, ham: &Hamiltonian<Vector2<f64>>) {
    ///     let mut rate = Vector2::zeros();
    ///     ham.dp_dt(q, &mut rate);
    ///     *p += h * rate;
    ///     ham.dq_dt(p, &mut rate);
    ///     *q += h * rate;
    /// }
    /// let theirs = BlackBox::canonical(*EULER_CROMER.meta(), &[], kick_drift);
    /// guard::assert_order(&theirs, &KeplerCircular);
    /// guard::assert_symplectic(&theirs, &KeplerCircular);
    /// ```
    pub fn canonical<V, S>(
        meta: SchemeMeta,
        masses: &[f64],
        step: S,
    ) -> BlackBox<T, impl BlackBoxStep<T, Kept = ()>>
    where
        V: Vector<Scalar = T>,
        S: Fn(&mut V, &mut V, T, &Hamiltonian<'_, V>),
    {
        let step = Shape::canonical(
            masses,
            move |_: &mut (), q: &mut V, p: &mut V, h: T, ham: &Hamiltonian<'_, V>| {
                step(q, p, h, ham)
            },
        );
        BlackBox::stateful(meta, || (), step)
    }

    /// Wraps a step on the integrator's own vector type:
    /// `step(q, v, h, force)` as for [`BlackBox::new`], with `q`, `v` and
    /// the force's arguments of type `V`.
    ///
    /// ```
    /// use stepladder::guard;
    /// use stepladder::scene::KeplerCircular;
    /// use stepladder::scheme::{BlackBox, Scheme, VectorForce, VELOCITY_VERLET};
    /// use stepladder::nalgebra::DVector;
    ///
    /// fn verlet(q: &mut DVector<f64>, v: &mut DVector<f64>, h: f64, force: &VectorForce<DVector<f64>>) {
    ///     let mut a = DVector::zeros(q.len());
    ///     force(q, &mut a);
    ///     *v += 0.5 * h * &a;
    ///     *q += h * &*v;
    ///     force(q, &mut a);
    ///     *v += 0.5 * h * &a;
    /// }
    /// let mut claims = *VELOCITY_VERLET.meta();
    /// claims.force_evaluations = 2; // it does not reuse the last force
    /// let theirs = BlackBox::on_vectors(claims, verlet);
    /// guard::assert_order(&theirs, &KeplerCircular);
    /// guard::assert_evaluations(&theirs, &KeplerCircular);
    /// ```
    pub fn on_vectors<V, S>(
        meta: SchemeMeta,
        step: S,
    ) -> BlackBox<T, impl BlackBoxStep<T, Kept = ()>>
    where
        V: Vector<Scalar = T>,
        S: Fn(&mut V, &mut V, T, &VectorForce<'_, V>),
    {
        let step = Shape::on_vectors(
            move |_: &mut (), q: &mut V, v: &mut V, h: T, f: &VectorForce<'_, V>| step(q, v, h, f),
        );
        BlackBox::stateful(meta, || (), step)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Harmonic, KeplerCircular, Scene};
    use crate::scheme::{EULER_CROMER, Rk4, Scheme, StepFailure, VELOCITY_VERLET};
    use crate::state::State;
    use nalgebra::Vector2;

    fn run<M: Scheme, S: Scene<D>, const D: usize>(m: &M, scene: &S, h: f64, n: usize) -> State<D> {
        let mut c = m.start(scene, &scene.initial(), h);
        for _ in 0..n {
            m.step(scene, &mut c, h).unwrap();
        }
        m.state(&c, h)
    }

    /// Classical RK4 on a first-order system, written as the textbook does.
    fn rk4(y: &mut Vec<f64>, h: f64, f: &Rhs<Vec<f64>>) {
        let n = y.len();
        let (mut k1, mut k2, mut k3, mut k4) =
            (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let at =
            |k: &Vec<f64>, c: f64| -> Vec<f64> { (0..n).map(|i| y[i] + c * h * k[i]).collect() };
        f(y, &mut k1);
        f(&at(&k1, 0.5), &mut k2);
        f(&at(&k2, 0.5), &mut k3);
        f(&at(&k3, 1.0), &mut k4);
        for i in 0..n {
            y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }

    /// An ndarray step goes through the adapter's copy-in and copy-out: the
    /// same kick-drift-kick as the catalogue's, so the same states to
    /// round-off (it recomputes the first force, which only costs).
    #[cfg(feature = "ndarray")]
    #[test]
    fn an_ndarray_velocity_verlet_is_the_catalogue_one_to_round_off() {
        use ndarray::Array1;
        fn verlet(
            q: &mut Array1<f64>,
            v: &mut Array1<f64>,
            h: f64,
            force: &VectorForce<Array1<f64>>,
        ) {
            let mut a = Array1::zeros(q.len());
            force(q, &mut a);
            v.scaled_add(0.5 * h, &a);
            q.scaled_add(h, v);
            force(q, &mut a);
            v.scaled_add(0.5 * h, &a);
        }
        let mut claims = *VELOCITY_VERLET.meta();
        claims.force_evaluations = 2;
        let theirs = BlackBox::on_vectors(claims, verlet);
        let (a, b) = (
            run(&theirs, &KeplerCircular, 1e-3, 1000),
            run(&VELOCITY_VERLET, &KeplerCircular, 1e-3, 1000),
        );
        assert!((a.q - b.q).amax() < 1e-12, "{} vs {}", a.q, b.q);
        assert!((a.v - b.v).amax() < 1e-11, "{} vs {}", a.v, b.v);
    }

    #[test]
    fn a_first_order_rk4_is_the_catalogue_rk4_to_round_off() {
        // the same stages in another arrangement: equal to a few ulps
        let theirs = BlackBox::first_order(*Rk4.meta(), rk4);
        let (a, b) = (
            run(&theirs, &KeplerCircular, 0.01, 30),
            run(&Rk4, &KeplerCircular, 0.01, 30),
        );
        let d = (a.q - b.q).amax().max((a.v - b.v).amax());
        assert!(d < 1e-13, "first-order RK4 against the catalogue's: {d:e}");
        // and not trivially: a third of an orbit moves the planet by ~1.7 AU
        assert!((a.q - KeplerCircular.initial().q).amax() > 1.0);
    }

    #[test]
    fn a_first_order_rhs_that_forgot_nothing_supplies_both_halves() {
        // Euler on y' = f(y): q gains h v, v gains h a(q)
        let euler = BlackBox::first_order(
            *crate::scheme::Euler.meta(),
            |y: &mut Vec<f64>, h: f64, f: &Rhs<Vec<f64>>| {
                let mut dy = vec![0.0; y.len()];
                f(y, &mut dy);
                for (y, dy) in y.iter_mut().zip(&dy) {
                    *y += h * dy;
                }
            },
        );
        let osc = Harmonic::default();
        let s0 = osc.initial();
        let s = run(&euler, &osc, 0.1, 1);
        let a = osc.acceleration(&s0.q);
        assert_eq!(s.q[0], s0.q[0] + 0.1 * s0.v[0]);
        assert_eq!(s.v[0], s0.v[0] + 0.1 * a[0]);
    }

    fn kick_drift(
        q: &mut Vector2<f64>,
        p: &mut Vector2<f64>,
        h: f64,
        ham: &Hamiltonian<Vector2<f64>>,
    ) {
        let mut rate = Vector2::zeros();
        ham.dp_dt(q, &mut rate);
        *p += h * rate;
        ham.dq_dt(p, &mut rate);
        *q += h * rate;
    }

    #[test]
    fn canonical_coordinates_with_masses_give_the_same_motion() {
        // p = m v and back: the masses cancel up to rounding
        let unit = BlackBox::canonical(*EULER_CROMER.meta(), &[], kick_drift);
        let heavy = BlackBox::canonical(*EULER_CROMER.meta(), &[3.0, 7.0], kick_drift);
        let (a, b) = (
            run(&unit, &KeplerCircular, 0.01, 100),
            run(&heavy, &KeplerCircular, 0.01, 100),
        );
        let c = run(&EULER_CROMER, &KeplerCircular, 0.01, 100);
        assert_eq!(
            a, c,
            "unit masses: the catalogue's symplectic Euler bit for bit"
        );
        let d = (a.q - b.q).amax().max((a.v - b.v).amax());
        assert!(
            d > 0.0 && d < 1e-12,
            "masses 3 and 7 against unit masses: {d:e}"
        );
    }

    /// The message of the first step's failure on `scene`.
    fn first_failure<M: Scheme, S: Scene<D>, const D: usize>(m: &M, scene: &S) -> String {
        let mut c = m.start(scene, &scene.initial(), 0.01);
        match m.step(scene, &mut c, 0.01) {
            Err(StepFailure::Unfit { message }) => message,
            other => panic!("expected an unfit step, got {other:?}"),
        }
    }

    #[test]
    fn the_wrong_number_of_masses_is_an_error_naming_it() {
        let bb = BlackBox::canonical(*EULER_CROMER.meta(), &[1.0, 2.0, 3.0], kick_drift);
        let message = first_failure(&bb, &KeplerCircular);
        assert!(
            message.contains("3 masses given for a scene of dimension 2"),
            "{message}"
        );
    }

    #[test]
    fn a_fixed_vector_of_the_wrong_length_is_an_error_naming_it() {
        // y = [q, v] of the orbit has 4 numbers, a Vector2 holds 2
        let bb = BlackBox::first_order(
            *Rk4.meta(),
            |_: &mut Vector2<f64>, _: f64, _: &Rhs<Vector2<f64>>| {},
        );
        let message = first_failure(&bb, &KeplerCircular);
        assert!(
            message.contains("cannot hold the 4 numbers the scene needs"),
            "{message}"
        );
        assert!(
            message.contains("Matrix<f64"),
            "the type is named: {message}"
        );
        // and on a scene it fits (the oscillator's y has 2 numbers) it runs
        let mut c = bb.start(&Harmonic::default(), &Harmonic::default().initial(), 0.01);
        assert_eq!(bb.step(&Harmonic::default(), &mut c, 0.01), Ok(()));
    }

    #[test]
    fn a_guard_on_a_vector_of_the_wrong_length_fails_with_the_mismatch() {
        let bb = BlackBox::on_vectors(
            *VELOCITY_VERLET.meta(),
            |_: &mut Vector2<f64>, _: &mut Vector2<f64>, _: f64, _: &VectorForce<Vector2<f64>>| {},
        );
        let record = crate::study::claims(&bb, &Harmonic::default()).unwrap();
        let order = &record.verdicts[0];
        assert!(order.verdict.fails_a_guard(), "{order:?}");
        assert!(
            order.message.contains("cannot hold the 1 numbers"),
            "{}",
            order.message
        );
    }

    /// A first-order step kept between steps, on slices: the state it keeps
    /// is the scene's own (each run starts fresh), and the slice
    /// right-hand side is the adapter's `[v, a(q)]`.
    #[test]
    fn a_kept_first_order_step_on_slices_counts_its_own_steps_per_run() {
        let counted = BlackBox::stateful(
            *crate::scheme::Euler.meta(),
            || 0u32,
            Shape::first_order_on_slices(|n: &mut u32, y: &mut [f64], h: f64, f: &Force<f64>| {
                let mut dy = [0.0; 2];
                f(y, &mut dy);
                y[0] += h * dy[0];
                y[1] += h * dy[1];
                *n += 1;
                if *n > 3 {
                    return Err(StepFailure::NotConverged {
                        iterations: *n,
                        residual: 0.0,
                    });
                }
                Ok(())
            }),
        );
        let osc = Harmonic::default();
        let s0 = osc.initial();
        // one step: explicit Euler on y' = [v, a(q)]
        let s = run(&counted, &osc, 0.1, 1);
        assert_eq!(s.q[0], s0.q[0] + 0.1 * s0.v[0]);
        assert_eq!(s.v[0], s0.v[0] + 0.1 * osc.acceleration(&s0.q)[0]);
        // the kept count belongs to a run: three steps pass, the fourth fails
        let mut c = counted.start(&osc, &s0, 0.1);
        for _ in 0..3 {
            counted.step(&osc, &mut c, 0.1).unwrap();
        }
        assert!(counted.step(&osc, &mut c, 0.1).is_err());
        let mut fresh = counted.start(&osc, &s0, 0.1);
        assert_eq!(counted.step(&osc, &mut fresh, 0.1), Ok(()));
    }

    /// A first-order step on slices longer than the stack scratch (100
    /// coordinates, y of 200 > [`STACK_LEN`] = 192) is the same arithmetic
    /// on the heap.
    #[test]
    fn a_first_order_step_beyond_the_stack_scratch_runs() {
        let euler = |y: &mut [f64], h: f64, f: &Force<f64>| {
            let mut dy = vec![0.0; y.len()];
            f(y, &mut dy);
            for (y, dy) in y.iter_mut().zip(&dy) {
                *y += h * dy;
            }
        };
        let step = Shape::first_order_on_slices(
            move |_: &mut (), y: &mut [f64], h: f64, f: &Force<f64>| euler(y, h, f),
        );
        let (mut q, mut v) = (vec![1.0; 100], vec![0.5; 100]);
        let spring = |x: &[f64], a: &mut [f64]| {
            for (a, x) in a.iter_mut().zip(x) {
                *a = -x;
            }
        };
        step(&mut (), &mut q, &mut v, 0.1, &spring).unwrap();
        assert!(
            q.iter().all(|&q| q == 1.05) && v.iter().all(|&v| v == 0.4),
            "{q:?} {v:?}"
        );
    }

    #[test]
    fn a_step_on_dvectors_is_the_slice_step() {
        fn verlet(
            q: &mut DVector<f64>,
            v: &mut DVector<f64>,
            h: f64,
            force: &VectorForce<DVector<f64>>,
        ) {
            let mut a = DVector::zeros(q.len());
            force(q, &mut a);
            for i in 0..q.len() {
                v[i] += 0.5 * h * a[i];
                q[i] += h * v[i];
            }
            force(q, &mut a);
            for i in 0..q.len() {
                v[i] += 0.5 * h * a[i];
            }
        }
        let bb = BlackBox::on_vectors(*VELOCITY_VERLET.meta(), verlet);
        // same operations in the same order as the catalogue's: bit for bit
        assert_eq!(
            run(&bb, &KeplerCircular, 0.01, 1000),
            run(&VELOCITY_VERLET, &KeplerCircular, 0.01, 1000)
        );
    }
}
