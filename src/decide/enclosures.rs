//! The enclosures of a sampled statement's comparisons at one state: each side walked
//! once in interval arithmetic ([`crate::eval::interval`]), so that a difference found
//! in floating point can be told from rounding before it becomes a counterexample.

use super::sampler::Sampler;
use crate::eval::interval::{Enclosure, Interval, IntervalEnv, R};
use crate::eval::labeled::Labeled;
use crate::eval::state::State;
use rustc_hash::FxHashMap as HashMap;

/// The enclosures of a sampled statement's comparisons at one state, each side walked
/// once.
pub(crate) struct Enclosures<'s, 'a> {
    sampler: &'s Sampler<'a>,
    state: &'s State,
    env: Option<R<IntervalEnv<'a>>>,
    sides: HashMap<(usize, usize), R<Labeled<Interval>>>,
}

impl<'s, 'a> Enclosures<'s, 'a> {
    pub(crate) fn new(sampler: &'s Sampler<'a>, state: &'s State) -> Self {
        Enclosures {
            sampler,
            state,
            env: None,
            sides: HashMap::default(),
        }
    }

    /// The enclosures of sides `k` and `k + 1` of chain `chain` (both 0-based) at the
    /// index values `at` (0-based, by letter), and whether they are loose
    /// ([`IntervalEnv::loose`]).
    pub(crate) fn pair(
        &mut self,
        chain: usize,
        k: usize,
        at: &[(char, usize)],
    ) -> R<(Interval, Interval, bool)> {
        let (sampler, state) = (self.sampler, self.state);
        let env = self.env.get_or_insert_with(|| {
            IntervalEnv::at_state(
                sampler.decls,
                &sampler.check.defs,
                &sampler.parametrisation,
                &sampler.check.assumptions,
                state,
            )
        });
        let env = match env {
            Ok(env) => env,
            Err(e) => return Err(e.clone()),
        };
        let mut side = |j: usize| -> R<Interval> {
            let value = self.sides.entry((chain, j)).or_insert_with(|| {
                let s = &sampler.check.chains[chain][j];
                match &s.node {
                    Ok(node) => env.eval(node),
                    Err(e) => Err(Enclosure(e.message.clone())),
                }
            });
            Ok(*value.as_ref().map_err(Clone::clone)?.at(at))
        };
        let (l, r) = (side(k)?, side(k + 1)?);
        Ok((l, r, env.loose()))
    }
}
