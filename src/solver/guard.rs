//! The floating guard: which contact points to hold active when the
//! active set cannot hold the bodies.
//!
//! A rigid mode r that the supports leave free (a body held only by
//! contact) costs nothing in the bulk stiffness; the secant kernel (18)
//! holds it only through its active points, by Σ_active w γ (⟦r_n⟧)². If
//! no active point sees r — a body above the obstacle, or the start of a
//! solve with an open gap — the kernel is singular along r. The guard then
//! makes the points of smallest P active, as few as hold every free mode
//! (plus exact ties, so a flat face is taken whole), and the step uses
//! their tied force law too ([`crate::contact::nitsche::Law::Tied`]):
//! the linearised step pulls exactly those points onto the obstacle, which
//! closes a gap of any size in one rigid motion.

use crate::problem::Problem;
use nalgebra::DMatrix;

/// The floating modes seen by every contact point.
pub(crate) struct Guard {
    /// The floating modes (full DOF vectors).
    pub modes: Vec<Vec<f64>>,
    /// ⟦r_n⟧ at every point for every floating mode r.
    jumps: Vec<Vec<f64>>,
    weights: Vec<f64>,
    gammas: Vec<f64>,
    /// The smallest eigenvalue of Σ w jjᵀ that counts as holding the
    /// modes: a fraction of the largest of the whole boundary.
    threshold: f64,
}

/// The fraction of the whole boundary's hold on the floating modes that
/// the active set must reach.
const HOLD: f64 = 1e-6;
/// Points whose P is within this relative distance of the last point
/// chosen are taken too.
const TIE: f64 = 1e-8;

impl Guard {
    pub fn new(problem: &Problem) -> Self {
        let modes = problem.floating_modes();
        let jumps: Vec<Vec<f64>> = problem
            .points
            .iter()
            .map(|cp| {
                modes
                    .iter()
                    .map(|r| cp.normal_stress_and_jump(r).1)
                    .collect()
            })
            .collect();
        let weights: Vec<f64> = problem.points.iter().map(|cp| cp.weight).collect();
        let gammas: Vec<f64> = problem.points.iter().map(|cp| cp.gamma).collect();
        let mut guard = Self {
            modes,
            jumps,
            weights,
            gammas,
            threshold: 0.0,
        };
        // Supports that hold every body leave nothing to guard: the
        // threshold stays 0 and `select` never forces a point.
        if !guard.modes.is_empty() {
            let all: Vec<usize> = (0..guard.weights.len()).collect();
            guard.threshold = HOLD * guard.hold(&all).1;
        }
        guard
    }

    /// The number of contact points.
    pub fn points(&self) -> usize {
        self.weights.len()
    }

    fn modes(&self) -> usize {
        self.modes.len()
    }

    /// (smallest, largest) eigenvalue of Σ_{q ∈ set} w_q j_q j_qᵀ; with
    /// no floating mode, (∞, 0): nothing to hold, held by any set.
    fn hold(&self, set: &[usize]) -> (f64, f64) {
        let m = self.modes();
        if m == 0 {
            return (f64::INFINITY, 0.0);
        }
        let mut a = DMatrix::<f64>::zeros(m, m);
        for &q in set {
            let j = &self.jumps[q];
            for r in 0..m {
                for c in 0..m {
                    a[(r, c)] += self.weights[q] * j[r] * j[c];
                }
            }
        }
        let e = a.symmetric_eigen().eigenvalues;
        (e.min(), e.max())
    }

    /// The points to force active at the P values `p`: none when the
    /// active points (P ≤ 0) hold every floating mode.
    pub fn select(&self, p: &[f64]) -> Vec<usize> {
        if self.modes() == 0 || self.threshold <= 0.0 {
            return Vec::new();
        }
        let mut set: Vec<usize> = (0..p.len()).filter(|&q| p[q] <= 0.0).collect();
        if self.hold(&set).0 >= self.threshold {
            return Vec::new();
        }
        let mut open: Vec<usize> = (0..p.len()).filter(|&q| p[q] > 0.0).collect();
        open.sort_by(|&a, &b| p[a].total_cmp(&p[b]));
        let mut forced = Vec::new();
        let mut last = None;
        for &q in &open {
            if let Some(pl) = last {
                // held: take exact ties of the last point, then stop
                if p[q] > pl + TIE * f64::abs(pl) {
                    break;
                }
            }
            forced.push(q);
            set.push(q);
            if last.is_none() && self.hold(&set).0 >= self.threshold {
                last = Some(p[q]);
            }
        }
        forced
    }
}

impl Guard {
    /// The rigid shifts t (one per floating mode) that balance the load
    /// along every floating mode, given P at every point and f0 = rᵀR(u)
    /// per mode: F(t) = f0 + Σ_q w v_q (\[P_q − γ v_q·t\]₋ − \[P_q\]₋) = 0,
    /// v_q = ⟦r_n⟧ at q. F = −∇Φ for the convex
    /// Φ(t) = −c·t + Σ_q (w/2γ) \[P_q − γ v_q·t\]₋², minimised by Newton
    /// with backtracking.
    pub fn balance(&self, p: &[f64], f0: &[f64]) -> Vec<f64> {
        let m = self.modes();
        if m == 0 {
            return Vec::new();
        }
        let vt = |q: usize, t: &[f64]| -> f64 { (0..m).map(|k| self.jumps[q][k] * t[k]).sum() };
        let mut c = f0.to_vec();
        for q in 0..p.len() {
            for k in 0..m {
                c[k] -= self.weights[q] * self.jumps[q][k] * p[q].min(0.0);
            }
        }
        let phi = |t: &[f64]| -> f64 {
            let lin: f64 = (0..m).map(|k| c[k] * t[k]).sum();
            -lin + (0..p.len())
                .map(|q| {
                    let x = (p[q] - self.gammas[q] * vt(q, t)).min(0.0);
                    self.weights[q] / (2.0 * self.gammas[q]) * x * x
                })
                .sum::<f64>()
        };
        let force = |t: &[f64]| -> Vec<f64> {
            let mut f = c.clone();
            for q in 0..p.len() {
                let x = (p[q] - self.gammas[q] * vt(q, t)).min(0.0);
                for k in 0..m {
                    f[k] += self.weights[q] * self.jumps[q][k] * x;
                }
            }
            f
        };
        let mut all = DMatrix::<f64>::zeros(m, m);
        for q in 0..p.len() {
            for a in 0..m {
                for b in 0..m {
                    all[(a, b)] +=
                        self.weights[q] * self.gammas[q] * self.jumps[q][a] * self.jumps[q][b];
                }
            }
        }
        let mu = 1e-10 * all.symmetric_eigen().eigenvalues.max();
        let scale: f64 = c
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt()
            .max(f64::MIN_POSITIVE);
        let mut t = vec![0.0; m];
        for _ in 0..100 {
            let f = force(&t);
            let fnorm = f.iter().map(|v| v * v).sum::<f64>().sqrt();
            if fnorm <= 1e-13 * scale {
                break;
            }
            let mut h = DMatrix::<f64>::identity(m, m) * mu;
            for q in 0..p.len() {
                if p[q] - self.gammas[q] * vt(q, &t) < 0.0 {
                    for a in 0..m {
                        for b in 0..m {
                            h[(a, b)] += self.weights[q]
                                * self.gammas[q]
                                * self.jumps[q][a]
                                * self.jumps[q][b];
                        }
                    }
                }
            }
            let Some(d) = h.lu().solve(&nalgebra::DVector::from_vec(f.clone())) else {
                break;
            };
            let phi0 = phi(&t);
            let slope: f64 = -(0..m).map(|k| f[k] * d[k]).sum::<f64>();
            let mut alpha = 1.0;
            let mut moved = false;
            for _ in 0..80 {
                let trial: Vec<f64> = (0..m).map(|k| t[k] + alpha * d[k]).collect();
                if phi(&trial) <= phi0 + 1e-4 * alpha * slope {
                    t = trial;
                    moved = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !moved {
                break;
            }
        }
        t
    }
}
