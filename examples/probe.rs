use std::time::Instant;
use stepladder::measure::order::{OrderRecord, OrderSpec, global_order};
use stepladder::scene::{AnyScene, Hidden, Scene, SceneVisitor};
use stepladder::scheme::{Scheme, SchemeVisitor, scheme_ids, visit_scheme};
struct Twins<'a>(&'a AnyScene);
impl SchemeVisitor for Twins<'_> {
    type Output = (OrderRecord, OrderRecord, f64, f64);
    fn visit<M: Scheme + Sync + 'static>(self, m: &'static M) -> Self::Output {
        struct On<M: 'static>(&'static M);
        impl<M: Scheme> SceneVisitor for On<M> {
            type Output = (OrderRecord, OrderRecord, f64, f64);
            fn visit<S: Scene<D> + Clone + Send + Sync + 'static, const D: usize>(
                self,
                s: &S,
            ) -> Self::Output {
                let t = Instant::now();
                let a = global_order(self.0, s, &OrderSpec::default()).unwrap();
                let ta = t.elapsed().as_secs_f64();
                let t = Instant::now();
                let b = global_order(self.0, &Hidden(s.clone()), &OrderSpec::default()).unwrap();
                (a, b, ta, t.elapsed().as_secs_f64())
            }
        }
        self.0.visit(On(m))
    }
}
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scenes: Vec<AnyScene> = if args.len() > 1 {
        args[1..]
            .iter()
            .map(|a| AnyScene::parse(a).unwrap())
            .collect()
    } else {
        AnyScene::all()
    };
    for sc in &scenes {
        for id in scheme_ids() {
            if std::env::var("ONLY").map_or(false, |o| o != id) {
                continue;
            }
            let (a, b, ta, tb) = visit_scheme(id, Twins(sc)).unwrap();
            if std::env::var("DUMP").is_ok() {
                dump(&a);
                dump(&b);
            }
            let inside = match (a.ci95, b.measured_order) {
                (Some([lo, hi]), Some(p)) => lo <= p && p <= hi,
                _ => false,
            };
            println!(
                "{:18} {:28} exact {:>12} {:>7} [{:.3},{:.3}] {:5.2}s | hidden {:>12} {:>7} {:5.2}s {} {}",
                id,
                format!(
                    "{}:{}",
                    a.scene,
                    a.scene_parameters.chars().take(14).collect::<String>()
                ),
                a.verdict.name(),
                a.measured_order.map_or("-".into(), |p| format!("{p:.3}")),
                a.ci95.map_or(f64::NAN, |c| c[0]),
                a.ci95.map_or(f64::NAN, |c| c[1]),
                ta,
                b.verdict.name(),
                b.measured_order.map_or("-".into(), |p| format!("{p:.3}")),
                tb,
                if a.verdict == b.verdict && (inside || a.measured_order.is_none()) {
                    ""
                } else {
                    "<<< MISMATCH"
                },
                if a.verdict != stepladder::measure::Verdict::Pass {
                    a.reason.chars().take(160).collect::<String>()
                } else {
                    String::new()
                }
            );
        }
    }
}
pub fn dump(r: &OrderRecord) {
    println!("fit {:?}\ntrend {:?}", r.fit, r.trend_systematic);
    println!(
        "== {} on {} {}: {} | {:?} {:?} m={:?} end={:?} shortened={:?}",
        r.scheme,
        r.scene,
        r.reference_name(),
        r.reason,
        r.round_off.map(|m| (m.exponent, m.log_scatter)),
        r.window,
        r.per_octave,
        r.ladder_end,
        r.shortened_from
    );
    for (i, g) in r.rungs.iter().enumerate() {
        println!(
            "{i:3} {:8} {:.3e} e={:<22} ro={:<10} bd={:<10} l={:<7} {:?}{}",
            g.steps,
            g.h,
            g.error.map_or("-".into(), |e| format!("{e:e}")),
            g.round_off_sample
                .map_or("-".into(), |e| format!("{e:.2e}")),
            g.round_off_bound.map_or("-".into(), |e| format!("{e:.2e}")),
            g.local_order.map_or("-".into(), |e| format!("{e:.3}")),
            g.dropped,
            if g.used { " *" } else { "" }
        );
    }
}
trait Name {
    fn reference_name(&self) -> &'static str;
}
impl Name for OrderRecord {
    fn reference_name(&self) -> &'static str {
        match self.reference {
            stepladder::measure::order::Reference::Exact => "exact",
            _ => "half-step",
        }
    }
}
