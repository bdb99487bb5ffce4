//! Curve families for the experiments: cubic spline interpolants (see [`crate::build::interpolate`])
//! of sampled functions and of hand-digitised outlines.
//!
//! Everything here is deterministic (no randomness), so a harness gets the same curves on
//! every run.

use crate::build::interpolate::{interpolate_cubic, InterpolateError, Parametrization};
use crate::spline::curve::NurbsCurve;

/// A sampled test function f on an interval [x0, x1].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TestFunction {
    /// sin x on [0, 2 pi]
    Sin,
    /// Runge's function 1 / (1 + 25 x^2) on [-1, 1]
    Runge,
    /// exp x on [0, 3]
    Exp,
    /// a smoothed step tanh(10 x) on [-1, 1] (flat tails, one steep rise)
    TanhStep,
}

impl TestFunction {
    /// All test functions.
    pub const ALL: [TestFunction; 4] = [
        TestFunction::Sin,
        TestFunction::Runge,
        TestFunction::Exp,
        TestFunction::TanhStep,
    ];

    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            TestFunction::Sin => "sin",
            TestFunction::Runge => "runge",
            TestFunction::Exp => "exp",
            TestFunction::TanhStep => "tanh-step",
        }
    }

    /// The interval the function is sampled on.
    pub fn interval(self) -> (f64, f64) {
        match self {
            TestFunction::Sin => (0.0, 2.0 * std::f64::consts::PI),
            TestFunction::Runge | TestFunction::TanhStep => (-1.0, 1.0),
            TestFunction::Exp => (0.0, 3.0),
        }
    }

    /// f(x) (f64 library functions; the samples are data, their rounding does not matter).
    pub fn eval(self, x: f64) -> f64 {
        match self {
            TestFunction::Sin => x.sin(),
            TestFunction::Runge => 1.0 / (1.0 + 25.0 * x * x),
            TestFunction::Exp => x.exp(),
            TestFunction::TanhStep => (10.0 * x).tanh(),
        }
    }

    /// `n` equally spaced sample abscissae x_0 = x0 < ... < x_{n-1} = x1.
    pub fn abscissae(self, n: usize) -> Vec<f64> {
        let (a, b) = self.interval();
        let last = n.saturating_sub(1).max(1) as f64;
        (0..n).map(|i| a + (b - a) * (i as f64 / last)).collect()
    }

    /// The graph samples (x_i, f(x_i)), 2-D.
    pub fn graph_samples(self, n: usize) -> Vec<Vec<f64>> {
        self.abscissae(n)
            .into_iter()
            .map(|x| vec![x, self.eval(x)])
            .collect()
    }
}

/// The interpolant of the graph (x_i, f(x_i)) of `f` at `n` equally spaced samples, a 2-D
/// curve, with the given parametrisation. Errors for n < 2.
pub fn function_graph(
    f: TestFunction,
    n: usize,
    param: Parametrization,
) -> Result<NurbsCurve, InterpolateError> {
    interpolate_cubic(&f.graph_samples(n), param)
}

/// The 1-D interpolant of the values f(x_i) at `n` equally spaced samples with the uniform
/// parametrisation: the classical natural cubic spline of f, as a function of the sample
/// index (the thesis's 1-D test curves are of this kind). Errors for n < 2.
pub fn function_values(f: TestFunction, n: usize) -> Result<NurbsCurve, InterpolateError> {
    let v: Vec<Vec<f64>> = f
        .abscissae(n)
        .into_iter()
        .map(|x| vec![f.eval(x)])
        .collect();
    interpolate_cubic(&v, Parametrization::Uniform)
}

/// A hand-digitised outline of the letter "S" (open stroke from the lower tail to the upper
/// terminal, in a 10 x 10 em box), 18 points.
pub fn letter_s_points() -> Vec<Vec<f64>> {
    [
        [1.0, 2.2],
        [1.8, 1.2],
        [3.2, 0.5],
        [5.0, 0.3],
        [6.8, 0.6],
        [8.0, 1.5],
        [8.4, 2.8],
        [7.9, 4.0],
        [6.6, 4.8],
        [5.0, 5.3],
        [3.4, 5.8],
        [2.2, 6.6],
        [1.7, 7.8],
        [2.2, 9.0],
        [3.6, 9.7],
        [5.2, 9.9],
        [6.8, 9.6],
        [8.0, 8.8],
    ]
    .iter()
    .map(|p| p.to_vec())
    .collect()
}

/// A hand-digitised profile (radius, height) of a vase: foot, stem, belly, neck, lip; with a
/// sharp turn at the foot. 12 points.
pub fn vase_profile_points() -> Vec<Vec<f64>> {
    [
        [0.0, 0.0],
        [2.0, 0.0],
        [2.2, 0.3],
        [1.6, 0.8],
        [1.0, 1.6],
        [0.9, 3.0],
        [1.3, 4.5],
        [2.4, 6.0],
        [3.0, 7.5],
        [2.8, 8.8],
        [2.2, 9.5],
        [2.5, 10.0],
    ]
    .iter()
    .map(|p| p.to_vec())
    .collect()
}

/// `n` samples of the helix (cos s, sin s, s / 4), s in [0, 4 pi]: a 3-D point set.
pub fn helix_points(n: usize) -> Vec<Vec<f64>> {
    let last = n.saturating_sub(1).max(1) as f64;
    (0..n)
        .map(|i| {
            let s = 4.0 * std::f64::consts::PI * i as f64 / last;
            vec![s.cos(), s.sin(), s / 4.0]
        })
        .collect()
}

/// One member of a family: a name and the curve.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyCurve {
    /// e.g. `runge/graph/centripetal/n=9`
    pub name: String,
    /// the interpolant
    pub curve: NurbsCurve,
}

/// All families at `n` samples per sampled function: for each [`TestFunction`] its graph
/// interpolant under every parametrisation and its 1-D value interpolant; the letter "S" and
/// the vase profile under every parametrisation; the helix (3-D) under every parametrisation
/// but Foley's (plane curves only). Errors for n < 2.
pub fn all_families(n: usize) -> Result<Vec<FamilyCurve>, InterpolateError> {
    let mut out = Vec::new();
    let mut push = |name: String, c: Result<NurbsCurve, InterpolateError>| -> Result<(), _> {
        out.push(FamilyCurve { name, curve: c? });
        Ok::<(), InterpolateError>(())
    };
    for f in TestFunction::ALL {
        for p in Parametrization::ALL {
            push(
                format!("{}/graph/{}/n={n}", f.name(), p.name()),
                function_graph(f, n, p),
            )?;
        }
        push(
            format!("{}/values/uniform/n={n}", f.name()),
            function_values(f, n),
        )?;
    }
    for (name, pts) in [
        ("letter-s", letter_s_points()),
        ("vase", vase_profile_points()),
    ] {
        for p in Parametrization::ALL {
            push(format!("{name}/{}", p.name()), interpolate_cubic(&pts, p))?;
        }
    }
    for p in Parametrization::ALL {
        if p != Parametrization::Foley {
            push(
                format!("helix/{}/n={n}", p.name()),
                interpolate_cubic(&helix_points(n), p),
            )?;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::interpolate::{
        interpolate_cubic_with, interpolation_residual, InterpolationOptions,
    };

    #[test]
    fn families_are_built_and_interpolate() {
        let fam = all_families(9).unwrap();
        assert_eq!(fam.len(), 4 * 5 + 2 * 4 + 3);
        assert!(fam.iter().any(|f| f.name == "runge/graph/foley/n=9"));
        assert_eq!(
            function_graph(TestFunction::Sin, 1, Parametrization::Uniform)
                .unwrap_err()
                .kind(),
            "too_few_points"
        );
        let pts = letter_s_points();
        let it = interpolate_cubic_with(
            &pts,
            &InterpolationOptions {
                param: Parametrization::Foley,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(interpolation_residual(&it.curve, &it.params, &pts).unwrap() < 1e-13);
        // the 1-D value interpolant of sin at 9 points: C(i) = sin(x_i)
        let c = function_values(TestFunction::Sin, 9).unwrap();
        let v: Vec<f64> = c.point(2.0).unwrap();
        assert!((v[0] - (std::f64::consts::PI / 2.0).sin()).abs() < 1e-14);
    }
}
