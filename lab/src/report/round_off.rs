//! The report's round-off sections: floors against the step, and long runs
//! of exactly conserved quantities.

use super::markdown::{Table, opt, sci};
use crate::suite::round_off::{BrouwerRun, RoundoffRecords};
use std::fmt::Write as _;
use stepladder::internals::round_off::floor::{Floor, PairRecord, RoundoffRecord};
use stepladder::internals::round_off::longrun::LongrunRecord;

/// Both sections, as they appear in REPORT.md.
pub fn sections(records: &RoundoffRecords) -> String {
    let mut out = String::new();
    out.push_str("\n## Round-off floors\n\n");
    out.push_str(FLOORS_METHOD);
    for r in &records.floors {
        let _ = writeln!(
            out,
            "\n### {} ({} period{}, up to {} steps)\n",
            r.scene,
            r.periods,
            if r.periods == 1.0 { "" } else { "s" },
            r.max_steps
        );
        out.push_str(&floor_table(r));
        out.push('\n');
        out.push_str(&law_table(r));
    }
    out.push_str(FLOORS_EXPLAINED);
    out.push_str(
        "\nEvery pair, rung by rung, is on [a detail page](details/round-off-rungs.md).\n",
    );
    out.push_str("\n## Long runs: round-off growth\n\n");
    out.push_str(LONGRUN_METHOD);
    out.push_str(&longrun_table(&records.longrun));
    out.push_str(&longrun_explained(&records.longrun));
    out.push_str("\n## Brouwer's law: round-off optimal or not\n\n");
    out.push_str(BROUWER_METHOD);
    out.push_str(&brouwer_table(&records.brouwer));
    out.push_str(&brouwer_verdicts(&records.brouwer));
    out.push_str(BROUWER_EXPLAINED);
    out
}

const BROUWER_METHOD: &str = "An integrator is *round-off optimal* when its energy error \
over a long run is the random walk of the rounding it cannot avoid (Brouwer's law, \
`t^(1/2)`) and no more. Claimed for an integrator, it is judged by \
`stepladder::study::round_off_growth`: 16 runs of `2^20` steps of \
the outer solar system at `h = P/2000` (`P` the scene's period, Jupiter's; the \
truncation error of an eighth-order method is then some `1e-20` of the energy), started \
7919 steps apart, the energy read every 16 steps in double-double at the state plus the \
low parts a compensated scheme carries. `g` is the exponent of the variogram, the root \
mean square change of the relative energy error over a lag `L`, fitted over lags from \
`N/1024` to `N/8` with its jackknife interval over the runs: a random walk gives `1/2` \
at every lag, a drift `1`, a bounded error `0`. The claim passes when the interval lies \
inside [0.45, 0.55] and the walk per step, `rms(L)/sqrt(L)` at the longest lag, is below \
the floor of rounding every coordinate once a step, `u/sqrt(12) (sum (q_i dE/dq_i)^2 + \
sum v_i^4)^(1/2) / |E|` averaged along the runs (`u = eps/2`; a double `x` rounds by a \
uniform error of width `ulp(x) > u |x|`).\n\n";

const BROUWER_EXPLAINED: &str = "\nBoth runs are random walks: rounding to nearest is \
unbiased, and neither grows like `t`. What separates them is the size of the walk. The \
plain method rounds every coordinate at every step, and its walk is above the floor that \
one such rounding a step would give. With compensated sums, what each step loses is the \
rounding of its increments and of the force, about `h w` of a coordinate's: the walk is \
some `h w = 2 pi/2000` times smaller, and far below the floor. The energy has to be read \
in double-double to see it: read in doubles it rounds by about `1e-16` of itself at every \
reading, as much as the compensated walk's whole size after a million steps.\n";

/// One row per integrator of the Brouwer study.
pub fn brouwer_table(runs: &[BrouwerRun]) -> String {
    let mut t = Table::new(&[
        "integrator",
        "runs x steps",
        "h",
        "g",
        "95% interval",
        "walk per step",
        "rounding floor",
        "largest relative error",
        "round-off optimal",
    ]);
    for b in runs {
        let r = &b.record;
        t.row(vec![
            format!(
                "`{}`{}",
                r.scheme,
                if b.compensated { " compensated" } else { "" }
            ),
            format!("{} x {}", r.runs, r.steps),
            sci(r.h),
            opt(r.growth_exponent, |g| format!("{g:.3}")),
            r.ci95
                .map_or("-".into(), |[a, b]| format!("[{a:.3}, {b:.3}]")),
            sci(r.per_step),
            sci(r.rounding_floor),
            sci(r.max_relative_error),
            r.verdict.name().into(),
        ]);
    }
    t.render()
}

/// Each verdict's reason, as the study states it.
fn brouwer_verdicts(runs: &[BrouwerRun]) -> String {
    let mut out = String::from("\n");
    for b in runs {
        let _ = writeln!(
            out,
            "- `{}`{}: {}: {}.",
            b.record.scheme,
            if b.compensated { " compensated" } else { "" },
            b.record.verdict.name(),
            b.record.reason
        );
    }
    out
}

const FLOORS_METHOD: &str = "Each plain Verlet form runs beside its compensated-summation variant \
(the same map in exact arithmetic; position and velocity sums keep what rounding drops, \
by Knuth's TwoSum) over a ladder of steps halving from 1/8 of a period, until the plain \
scheme's error has failed twice in a row to improve on its smallest value, or the finest \
step allowed. `error` is the largest phase-space error against the exact solution at 4096 \
evenly spaced points of the run; `round-off` is the largest distance between the plain and \
the compensated solution, the plain scheme's round-off with truncation removed, measured \
even where truncation hides it. The floor is the smallest error reached; a scheme stops \
improving at the step of its floor when a finer step did worse.\n";

const FLOORS_EXPLAINED: &str = "\n### Why the floors are where they are\n\n\
With unit round-off `u = eps/2`, motion of size `A` and frequency `w`, and `N = T/h` steps \
in a run of length `T`:\n\n\
- **Velocity Verlet and leap-frog** round `q + h v` and `v + h a` to the precision of \
`q` and `v`: about `u A` per step, not magnified by the step. The flow turns such \
perturbations without growing them (on the orbit it also turns an energy error into a phase \
drift, which multiplies them by about `w T` without changing the law), so `N` unbiased \
roundings add up as a random walk, `u A N^(1/2)`: at fixed `T`, `h^(-1/2)`. A bias in the \
rounding would make it `u A N`, `h^(-1)`.\n\
- **The two-step form** computes `2 q(n) - q(n-1)` exactly (its operands are within a \
factor two of each other, so the subtraction is exact by Sterbenz's lemma), and then adds \
`h^2 a`, which loses its bits below the last bit of `q`: `u A` per step in the second \
difference, which is `h` times the velocity. A random walk of velocity kicks `u A / h` \
integrates to a position error `u A N^(1/2) / (h w) = u A N^(3/2) / (w T)`: at fixed \
`T`, `h^(-3/2)`, a whole power of `h` steeper, so the floor comes far earlier and higher. \
Its central-difference velocity, a rounded difference divided by `2 h`, adds `u A / h` \
at each read-out without accumulating.\n\
- **The compensated variants** lose only the rounding of the increments and of the force \
at the rounded position, `u h w A` per step: `u A h w N^(1/2)`, falling with `h`. What \
remains is what no summation can remove (the rounding of the output state and of the exact \
solution), a few `u A`.\n\n\
With the truncation error `C h^2`, `C h^2 + R h^(-g)` is smallest at \
`h* = (g R / 2C)^(1/(2+g))`, where it is `(1 + 2/g) C h*^2`: five times the truncation \
error for `g = 1/2`, 7/3 for `g = 3/2`. The law table fits `R` and `g` to the measured \
round-off and `C` to the compensated error, and compares the model's minimum with the \
floor the ladder found (`g` is also the exponent of `N`: at fixed `T`, `N` is \
proportional to `1/h`). Whatever the model's constants, a plain floor at step `h_f` is at \
least the truncation error there, less what round-off, random in direction, may cancel \
(at most half of an error that grows steadily along the run), while the compensated \
variant's error at `h_f` is its truncation alone and falls four-fold with each further \
halving: its floor is lower by at least `4^j / 2` when the ladder runs `j` rungs past the \
plain floor, which the tests assert.\n";

const LONGRUN_METHOD: &str = "Each Verlet form and its compensated variant runs 16 times \
from 16 evenly spaced points of the exact orbit, at 100 steps a period, following a \
quantity it conserves exactly in exact arithmetic, so that whatever the quantity does is \
round-off: on the oscillator the modified energy `v^2/2 + w^2 x^2 (1 - (h w)^2/4)/2`, \
which velocity Verlet's map conserves and which leap-frog and the two-step form conserve \
too, their synchronised velocities being velocity Verlet's in exact arithmetic; on the \
circular orbit the angular momentum `x v_y - y v_x`, which every kick (along `-r`) and \
every drift (along `v`) leaves unchanged. The true energy would not do: it oscillates by \
`(h w)^2/4 = 1e-3` of itself, far above any round-off. `g` is the exponent of the root \
mean square of `(Q - Q0)/Q0` over the runs, fitted over the last two decades of time \
(`t^(1/2)` for a random walk, `t` for biased rounding, `t^0` for an error that does not \
accumulate), with its jackknife standard error over the runs; one run alone would do \
poorly, a single random walk's exponent varying by 0.15 from one realisation to the next. \
`per step` is the final root mean square over `eps N^(1/2)`: a random walk's step in \
units of `eps`.\n\n";

/// The mean over one orbit of `f(phi)`, by the midpoint rule on `2^20`
/// phases (the binade step functions below jump at finitely many phases,
/// which this many points resolve to a few parts in a million).
fn orbit_mean(f: impl Fn(f64) -> f64) -> f64 {
    let n = 1u32 << 20;
    (0..n)
        .map(|k| f(std::f64::consts::TAU * (f64::from(k) + 0.5) / f64::from(n)))
        .sum::<f64>()
        / f64::from(n)
}

/// `4^floor(log2 |y|)`: the square of `y`'s ulp in units of `eps`.
fn binade_squared(y: f64) -> f64 {
    4f64.powf(y.abs().log2().floor())
}

/// The long-run random walks predicted from the roundings a step makes,
/// beside the oscillator's measured ones.
fn longrun_explained(records: &[LongrunRecord]) -> String {
    let find = |scheme: &str| {
        records
            .iter()
            .find(|r| r.scheme == scheme && r.scene == "harmonic" && !r.compensated)
    };
    let (Some(vv), Some(two_step)) = (find("velocity-verlet"), find("stormer-verlet")) else {
        return String::new();
    };
    // the oscillator at amplitude 1 and w = 1: h w is the step itself
    let hw = vv.h;
    let runs = vv.runs;
    // one rounding's variance over eps^2 is binade_squared / 12; the
    // modified energy moves by 2 delta cos phi (q) or 2 delta sin phi (v)
    let c_q = (orbit_mean(|p| p.cos().powi(2) * binade_squared(p.cos())) / 3.0).sqrt();
    let c_v = (orbit_mean(|p| p.sin().powi(2) * binade_squared(p.sin())) / 3.0).sqrt();
    let c_vv = (c_q * c_q + 4.0 * c_v * c_v).sqrt();
    let designed = orbit_mean(|p| p.sin().powi(2) * binade_squared(p.cos())) / (3.0 * hw * hw);
    let crossing = 4.0 / (15.0 * std::f64::consts::PI * hw);
    let c_two = (designed + crossing).sqrt();
    let spread = 100.0 / (2.0 * runs as f64).sqrt();
    format!(
        "\nA rounding of `y` errs by up to half an ulp, `eps 2^floor(log2 |y|) / 2`, with variance \
`eps^2 4^floor(log2 |y|) / 12`; on the oscillator (amplitude 1, `w = 1`) the binade is \
averaged over the orbital phase `phi`. A plain velocity Verlet step rounds `q` once, moving \
the modified energy by `2 delta cos phi` of itself, and `v` twice, by `2 delta sin phi`; \
the half-kick that ends a step and the one that starts the next add the same increment \
`h a / 2` to `v`, in the same binade nearly always, and round alike, so those two add \
coherently: `c^2 = c_q^2 + (2 c_v)^2`, `c_q^2 = <cos^2 phi 4^floor(log2 |cos phi|)> / 3` \
and `c_v` the same in `sin phi`, {c_vv:.2} `eps` a step, a random walk `{c_vv:.2} eps \
N^(1/2)`. The two-step form rounds `q(n+1)`, which moves the reconstructed velocity by \
`delta / h` and the modified energy by `2 delta sin phi / (h w)`: `<sin^2 phi \
4^floor(log2 |cos phi|)> / (3 (h w)^2)` in `eps^2` a step. Where `|q|` grows past a power \
of two `2^-j`, twice a period for each `j`, `2 q(n) - q(n-1)` leaves `q(n-1)`'s binade and \
is rounded as well, half an ulp squared on average, at a phase where `sin phi` is near 1: \
`4 / (15 pi h w)` more. Together {c_two:.2} `eps` a step at {per:.0} steps a period, \
{ratio:.1} times velocity Verlet's. A root mean square over {runs} runs is uncertain by \
about `1 / sqrt(2 x {runs})` = {spread:.0}%; measured over predicted, velocity Verlet \
{m_vv:.2} and the two-step form {m_two:.2} on the oscillator. Compensated summation leaves \
the rounding of the increments, `u h w` a step (`u = eps/2`): the same law, `h w` times \
smaller, beneath the rounding of the read-out state and of `Q` itself, a few `eps` that do \
not accumulate.\n",
        per = std::f64::consts::TAU / hw,
        ratio = c_two / c_vv,
        m_vv = vv.per_step_ulps / c_vv,
        m_two = two_step.per_step_ulps / c_two,
    )
}

/// One row per scheme: the floor and where it was reached.
pub fn floor_table(r: &RoundoffRecord) -> String {
    let mut t = Table::new(&[
        "scheme",
        "floor (smallest error)",
        "at h",
        "round-off reaches truncation at h",
        "stops improving",
    ]);
    let row = |t: &mut Table, f: &Option<Floor>, crossover: Option<f64>| {
        let Some(f) = f else {
            return;
        };
        t.row(vec![
            format!("`{}`", f.scheme),
            sci(f.floor),
            sci(f.h),
            opt(crossover, sci),
            if f.stopped {
                format!("at h = {}", sci(f.h))
            } else {
                "not within the ladder".into()
            },
        ]);
    };
    for p in &r.pairs {
        row(&mut t, &p.plain_floor, p.crossover_h);
        row(&mut t, &p.compensated_floor, None);
    }
    t.render()
}

/// One row per plain scheme: the fitted round-off law and the model's floor.
pub fn law_table(r: &RoundoffRecord) -> String {
    let mut t = Table::new(&[
        "scheme",
        "round-off ~ h^(-g): g",
        "theory g",
        "R",
        "truncation ~ h^p: p",
        "C",
        "model h*",
        "model floor",
        "floor / compensated floor",
    ]);
    for p in &r.pairs {
        let theory = if p.plain.starts_with("stormer") {
            "3/2"
        } else {
            "1/2"
        };
        t.row(vec![
            format!("`{}`", p.plain),
            opt(p.round_off_fit.map(|f| -f.slope), |g| {
                let f = p.round_off_fit.expect("present");
                format!("{g:.2} [{:.2}, {:.2}]", -f.ci95[1], -f.ci95[0])
            }),
            theory.into(),
            opt(p.round_off_fit.map(|f| f.intercept.exp()), sci),
            opt(p.truncation_fit.map(|f| f.slope), |x| format!("{x:.3}")),
            opt(p.truncation_fit.map(|f| f.intercept.exp()), sci),
            opt(p.predicted_h, sci),
            opt(p.predicted_floor, sci),
            match (&p.plain_floor, &p.compensated_floor) {
                (Some(a), Some(b)) if a.stopped && b.floor > 0.0 => {
                    format!("{:.1}", a.floor / b.floor)
                }
                _ => "-".into(),
            },
        ]);
    }
    t.render()
}

/// One pair's ladder, rung by rung, folded.
pub fn pair_rungs(p: &PairRecord) -> String {
    let mut out = format!(
        "\n<details><summary><code>{}</code> and <code>{}</code>, rung by rung</summary>\n\n",
        p.plain, p.compensated
    );
    let mut t = Table::new(&[
        "h",
        "steps",
        "plain error",
        "compensated error",
        "round-off (plain - compensated)",
    ]);
    for g in &p.rungs {
        t.row(vec![
            sci(g.h),
            g.steps.to_string(),
            opt(g.plain_error, sci),
            opt(g.compensated_error, sci),
            opt(g.round_off, sci),
        ]);
    }
    out.push_str(&t.render());
    out.push_str("\n</details>\n");
    out
}

/// One row per long run.
pub fn longrun_table(records: &[LongrunRecord]) -> String {
    let mut t = Table::new(&[
        "scheme",
        "scene",
        "quantity",
        "runs x steps",
        "largest relative change",
        "rms at the end",
        "per step (eps)",
        "g",
        "class",
    ]);
    for r in records {
        t.row(vec![
            format!("`{}`", r.scheme),
            format!("`{}`", r.scene),
            r.invariant.name().into(),
            format!("{} x {}", r.runs, r.steps),
            sci(r.max_relative_error),
            sci(r.final_rms),
            format!("{:.2}", r.per_step_ulps),
            match (r.growth_exponent, r.growth_standard_error) {
                (Some(g), Some(se)) => format!("{g:.2} -+ {se:.2}"),
                _ => "-".into(),
            },
            r.class.map_or("-", |c| c.name()).into(),
        ]);
    }
    t.render()
}
